// SPDX-License-Identifier: MIT
// Draw lists: weights, positions and the drawings to blend for each
// character of a frame (posemorph/draw_list.h).
#include "posemorph/draw_list.h"

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <new>

#include "draw_list_internal.h"
#include "posemorph/jobs.h"
#include "posemorph/rig_format.h"

namespace posemorph {

namespace {

// The transform with these fields, or the identity when one does not fit a
// float (or is not a number): a transform's fields are always finite.
Transform2D Fitted(double a, double b, double c, double d, double tx, double ty) {
  constexpr double kMax = 3.4028234663852886e38;  // the largest float
  for (double v : {a, b, c, d, tx, ty})
    if (!(std::fabs(v) <= kMax)) return Transform2D{};
  Transform2D t;
  t.a = float(a), t.b = float(b), t.c = float(c), t.d = float(d), t.tx = float(tx), t.ty = float(ty);
  return t;
}

}  // namespace

Transform2D Transform2D::Make(double x, double y, double radians, double scale_x, double scale_y, bool flip_x) {
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(radians) || !std::isfinite(scale_x) ||
      !std::isfinite(scale_y))
    return Transform2D{};
  // Linear part R * F * S with F = diag(-1, 1) when flipped, S = diag(sx, sy).
  const double cs = std::cos(radians), sn = std::sin(radians);
  const double fx = flip_x ? -scale_x : scale_x;
  return Fitted(cs * fx, sn * fx, -sn * scale_y, cs * scale_y, x, y);
}

Transform2D Transform2D::Place(const Rig& rig, double x, double y, double radians, double scale, bool face_left) {
  for (double v : {x, y, radians, scale})
    if (!std::isfinite(v)) return Transform2D{};
  return Compose(Make(x, y, radians, scale, scale, face_left != rig.facing_left()),
                 Make(-rig.anchor_x(), -rig.anchor_y()));
}

Transform2D Compose(const Transform2D& o, const Transform2D& i) {
  return Fitted(double(o.a) * i.a + double(o.c) * i.b, double(o.b) * i.a + double(o.d) * i.b,
                double(o.a) * i.c + double(o.c) * i.d, double(o.b) * i.c + double(o.d) * i.d,
                double(o.a) * i.tx + double(o.c) * i.ty + o.tx, double(o.b) * i.tx + double(o.d) * i.ty + o.ty);
}

Colour ClampColour(const Colour& c) {
  const auto unit = [](float v) { return v >= 0 ? (v <= 1 ? v : 1.0f) : (v < 0 ? 0.0f : 1.0f); };  // NaN: 1
  return Colour{unit(c.r), unit(c.g), unit(c.b), unit(c.a)};
}

std::uint32_t PickDrawings(Span<const double> w, std::uint32_t max_drawings, Span<BlendedDrawing> out) {
  std::uint32_t K = max_drawings < kMaxBlendDrawings ? max_drawings : kMaxBlendDrawings;
  if (out.size < K) K = std::uint32_t(out.size);
  if (K == 0 || w.size == 0 || !out.data) return 0;
  std::uint32_t best[kMaxBlendDrawings] = {};
  double weight[kMaxBlendDrawings] = {};
  std::uint32_t count = 0;
  for (std::uint32_t i = 0; i < w.size; ++i) {                   // insertion into a short list, largest first
    const double wi = w[i] > 0 && w[i] < HUGE_VAL ? w[i] : 0.0;  // NaN and infinity count as 0
    std::uint32_t at = count;
    while (at > 0 && weight[at - 1] < wi) --at;
    if (at >= K) continue;
    for (std::uint32_t k = count < K - 1 ? count : K - 1; k > at; --k) best[k] = best[k - 1], weight[k] = weight[k - 1];
    best[at] = i, weight[at] = wi;
    if (count < K) ++count;
  }
  double sum = 0;
  for (std::uint32_t k = 0; k < count; ++k) sum += weight[k];
  if (!(sum < HUGE_VAL)) {  // finite weights whose sum overflows: scaled by the largest first
    for (std::uint32_t k = 1; k < count; ++k) weight[k] /= weight[0];
    weight[0] = 1;
    sum = 0;
    for (std::uint32_t k = 0; k < count; ++k) sum += weight[k];
  }
  for (std::uint32_t k = 0; k < count; ++k) {
    out[k].pose = best[k];
    out[k].weight = sum > 0 ? float(weight[k] / sum) : (k == 0 ? 1.0f : 0.0f);
    out[k].uvs = nullptr;
  }
  return count;
}

