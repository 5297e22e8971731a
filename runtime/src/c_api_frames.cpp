// SPDX-License-Identifier: MIT
// The C API's per-frame calls: pose points, weights, morphs (one character
// and batches), draw lists, paths and quantised points.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <new>

#include "c_api_draw.h"
#include "c_api_internal.h"
#include "draw_list_internal.h"
#include "posemorph/draw_list.h"
#include "posemorph/jobs.h"
#include "posemorph/path.h"
#include "posemorph/posemorph.h"
#include "posemorph/quantize.h"

using namespace posemorph::c_api;  // NOLINT(google-build-using-namespace): the C API's own helpers
using posemorph::Span;

extern "C" {
int pm_rig_pose_point(const pm_rig* rig, uint32_t pose, double* x, double* y) {
  if (!rig || !x || !y || pose >= rig->rig.pose_count()) return PM_ERROR_INVALID_ARGUMENT;
  *x = rig->rig.pose_points()[2 * pose];
  *y = rig->rig.pose_points()[2 * pose + 1];
  return PM_OK;
}

int pm_weights(const pm_rig* rig, double x, double y, double sigma, int limit_weights, double* raw, double* limited,
               double* texture, size_t capacity) {
  return pm_channel_weights(rig, 0, x, y, sigma, limit_weights, raw, limited, texture, capacity);
}

size_t pm_morph_workspace_size(const pm_rig* rig) { return rig ? rig->rig.morph_workspace_size() : 0; }

int pm_morph(const pm_rig* rig, const double* weights, const double* limited_weights, int linear, double* workspace,
             size_t workspace_capacity, double* positions, float* positions_f32, size_t positions_capacity) {
  if (!rig || !Aligned(workspace) || !Aligned(positions) || !Aligned(positions_f32)) return PM_ERROR_INVALID_ARGUMENT;
  const posemorph::Rig& r = rig->rig;
  const std::size_t n = r.pose_count(), v2 = 2 * std::size_t(r.vertex_count());
  if ((workspace && workspace_capacity < r.morph_workspace_size()) || positions_capacity < v2)
    return PM_ERROR_BUFFER_TOO_SMALL;
  posemorph::MorphJob job;
  job.rig = &r;
  job.weights = {weights, n};
  job.limited_weights = {limited_weights, n};
  job.interpolation = linear ? posemorph::Interpolation::kLinear : posemorph::Interpolation::kRigid;
  job.workspace = {workspace, r.morph_workspace_size()};
  job.positions = {positions, v2};
  job.positions_f32 = {positions_f32, positions_f32 ? v2 : 0};
  if (!job.Validate()) return PM_ERROR_INVALID_ARGUMENT;
  return job.Run() ? PM_OK : PM_ERROR_BAD_VALUE;  // a solve beyond kMaxPosition: zeros written
}

size_t pm_batch_workspace_size(const pm_rig* rig) { return rig ? rig->rig.batch_workspace_size() : 0; }

int pm_morph_batch(const pm_rig* rig, size_t count, const double* weights, const double* limited_weights,
                   double* workspace, size_t workspace_capacity, double* positions, float* positions_f32,
                   size_t positions_capacity) {
  if (!rig || !Aligned(workspace) || !Aligned(positions) || !Aligned(positions_f32)) return PM_ERROR_INVALID_ARGUMENT;
  const posemorph::Rig& r = rig->rig;
  const std::size_t n = r.pose_count(), v2 = 2 * std::size_t(r.vertex_count());
  if (count > (std::size_t(-1) / 2) / (v2 + n)) return PM_ERROR_INVALID_ARGUMENT;
  if (count && ((workspace && workspace_capacity < r.batch_workspace_size()) ||
                ((positions || positions_f32) && positions_capacity < count * v2)))
    return PM_ERROR_BUFFER_TOO_SMALL;
  posemorph::MorphBatchJob job;
  job.rig = &r;
  job.count = count;
  job.weights = {weights, weights ? count * n : 0};
  job.limited_weights = {limited_weights, limited_weights ? count * n : 0};
  job.workspace = {workspace, workspace ? r.batch_workspace_size() : 0};
  job.positions = {positions, positions ? count * v2 : 0};
  job.positions_f32 = {positions_f32, positions_f32 ? count * v2 : 0};
  if (!job.Validate()) return PM_ERROR_INVALID_ARGUMENT;
  return job.Run() ? PM_OK : PM_ERROR_BAD_VALUE;  // a solve beyond kMaxPosition: zeros written
}

void pm_transform_make(double x, double y, double radians, double scale_x, double scale_y, int flip_x,
                       pm_transform* out) {
  if (!out) return;
  const posemorph::Transform2D t = posemorph::Transform2D::Make(x, y, radians, scale_x, scale_y, flip_x != 0);
  *out = {t.a, t.b, t.c, t.d, t.tx, t.ty};
}

static_assert(sizeof(pm_colour) == 4 * sizeof(float) && sizeof(posemorph::Colour) == 4 * sizeof(float) &&
                  offsetof(pm_colour, a) == offsetof(posemorph::Colour, a),
              "pm_colour is posemorph::Colour: four floats r, g, b, a");
static_assert(PM_MAX_PARTS == posemorph::format::kMaxParts, "PM_MAX_PARTS is the format's");

void pm_draw_options_default(pm_draw_options* out) {
  if (!out) return;
  *out = pm_draw_options{};
  out->sigma = -1.0;
  out->limit_weights = 1;
  out->linear = 0;
  out->max_drawings = posemorph::kMaxBlendDrawings;
}

int pm_draw_list_buffers(const pm_rig* rig, size_t count, size_t* workspace_doubles, size_t* position_floats) {
  if (!rig || count == 0 || count > posemorph::MaxDrawListCount(rig->rig)) return PM_ERROR_INVALID_ARGUMENT;
  const posemorph::CharacterBuffers b = posemorph::CharacterBuffers::For(rig->rig, count);
  if (workspace_doubles) *workspace_doubles = b.workspace;
  if (position_floats) *position_floats = b.positions;
  return PM_OK;
}

int pm_draw_lists(const pm_rig* rig, const pm_draw_options* options, size_t count, const double* points,
                  const pm_transform* transforms, double* workspace, size_t workspace_capacity, float* positions,
                  size_t positions_capacity, pm_draw_list* out, size_t out_capacity) {
  if (!rig || !points || !workspace || !positions || !out || count == 0 || !Aligned(points) || !Aligned(workspace) ||
      !Aligned(positions) || !Aligned(out) || !Aligned(transforms))
    return PM_ERROR_INVALID_ARGUMENT;
  pm_draw_options o;
  pm_draw_options_default(&o);
  if (options) o = *options;
  if (!Aligned(o.colours) || !Aligned(o.part_opacities)) return PM_ERROR_INVALID_ARGUMENT;
  const posemorph::Rig& r = rig->rig;
  std::size_t need_workspace = 0, need_positions = 0;
  if (pm_draw_list_buffers(rig, count, &need_workspace, &need_positions) != PM_OK) return PM_ERROR_INVALID_ARGUMENT;
  if (workspace_capacity < need_workspace || positions_capacity < need_positions || out_capacity < count)
    return PM_ERROR_BUFFER_TOO_SMALL;
  posemorph::DrawListJob job;
  job.rig = &r;
  job.count = count;
  job.points = {points, 2 * count};
  SetDrawOptions(o, count, r, &job);
  job.workspace = {workspace, need_workspace};
  job.positions = {positions, need_positions};
  if (!posemorph::detail::ValidDrawListInputs(job)) return PM_ERROR_INVALID_ARGUMENT;
  const auto transform_at = [transforms](std::size_t k) {
    return transforms ? TransformFromC(transforms[k]) : posemorph::Transform2D();
  };
  const bool ok = posemorph::detail::RunDrawLists(
      job, transform_at,
      [&](std::size_t k, const posemorph::DrawList& list) { DrawListToC(list, r.vertex_count(), &out[k]); });
  return ok ? PM_OK : PM_ERROR_INVALID_ARGUMENT;
}

uint32_t pm_pick_drawings(const double* texture_weights, uint32_t pose_count, uint32_t max_drawings,
                          pm_blended_drawing* out, uint32_t capacity) {
  if (!texture_weights || !out || !Aligned(texture_weights) || !Aligned(out)) return 0;
  posemorph::BlendedDrawing picked[posemorph::kMaxBlendDrawings];
  const std::uint32_t room = capacity < posemorph::kMaxBlendDrawings ? capacity : posemorph::kMaxBlendDrawings;
  const std::uint32_t n = posemorph::PickDrawings({texture_weights, pose_count}, max_drawings, {picked, room});
  for (std::uint32_t k = 0; k < n; ++k) out[k] = {picked[k].pose, picked[k].weight, nullptr};
  return n;
}

int pm_path_find(const pm_rig* rig, const char* name) { return rig ? rig->rig.FindPath(name) : -1; }

int pm_path_sample(const pm_rig* rig, uint32_t path, double time, double* x, double* y) {
  if (!rig) return PM_ERROR_INVALID_ARGUMENT;
  return posemorph::SamplePath(rig->rig, path, time, x, y) ? PM_OK : PM_ERROR_INVALID_ARGUMENT;
}

uint32_t pm_quantize_point(const pm_rig* rig, double x, double y) { return pm_channel_quantize_point(rig, 0, x, y); }

void pm_dequantize_point(const pm_rig* rig, uint32_t packed, double* x, double* y) {
  pm_channel_dequantize_point(rig, 0, packed, x, y);
}
}  // extern "C"
