// SPDX-License-Identifier: MIT
// The C API for control channels and attachments (format 1.7).
#include <cstdint>
#include <cstring>
#include <new>

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
// Control channels (format 1.7).
namespace {
const posemorph::Rig* ChannelRig(const pm_rig* rig, uint32_t channel) {
  return rig ? rig->rig.channel_rig(channel) : nullptr;
}
const posemorph::Rig* AttachmentRig(const pm_rig* rig, uint32_t attachment) {
  return rig && attachment < rig->rig.attachment_count() ? rig->rig.attachment(attachment).rig : nullptr;
}
}  // namespace

uint32_t pm_rig_channel_count(const pm_rig* rig) { return rig ? rig->rig.channel_count() : 0; }

uint32_t pm_channel_quantize_point(const pm_rig* rig, uint32_t channel, double x, double y) {
  const posemorph::Rig* c = ChannelRig(rig, channel);
  if (!c) return 0;
  const posemorph::QuantizedPoint q = posemorph::QuantizePoint(c->grid(), x, y);
  return uint32_t(q.x) | uint32_t(q.y) << 16;
}

void pm_channel_dequantize_point(const pm_rig* rig, uint32_t channel, uint32_t packed, double* x, double* y) {
  const posemorph::Rig* c = ChannelRig(rig, channel);
  if (!c || !x || !y) return;
  posemorph::DequantizePoint(c->grid(), {uint16_t(packed & 0xFFFFu), uint16_t(packed >> 16)}, x, y);
}

int pm_rig_channel_name(const pm_rig* rig, uint32_t channel, char* out, size_t capacity, size_t* length) {
  return CopyString(rig ? rig->rig.channel_name(channel) : posemorph::StringView{},
                    rig && channel < rig->rig.channel_count(), out, capacity, length);
}

int pm_rig_find_channel(const pm_rig* rig, const char* name) { return rig ? rig->rig.FindChannel(name) : -1; }

int pm_rig_channel_poses(const pm_rig* rig, uint32_t channel, uint32_t* pose_count, double* points, size_t capacity) {
  const posemorph::Rig* c = ChannelRig(rig, channel);
  if (!c || !pose_count) return PM_ERROR_INVALID_ARGUMENT;
  *pose_count = c->pose_count();
  if (!points) return PM_OK;
  if (capacity < 2 * std::size_t(c->pose_count())) return PM_ERROR_BUFFER_TOO_SMALL;
  for (std::size_t k = 0; k < 2 * std::size_t(c->pose_count()); ++k) points[k] = c->pose_points()[k];
  return PM_OK;
}

int pm_rig_channel_grid(const pm_rig* rig, uint32_t channel, pm_grid_info* out) {
  const posemorph::Rig* c = ChannelRig(rig, channel);
  if (!c || !out) return PM_ERROR_INVALID_ARGUMENT;
  const posemorph::PoseSpaceGrid& g = c->grid();
  *out = pm_grid_info{g.origin_x, g.origin_y, g.origin_x + g.cell * g.cells_x, g.origin_y + g.cell * g.cells_y, g.cell,
                      g.cells_x,  g.cells_y};
  return PM_OK;
}

int pm_channel_weights(const pm_rig* rig, uint32_t channel, double x, double y, double sigma, int limit_weights,
                       double* raw, double* limited, double* texture, size_t capacity) {
  const posemorph::Rig* c = ChannelRig(rig, channel);
  if (!c || !raw || !Aligned(raw) || !Aligned(limited) || !Aligned(texture)) return PM_ERROR_INVALID_ARGUMENT;
  const std::size_t n = c->pose_count();
  if (capacity < n) return PM_ERROR_BUFFER_TOO_SMALL;
  posemorph::WeightsJob job;
  job.rig = c;
  job.x = x;
  job.y = y;
  job.sigma = sigma;
  job.limit_weights = limit_weights != 0;
  job.raw = {raw, n};
  job.limited = {limited, limited ? n : 0};
  job.texture = {texture, texture ? n : 0};
  return job.Run() ? PM_OK : PM_ERROR_INVALID_ARGUMENT;
}

int pm_channel_path_find(const pm_rig* rig, uint32_t channel, const char* name) {
  const posemorph::Rig* c = ChannelRig(rig, channel);
  return c ? c->FindPath(name) : -1;
}

int pm_channel_path_sample(const pm_rig* rig, uint32_t channel, uint32_t path, double time, double* x, double* y) {
  const posemorph::Rig* c = ChannelRig(rig, channel);
  if (!c) return PM_ERROR_INVALID_ARGUMENT;
  return posemorph::SamplePath(*c, path, time, x, y) ? PM_OK : PM_ERROR_INVALID_ARGUMENT;
}

uint32_t pm_rig_attachment_count(const pm_rig* rig) { return rig ? rig->rig.attachment_count() : 0; }