namespace {

// Doubles per character of a rig with attachments: the body's positions,
// the later channels' raw, limited and texture weights, the attachments'
// positions.
std::size_t AttachedDoubles(const Rig& rig) {
  if (rig.attachment_count() == 0) return 0;
  return 2 * std::size_t(rig.vertex_count()) + 3 * std::size_t(rig.attached_weight_count()) +
         2 * std::size_t(rig.attached_vertex_count());
}

}  // namespace

std::size_t detail::DrawListBodyWorkspace(const Rig& rig, std::size_t count) {
  const std::size_t n = rig.pose_count(), v2 = 2 * std::size_t(rig.vertex_count());
  const std::size_t single = rig.morph_workspace_size() + v2;  // MorphJob's workspace and double positions
  const std::size_t batch = count > 1 ? rig.batch_workspace_size() : 0;
  return 2 * count * n + n + (batch > single ? batch : single);
}

std::size_t MaxDrawListCount(const Rig& rig) {
  if (!rig.loaded()) return 0;
  // Every buffer's bytes, count x (2V floats + 2N doubles, and for
  // attachments theirs) and the batch workspace, stay far inside size_t
  // (32-bit targets included).
  return (std::size_t(-1) / 64) /
         (2 * std::size_t(rig.vertex_count()) + 2 * std::size_t(rig.pose_count()) + 1 + AttachedDoubles(rig) +
          2 * std::size_t(rig.attached_vertex_count()) + rig.attachment_count() * sizeof(DrawList));
}

std::size_t DrawListWorkspaceSize(const Rig& rig, std::size_t count) {
  if (!rig.loaded() || count == 0 || count > MaxDrawListCount(rig)) return 0;
  const std::size_t extra = rig.attachment_count() ? count * AttachedDoubles(rig) + rig.attach_workspace_size() : 0;
  return detail::DrawListBodyWorkspace(rig, count) + extra;
}

std::uint32_t CharacterDrawSteps(const Rig& rig, const DrawList& body, const DrawList* attached, Span<DrawStep> out) {
  const std::uint32_t lists = 1 + (attached ? rig.attachment_count() : 0);
  auto list_of = [&](std::uint32_t i) -> const DrawList& { return i == 0 ? body : attached[i - 1]; };
  auto rig_of = [&](std::uint32_t i) -> const Rig& { return i == 0 ? rig : *rig.attachment(i - 1).rig; };
  return detail::MergeDrawSteps(
      lists, [&](std::uint32_t i) { return list_of(i).parts; },
      [&](std::uint32_t i, std::uint32_t part) {
        const DrawList& l = list_of(i);
        return rig_of(i).part_draw_order(part, l.drawing_count ? l.drawings[0].pose : 0);
      },
      [&](std::uint32_t k, std::uint32_t list, std::uint32_t part) {
        if (k < out.size) out[k] = DrawStep{list, part};
      });
}

namespace {

// The first `n` weights are finite and within what the morph jobs take.
bool FiniteWeights(Span<const double> w, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i)
    if (!(std::fabs(w[i]) <= kMaxJobWeight)) return false;
  return true;
}

}  // namespace

bool DrawListJob::Validate() const { return detail::ValidDrawListInputs(*this) && output.data && output.size >= count; }

bool detail::ValidDrawListInputs(const DrawListJob& job, bool attached_lists_elsewhere) {
  const Rig* rig = job.rig;
  const std::size_t count = job.count;
  if (!rig || !rig->loaded() || count == 0) return false;
  if (count > MaxDrawListCount(*rig)) return false;
  const std::size_t N = rig->pose_count();
  if (job.weights.size == 0) {
    if (!job.points.data || job.points.size / 2 < count) return false;
    if (job.limited_weights.size || job.texture_weights.size) return false;
  } else {
    if (job.points.size != 0) return false;
    for (const Span<const double>& w : {job.weights, job.limited_weights, job.texture_weights})
      if (!w.data || w.size / N < count) return false;
    if (!FiniteWeights(job.weights, count * N) || !FiniteWeights(job.limited_weights, count * N)) return false;
  }
  if (job.transforms.size != 0 && (!job.transforms.data || job.transforms.size != count)) return false;
  if (job.colours.size != 0 && (!job.colours.data || job.colours.size != count)) return false;
  if (job.part_opacities.size != 0 && (!job.part_opacities.data || job.part_opacities.size / rig->part_count() < count))
    return false;
  if (job.max_drawings < 1 || job.max_drawings > kMaxBlendDrawings) return false;
  if (job.interpolation != Interpolation::kRigid && job.interpolation != Interpolation::kLinear) return false;
  if (!job.workspace.data || job.workspace.size < DrawListWorkspaceSize(*rig, count)) return false;
  if (!job.positions.data || job.positions.size / (2 * std::size_t(rig->vertex_count())) < count) return false;
  const bool attached_given =
      job.attached_weights.size || job.attached_limited_weights.size || job.attached_texture_weights.size;
  if (job.attached_output.size == 0 && !attached_lists_elsewhere)
    return job.attached_positions.size == 0 && !attached_given;
  const std::size_t A = rig->attachment_count(), a2 = 2 * std::size_t(rig->attached_vertex_count());
  if (A == 0) return false;
  if (!attached_lists_elsewhere && (!job.attached_output.data || job.attached_output.size / A < count)) return false;
  if (!job.attached_positions.data || job.attached_positions.size / a2 < count) return false;
  if (job.weights.size != 0) {  // weights given: the attachments' too, and no channel points
    const std::size_t NW = rig->attached_weight_count();
    if (job.channel_points.size != 0) return false;
    for (const Span<const double>& w :
         {job.attached_weights, job.attached_limited_weights, job.attached_texture_weights})
      if (!w.data || w.size / NW < count) return false;
    return FiniteWeights(job.attached_weights, count * NW) && FiniteWeights(job.attached_limited_weights, count * NW);
  }
  if (attached_given) return false;
  const std::size_t c2 = 2 * std::size_t(rig->channel_count() - 1);
  if (job.channel_points.size != 0 && (!job.channel_points.data || job.channel_points.size / c2 < count)) return false;
  return true;
}

