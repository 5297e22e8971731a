// SPDX-License-Identifier: MIT
// Draw lists: weights, positions and the drawings to blend for each
// character of a frame (posemorph/draw_list.h).
#include "posemorph/draw_list.h"

#include <cmath>
#include <cstdint>
#include <new>

#include "draw_list_internal.h"

namespace posemorph {

Transform2D Transform2D::Make(double x, double y, double radians, double scale_x, double scale_y, bool flip_x) {
  Transform2D t;
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(radians) || !std::isfinite(scale_x) ||
      !std::isfinite(scale_y))
    return t;
  // Linear part R * F * S with F = diag(-1, 1) when flipped, S = diag(sx, sy).
  const double cs = std::cos(radians), sn = std::sin(radians);
  const double fx = flip_x ? -scale_x : scale_x;
  t.a = float(cs * fx), t.b = float(sn * fx);
  t.c = float(-sn * scale_y), t.d = float(cs * scale_y);
  t.tx = float(x), t.ty = float(y);
  return t;
}

Transform2D Compose(const Transform2D& o, const Transform2D& i) {
  Transform2D t;
  t.a = float(double(o.a) * i.a + double(o.c) * i.b);
  t.b = float(double(o.b) * i.a + double(o.d) * i.b);
  t.c = float(double(o.a) * i.c + double(o.c) * i.d);
  t.d = float(double(o.b) * i.c + double(o.d) * i.d);
  t.tx = float(double(o.a) * i.tx + double(o.c) * i.ty + o.tx);
  t.ty = float(double(o.b) * i.tx + double(o.d) * i.ty + o.ty);
  return t;
}

std::uint32_t PickDrawings(Span<const double> w, std::uint32_t max_drawings, Span<BlendedDrawing> out) {
  std::uint32_t K = max_drawings < kMaxBlendDrawings ? max_drawings : kMaxBlendDrawings;
  if (out.size < K) K = std::uint32_t(out.size);
  if (K == 0 || w.size == 0 || !out.data) return 0;
  std::uint32_t best[kMaxBlendDrawings] = {};
  double weight[kMaxBlendDrawings] = {};
  std::uint32_t count = 0;
  for (std::uint32_t i = 0; i < w.size; ++i) {  // insertion into a short list, largest first
    const double wi = w[i] > 0 ? w[i] : 0.0;    // also maps NaN to 0
    std::uint32_t at = count;
    while (at > 0 && weight[at - 1] < wi) --at;
    if (at >= K) continue;
    for (std::uint32_t k = count < K - 1 ? count : K - 1; k > at; --k) best[k] = best[k - 1], weight[k] = weight[k - 1];
    best[at] = i, weight[at] = wi;
    if (count < K) ++count;
  }
  double sum = 0;
  for (std::uint32_t k = 0; k < count; ++k) sum += weight[k];
  for (std::uint32_t k = 0; k < count; ++k) {
    out[k].pose = best[k];
    out[k].weight = sum > 0 ? float(weight[k] / sum) : (k == 0 ? 1.0f : 0.0f);
    out[k].uvs = nullptr;
  }
  return count;
}

std::size_t MaxDrawListCount(const Rig& rig) {
  if (!rig.loaded()) return 0;
  // Every buffer's bytes, count x (2V floats + 2N doubles) and the batch
  // workspace, stay far inside size_t (32-bit targets included).
  return (std::size_t(-1) / 64) / (2 * std::size_t(rig.vertex_count()) + 2 * std::size_t(rig.pose_count()) + 1);
}

std::size_t DrawListWorkspaceSize(const Rig& rig, std::size_t count) {
  if (!rig.loaded() || count == 0 || count > MaxDrawListCount(rig)) return 0;
  const std::size_t n = rig.pose_count(), v2 = 2 * std::size_t(rig.vertex_count());
  const std::size_t single = rig.morph_workspace_size() + v2;  // MorphJob's workspace and double positions
  const std::size_t batch = count > 1 ? rig.batch_workspace_size() : 0;
  return 2 * count * n + n + (batch > single ? batch : single);
}

bool DrawListJob::Validate() const {
  if (!rig || !rig->loaded() || count == 0) return false;
  if (count > MaxDrawListCount(*rig)) return false;
  if (!points.data || points.size / 2 < count) return false;
  if (transforms.size != 0 && (!transforms.data || transforms.size != count)) return false;
  if (max_drawings < 1 || max_drawings > kMaxBlendDrawings) return false;
  if (interpolation != Interpolation::kRigid && interpolation != Interpolation::kLinear) return false;
  if (!workspace.data || workspace.size < DrawListWorkspaceSize(*rig, count)) return false;
  if (!positions.data || positions.size / (2 * std::size_t(rig->vertex_count())) < count) return false;
  return true;
}

bool DrawListJob::Run() const {
  if (!Validate() || !output.data || output.size < count) return false;
  return detail::RunDrawLists(
      *this, [this](std::size_t k) { return transforms.size ? transforms[k] : Transform2D(); },
      [this](std::size_t k, const DrawList& list) { output[k] = list; });
}

CharacterBuffers CharacterBuffers::For(const Rig& rig, std::size_t count) {
  CharacterBuffers b;
  if (!rig.loaded() || count == 0 || count > MaxDrawListCount(rig)) return b;
  b.count = count;
  b.workspace = DrawListWorkspaceSize(rig, count);
  b.positions = count * 2 * std::size_t(rig.vertex_count());
  b.draw_lists = count;
  std::size_t bytes = b.workspace * sizeof(double) + b.positions * sizeof(float);
  bytes = (bytes + alignof(DrawList) - 1) / alignof(DrawList) * alignof(DrawList);
  b.bytes = bytes + count * sizeof(DrawList);
  return b;
}

bool CharacterBuffers::Bind(const Rig& rig, void* block, std::size_t block_bytes, DrawListJob* job) const {
  if (!job || !block || count == 0 || block_bytes < bytes) return false;
  if (reinterpret_cast<std::uintptr_t>(block) % kAlignment != 0) return false;
  // Sizes from another rig would not fit this one.
  const CharacterBuffers again = For(rig, count);
  if (again.bytes != bytes || again.workspace != workspace || again.positions != positions) return false;
  unsigned char* p = static_cast<unsigned char*>(block);
  job->rig = &rig;
  job->count = count;
  job->workspace = {reinterpret_cast<double*>(p), workspace};
  p += workspace * sizeof(double);
  job->positions = {reinterpret_cast<float*>(p), positions};
  const std::size_t used = workspace * sizeof(double) + positions * sizeof(float);
  const std::size_t lists_at = (used + alignof(DrawList) - 1) / alignof(DrawList) * alignof(DrawList);
  job->output = {reinterpret_cast<DrawList*>(static_cast<unsigned char*>(block) + lists_at), count};
  for (std::size_t k = 0; k < count; ++k) new (&job->output.data[k]) DrawList();
  return true;
}

}  // namespace posemorph
