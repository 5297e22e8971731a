// SPDX-License-Identifier: MIT
// The draw-list evaluation shared by DrawListJob (C++) and pm_draw_lists /
// pm_character_draw_lists (C): weights per character (or the given ones),
// positions for all (one batch for rigid characters), then each
// character's list handed to `emit` (the C++ job stores a DrawList, the C
// API converts it to its own struct); the attachments' lists alike; and
// the back-to-front merge of a character's lists.
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "posemorph/draw_list.h"

namespace posemorph::detail {

// The doubles of a DrawListJob's workspace before the attachments' part
// (DrawListWorkspaceSize less what the attachments need).
std::size_t DrawListBodyWorkspace(const Rig& rig, std::size_t count);

// Where a character's attachments are drawn: as its body's list.
struct ListPlacement {
  Transform2D transform;
  bool mirrored = false;
  Colour colour;
};

// One character's draw steps (CharacterDrawSteps): `lists` lists whose
// parts_of(i) are back to front already (each list's draw sequence in its
// dominant pose), merged by order_of(i, part), taking at each step the list
// whose next part has the lowest order (ties: the lower list); emit(k, list,
// part) for each step. Returns the number of steps.
template <typename PartsOf, typename OrderOf, typename Emit>
std::uint32_t MergeDrawSteps(std::uint32_t lists, PartsOf&& parts_of, OrderOf&& order_of, Emit&& emit) {
  std::uint32_t cursor[1 + format::kMaxAttachments] = {};
  if (lists > 1 + format::kMaxAttachments) return 0;
  std::uint32_t total = 0;
  for (std::uint32_t i = 0; i < lists; ++i) total += std::uint32_t(parts_of(i).size);
  for (std::uint32_t k = 0; k < total; ++k) {
    std::uint32_t best = lists;
    std::int32_t best_order = 0;
    for (std::uint32_t i = 0; i < lists; ++i) {
      const Span<const std::uint32_t> parts = parts_of(i);
      if (cursor[i] >= parts.size) continue;
      const std::int32_t order = order_of(i, parts[cursor[i]]);
      if (best == lists || order < best_order) best = i, best_order = order;
    }
    emit(k, best, parts_of(best)[cursor[best]]);
    ++cursor[best];
  }
  return total;
}

// DrawListJob::Validate() without its output lists: what pm_draw_lists
// checks, which emits into its own structs (job.output stays empty). With
// attached_lists_elsewhere the attachments' lists are the caller's too
// (pm_character_draw_lists): job.attached_output stays empty, and the rest
// of the attached layout is checked as if it were given.
bool ValidDrawListInputs(const DrawListJob& job, bool attached_lists_elsewhere = false);

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

// The attachments of a job's characters (their bodies' positions in
// `body`, doubles, which RunDrawLists kept; the workspace after them up to
// extra_end): each later channel's weights at the character's point (or
// the given ones), one AttachJob for all, then each attachment's list
// handed to emit(k, a, list), placed as placement_of(k) says (character
// k's body list: its transform, mirroring and colour).
template <typename PlacementOf, typename Emit>
bool RunAttachedLists(const DrawListJob& job, double* body, double* extra_end, PlacementOf&& placement_of,
                      Emit&& emit) {
  const Rig& rig = *job.rig;
  const std::size_t count = job.count, NW = rig.attached_weight_count(), v2 = 2 * std::size_t(rig.vertex_count());
  const std::size_t a2 = 2 * std::size_t(rig.attached_vertex_count()), A = rig.attachment_count();
  const std::uint32_t C = rig.channel_count();
  double* raw = body + count * v2;
  double* limited = raw + count * NW;
  double* texture = limited + count * NW;
  double* attached = texture + count * NW;
  double* work = attached + count * a2;
  const bool given = job.attached_weights.size != 0;  // an animator's, in the same layout
  const double* raw_in = given ? job.attached_weights.data : raw;
  const double* limited_in = given ? job.attached_limited_weights.data : limited;
  const double* texture_in = given ? job.attached_texture_weights.data : texture;
  for (std::uint32_t c = 1; c < C && !given; ++c) {
    const Rig& channel = *rig.channel_rig(c);
    const std::size_t n = channel.pose_count(), at = count * rig.channel_weight_offset(c);
    const double sigma = job.sigma >= 0 ? job.sigma : channel.default_sigma();
    for (std::size_t k = 0; k < count; ++k) {
      WeightsJob wj;
      wj.rig = &channel;
      const std::size_t p = k * 2 * std::size_t(C - 1) + 2 * std::size_t(c - 1);
      wj.x = job.channel_points.size ? job.channel_points[p] : channel.pose_points()[0];
      wj.y = job.channel_points.size ? job.channel_points[p + 1] : channel.pose_points()[1];
      wj.sigma = sigma;
      wj.limit_weights = job.limit_weights;
      wj.raw = {raw + at + k * n, n};
      wj.limited = {limited + at + k * n, n};
      wj.texture = {texture + at + k * n, n};
      if (!wj.Run()) return false;
    }
  }
  AttachJob aj;
  aj.rig = &rig;
  aj.count = count;
  aj.body_positions = {body, count * v2};
  aj.weights = {raw_in, count * NW};
  aj.limited_weights = {limited_in, count * NW};
  aj.interpolation = job.interpolation;
  aj.workspace = {work, std::size_t(extra_end - work)};
  aj.positions = {attached, count * a2};
  aj.positions_f32 = {job.attached_positions.data, count * a2};
  if (!aj.Run()) return false;
  std::size_t offset = 0;  // floats of the attachments before this one, per character
  for (std::uint32_t a = 0; a < A; ++a) {
    const AttachmentView view = rig.attachment(a);
    const Rig& part = *view.rig;
    const std::size_t p2 = 2 * std::size_t(part.vertex_count()), n = part.pose_count();
    const std::size_t at = count * rig.channel_weight_offset(view.channel);
    for (std::size_t k = 0; k < count; ++k) {
      DrawList list;
      list.positions = {job.attached_positions.data + offset * count + k * p2, p2};
      list.indices = part.triangles();
      list.drawing_count =
          PickDrawings({texture_in + at + k * n, n}, job.max_drawings, {list.drawings, kMaxBlendDrawings});
      list.parts = part.draw_sequence(list.drawing_count ? list.drawings[0].pose : 0);
      for (std::uint32_t d = 0; d < list.drawing_count; ++d) {
        const Span<const float> uv = part.uvs(list.drawings[d].pose);
        list.drawings[d].uvs = uv.size ? uv.data : nullptr;
      }
      const ListPlacement place = placement_of(k);
      list.transform = place.transform;
      list.mirrored = place.mirrored;
      list.colour = place.colour;
      emit(k, a, list);
    }
    offset += p2;
  }
  return true;
}

}  // namespace posemorph::detail