int pm_rig_attachment(const pm_rig* rig, uint32_t attachment, pm_attachment* out) {
  const posemorph::Rig* a = AttachmentRig(rig, attachment);
  if (!a || !out) return PM_ERROR_INVALID_ARGUMENT;
  const posemorph::AttachmentView v = rig->rig.attachment(attachment);
  pm_attachment r{};
  r.channel = v.channel;
  r.vertex_count = a->vertex_count(), r.triangle_count = a->triangle_count(), r.pose_count = a->pose_count();
  r.draw_order = a->part(0).draw_order;
  r.parent_triangle = v.parent_triangle, r.joint_triangle = v.joint_triangle;
  for (int k = 0; k < 3; ++k) r.parent_weights[k] = v.parent_weights[k], r.joint_weights[k] = v.joint_weights[k];
  *out = r;
  return PM_OK;
}

int pm_rig_attachment_name(const pm_rig* rig, uint32_t attachment, char* out, size_t capacity, size_t* length) {
  const posemorph::Rig* a = AttachmentRig(rig, attachment);
  return CopyString(a ? a->part(0).name : posemorph::StringView{}, a != nullptr, out, capacity, length);
}

int pm_rig_attachment_draw_order(const pm_rig* rig, uint32_t attachment, uint32_t pose, int32_t* out) {
  const posemorph::Rig* a = AttachmentRig(rig, attachment);
  if (!a || !out || pose >= a->pose_count()) return PM_ERROR_INVALID_ARGUMENT;
  *out = a->part_draw_order(0, pose);
  return PM_OK;
}

const uint32_t* pm_rig_attachment_triangles(const pm_rig* rig, uint32_t attachment) {
  const posemorph::Rig* a = AttachmentRig(rig, attachment);
  return a ? a->triangles().data : nullptr;
}

const float* pm_rig_attachment_uvs(const pm_rig* rig, uint32_t attachment, uint32_t pose) {
  const posemorph::Rig* a = AttachmentRig(rig, attachment);
  return a && pose < a->pose_count() && a->uvs(pose).size ? a->uvs(pose).data : nullptr;
}

int pm_rig_attachment_image(const pm_rig* rig, uint32_t attachment, uint32_t pose, char* out, size_t capacity,
                            size_t* length) {
  const posemorph::Rig* a = AttachmentRig(rig, attachment);
  return CopyString(a ? a->part_image(0, pose) : posemorph::StringView{}, a && pose < a->pose_count(), out, capacity,
                    length);
}

uint32_t pm_rig_attached_vertex_count(const pm_rig* rig) { return rig ? rig->rig.attached_vertex_count() : 0; }
uint32_t pm_rig_attached_weight_count(const pm_rig* rig) { return rig ? rig->rig.attached_weight_count() : 0; }
uint32_t pm_rig_channel_weight_offset(const pm_rig* rig, uint32_t channel) {
  return rig ? rig->rig.channel_weight_offset(channel) : 0;
}
size_t pm_attach_workspace_size(const pm_rig* rig) { return rig ? rig->rig.attach_workspace_size() : 0; }

int pm_attach(const pm_rig* rig, size_t count, const double* body_positions, size_t body_capacity,
              const double* weights, const double* limited_weights, size_t weights_capacity, int linear,
              double* workspace, size_t workspace_capacity, double* positions, float* positions_f32,
              size_t positions_capacity) {
  if (!rig || rig->rig.attachment_count() == 0 || !Aligned(body_positions) || !Aligned(weights) ||
      !Aligned(limited_weights) || !Aligned(workspace) || !Aligned(positions) || !Aligned(positions_f32))
    return PM_ERROR_INVALID_ARGUMENT;
  if (count == 0) return PM_OK;
  const std::size_t v2 = 2 * std::size_t(rig->rig.vertex_count()),
                    a2 = 2 * std::size_t(rig->rig.attached_vertex_count());
  const std::size_t nw = rig->rig.attached_weight_count();
  if (count > (std::size_t(-1) / 2) / (v2 + a2 + nw)) return PM_ERROR_INVALID_ARGUMENT;
  if (body_capacity < count * v2 || weights_capacity < count * nw || positions_capacity < count * a2 ||
      workspace_capacity < rig->rig.attach_workspace_size())
    return PM_ERROR_BUFFER_TOO_SMALL;
  posemorph::AttachJob job;
  job.rig = &rig->rig;
  job.count = count;
  job.body_positions = {body_positions, count * v2};
  job.weights = {weights, count * nw};
  job.limited_weights = {limited_weights, count * nw};
  job.interpolation = linear ? posemorph::Interpolation::kLinear : posemorph::Interpolation::kRigid;
  job.workspace = {workspace, workspace_capacity};
  job.positions = {positions, count * a2};
  job.positions_f32 = {positions_f32, positions_f32 ? count * a2 : 0};
  return job.Run() ? PM_OK : PM_ERROR_INVALID_ARGUMENT;
}
}  // extern "C"
