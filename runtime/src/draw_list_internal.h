// SPDX-License-Identifier: MIT
// The draw-list evaluation shared by DrawListJob (C++) and pm_draw_lists
// (C): weights per character (or the given ones), positions for all (one batch for rigid
// characters), then each character's list handed to `emit` (the C++ job
// stores a DrawList, the C API converts it to its own struct).
#pragma once
#include <cmath>

#include "posemorph/draw_list.h"

namespace posemorph::detail {

// DrawListJob::Validate() without its output lists: what pm_draw_lists
// checks, which emits into its own structs (job.output stays empty).
bool ValidDrawListInputs(const DrawListJob& job);

// Expects ValidDrawListInputs(job). Returns false only when a morph job refuses its
// input, which Validate() and WeightsJob's bounds rule out.
// transform_at(k) gives character k's transform (the job's own span is not
// read: the C API passes its pm_transform array this way). With
// body_doubles (count x 2V), the positions are kept there in doubles too
// (for the attachments).
template <typename TransformAt, typename Emit>
bool RunDrawLists(const DrawListJob& job, TransformAt&& transform_at, Emit&& emit, double* body_doubles = nullptr) {
  const Rig& rig = *job.rig;
  const std::size_t n = rig.pose_count(), v2 = 2 * std::size_t(rig.vertex_count()), count = job.count;
  double* raw = job.workspace.data;
  double* limited = raw + count * n;
  double* texture = limited + count * n;
  double* rest = texture + n;
  // The body's part of the workspace (the attachments' follows it, from body_doubles on).
  const std::size_t rest_size =
      body_doubles ? std::size_t(body_doubles - rest) : job.workspace.size - (2 * count * n + n);
  const double sigma = job.sigma >= 0 ? job.sigma : rig.default_sigma();  // NaN: the default too

  // Given weights (an animator's) are read where they are.
  const bool given = job.weights.size != 0;
  const double* raw_in = given ? job.weights.data : raw;
  const double* limited_in = given ? job.limited_weights.data : limited;
  for (std::size_t k = 0; k < count; ++k) {
    if (!given) {
      WeightsJob wj;
      wj.rig = &rig;
      wj.x = job.points[2 * k], wj.y = job.points[2 * k + 1];
      wj.sigma = sigma;
      wj.limit_weights = job.limit_weights;
      wj.raw = {raw + k * n, n};
      wj.limited = {limited + k * n, n};
      wj.texture = {texture, n};
      if (!wj.Run()) return false;
    }
    const Span<const double> texture_k = given ? job.texture_weights.subspan(k * n, n) : Span<const double>{texture, n};
    DrawList list;
    list.positions = job.positions.subspan(k * v2, v2);
    list.indices = rig.triangles();
    list.drawing_count = PickDrawings(texture_k, job.max_drawings, {list.drawings, kMaxBlendDrawings});
    // The dominant drawing's pose decides the draw order (when it changes with the pose).
    list.parts = rig.draw_sequence(list.drawing_count ? list.drawings[0].pose : 0);
    for (std::uint32_t d = 0; d < list.drawing_count; ++d) {
      const Span<const float> uv = rig.uvs(list.drawings[d].pose);
      list.drawings[d].uvs = uv.size ? uv.data : nullptr;
    }
    list.transform = transform_at(k);
    list.mirrored = list.transform.mirrors();
    if (job.colours.size) list.colour = ClampColour(job.colours[k]);
    if (job.part_opacities.size) {
      const std::uint32_t parts = rig.part_count();
      for (std::uint32_t p = 0; p < parts && p < format::kMaxParts; ++p)
        list.part_opacity[p] = ClampColour({1, 1, 1, job.part_opacities[k * parts + p]}).a;
    }
    emit(k, list);
  }

  if (job.interpolation == Interpolation::kRigid && count > 1) {
    MorphBatchJob bj;
    bj.rig = &rig;
    bj.count = count;
    bj.weights = {raw_in, count * n};
    bj.limited_weights = {limited_in, count * n};
    bj.workspace = {rest, rest_size};
    bj.positions_f32 = {job.positions.data, count * v2};
    if (body_doubles) bj.positions = {body_doubles, count * v2};
    return bj.Run();
  }
  for (std::size_t k = 0; k < count; ++k) {
    MorphJob mj;
    mj.rig = &rig;
    mj.weights = {raw_in + k * n, n};
    mj.limited_weights = {limited_in + k * n, n};
    mj.interpolation = job.interpolation;
    mj.workspace = {rest, rig.morph_workspace_size()};
    mj.positions =
        body_doubles ? Span<double>{body_doubles + k * v2, v2} : Span<double>{rest + rig.morph_workspace_size(), v2};
    mj.positions_f32 = job.positions.subspan(k * v2, v2);
    if (!mj.Run()) return false;
  }
  return true;
}

}  // namespace posemorph::detail