bool DrawListJob::Run() const {
  if (!Validate()) return false;
  double* body = attached_output.size ? workspace.data + detail::DrawListBodyWorkspace(*rig, count) : nullptr;
  if (!detail::RunDrawLists(
          *this, [this](std::size_t k) { return transforms.size ? transforms[k] : Transform2D(); },
          [this](std::size_t k, const DrawList& list) { output[k] = list; }, body))
    return false;
  if (!body) return true;
  const std::size_t A = rig->attachment_count();
  return detail::RunAttachedLists(
      *this, body, workspace.data + DrawListWorkspaceSize(*rig, count),
      [this](std::size_t k) {
        const DrawList& b = output[k];
        return detail::ListPlacement{b.transform, b.mirrored, b.colour};
      },
      [this, A](std::size_t k, std::uint32_t a, const DrawList& list) { attached_output[k * A + a] = list; });
}

CharacterBuffers CharacterBuffers::For(const Rig& rig, std::size_t count) {
  CharacterBuffers b;
  if (!rig.loaded() || count == 0 || count > MaxDrawListCount(rig)) return b;
  b.count = count;
  b.workspace = DrawListWorkspaceSize(rig, count);
  b.positions = count * 2 * std::size_t(rig.vertex_count());
  b.draw_lists = count;
  b.attached_positions = count * 2 * std::size_t(rig.attached_vertex_count());
  b.attached_lists = count * rig.attachment_count();
  std::size_t bytes = b.workspace * sizeof(double) + (b.positions + b.attached_positions) * sizeof(float);
  bytes = (bytes + alignof(DrawList) - 1) / alignof(DrawList) * alignof(DrawList);
  b.bytes = bytes + (count + b.attached_lists) * sizeof(DrawList);
  return b;
}

bool CharacterBuffers::Bind(const Rig& rig, void* block, std::size_t block_bytes, DrawListJob* job) const {
  if (!job || !block || count == 0 || block_bytes < bytes) return false;
  if (reinterpret_cast<std::uintptr_t>(block) % kAlignment != 0) return false;
  // Sizes from another rig would not fit this one.
  const CharacterBuffers again = For(rig, count);
  if (again.bytes != bytes || again.workspace != workspace || again.positions != positions ||
      again.attached_positions != attached_positions || again.attached_lists != attached_lists)
    return false;
  unsigned char* p = static_cast<unsigned char*>(block);
  job->rig = &rig;
  job->count = count;
  job->workspace = {reinterpret_cast<double*>(p), workspace};
  p += workspace * sizeof(double);
  job->positions = {reinterpret_cast<float*>(p), positions};
  p += positions * sizeof(float);
  job->attached_positions = {attached_positions ? reinterpret_cast<float*>(p) : nullptr, attached_positions};
  const std::size_t used = workspace * sizeof(double) + (positions + attached_positions) * sizeof(float);
  const std::size_t lists_at = (used + alignof(DrawList) - 1) / alignof(DrawList) * alignof(DrawList);
  DrawList* lists = reinterpret_cast<DrawList*>(static_cast<unsigned char*>(block) + lists_at);
  job->output = {lists, count};
  job->attached_output = {attached_lists ? lists + count : nullptr, attached_lists};
  for (std::size_t k = 0; k < count + attached_lists; ++k) new (&lists[k]) DrawList();
  return true;
}

}  // namespace posemorph
