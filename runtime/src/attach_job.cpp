// SPDX-License-Identifier: MIT
// AttachJob: a control channel's attachments placed on the body (DESIGN.md
// section 8). Each attachment is solved on its own with its joint pinned
// (MorphBatchJob, or MorphJob per character); minimising the as-rigid-as-
// possible energy with every target gradient turned by R and the joint held
// at p gives p + R (y - y_j), so the solve is followed by one rotation and
// one translation per character. R is the rotation of the parent triangle's
// deformation from pose 0 (its polar factor), computed with + - * / and sqrt
// only, in a fixed order: the same bits on every compiler and kernel path.
#include <cmath>

#include "posemorph/jobs.h"

namespace posemorph {
namespace {

// Rotation (c, s) of the 2x2 deformation taking triangle (r0, r1, r2) to
// (x0, x1, x2): the polar factor of J = M E^-1 with E = [r0 - r2, r1 - r2],
// M = [x0 - x2, x1 - x2]. det E > 0 (the loader's pose 0 is counter-
// clockwise), so M adj(E) has J's rotation; for J = [a b; c d] it is
// (a + d, c - b) normalised. A degenerate frame (zero length) keeps R = I.
void ParentRotation(const double* r, const double* x, const std::uint32_t* t, double* cs, double* sn) {
  const double e1x = r[2 * t[0]] - r[2 * t[2]], e1y = r[2 * t[0] + 1] - r[2 * t[2] + 1];
  const double e2x = r[2 * t[1]] - r[2 * t[2]], e2y = r[2 * t[1] + 1] - r[2 * t[2] + 1];
  const double m1x = x[2 * t[0]] - x[2 * t[2]], m1y = x[2 * t[0] + 1] - x[2 * t[2] + 1];
  const double m2x = x[2 * t[1]] - x[2 * t[2]], m2y = x[2 * t[1] + 1] - x[2 * t[2] + 1];
  // M adj(E), adj(E) = [e2y -e2x; -e1y e1x].
  const double j11 = m1x * e2y - m2x * e1y, j12 = m2x * e1x - m1x * e2x;
  const double j21 = m1y * e2y - m2y * e1y, j22 = m2y * e1x - m1y * e2x;
  const double c = j11 + j22, s = j21 - j12;
  const double h = std::sqrt(c * c + s * s);
  if (h > 0 && h < 1e300) {
    *cs = c / h;
    *sn = s / h;
  } else {
    *cs = 1;
    *sn = 0;
  }
}

// The point with barycentric weights w in triangle t of positions p.
void Barycentric(const double* p, const std::uint32_t* t, const double* w, double* px, double* py) {
  *px = (w[0] * p[2 * t[0]] + w[1] * p[2 * t[1]]) + w[2] * p[2 * t[2]];
  *py = (w[0] * p[2 * t[0] + 1] + w[1] * p[2 * t[1] + 1]) + w[2] * p[2 * t[2] + 1];
}

bool FiniteWeights(Span<const double> w, std::size_t n) {
  for (std::size_t k = 0; k < n; ++k)
    if (!(std::fabs(w[k]) <= kMaxJobWeight)) return false;
  return true;
}

}  // namespace

bool AttachJob::Validate() const {
  if (!rig || !rig->loaded() || rig->attachment_count() == 0) return false;
  if (count == 0) return true;
  const std::size_t v2 = 2 * std::size_t(rig->vertex_count()), a2 = 2 * std::size_t(rig->attached_vertex_count());
  const std::size_t nw = rig->attached_weight_count();
  if (count > (std::size_t(-1) / 2) / (v2 + a2 + nw)) return false;
  if (!body_positions.data || body_positions.size < count * v2) return false;
  if (!weights.data || weights.size < count * nw || !limited_weights.data || limited_weights.size < count * nw)
    return false;
  if (!FiniteWeights(weights, count * nw) || !FiniteWeights(limited_weights, count * nw)) return false;
  for (std::size_t k = 0; k < count * v2; ++k)
    if (!std::isfinite(body_positions[k])) return false;
  if (!workspace.data || workspace.size < rig->attach_workspace_size()) return false;
  if (!positions.data || positions.size < count * a2) return false;
  if (positions_f32.size != 0 && (!positions_f32.data || positions_f32.size < count * a2)) return false;
  if (interpolation != Interpolation::kRigid && interpolation != Interpolation::kLinear) return false;
  return true;
}

bool AttachJob::Run() const {
  if (!Validate()) return false;
  if (count == 0) return true;
  const Rig& body = *rig;
  const std::size_t v2 = 2 * std::size_t(body.vertex_count());
  const double* rest = body.pose_positions(0).data;
  const std::uint32_t* body_tris = body.triangles().data;
  std::size_t out = 0;  // doubles of positions written before this attachment's block
  bool within = true;   // every attachment's solve within kMaxPosition (jobs.h; zeros where not)
  for (std::uint32_t a = 0; a < body.attachment_count(); ++a) {
    const AttachmentView at = body.attachment(a);
    const Rig& part = *at.rig;
    const std::size_t n = part.pose_count(), p2 = 2 * std::size_t(part.vertex_count());
    const std::size_t w0 = count * std::size_t(body.channel_weight_offset(at.channel));
    double* y = positions.data + out;
    if (interpolation == Interpolation::kRigid && count > 1) {
      MorphBatchJob job;
      job.rig = &part;
      job.count = count;
      job.weights = weights.subspan(w0, count * n);
      job.limited_weights = limited_weights.subspan(w0, count * n);
      job.workspace = workspace;
      job.positions = {y, count * p2};
      within &= job.Run();
    } else {
      for (std::size_t k = 0; k < count; ++k) {
        MorphJob job;
        job.rig = &part;
        job.weights = weights.subspan(w0 + k * n, n);
        job.limited_weights = limited_weights.subspan(w0 + k * n, n);
        job.interpolation = interpolation;
        job.workspace = {workspace.data, part.morph_workspace_size()};
        job.positions = {y + k * p2, p2};
        within &= job.Run();
      }
    }
    const std::uint32_t* parent = body_tris + 3 * std::size_t(at.parent_triangle);
    const std::uint32_t* joint = part.triangles().data + 3 * std::size_t(at.joint_triangle);
    for (std::size_t k = 0; k < count; ++k) {
      const double* x = body_positions.data + k * v2;
      double* q = y + k * p2;
      double c, s, px, py, jx, jy;
      ParentRotation(rest, x, parent, &c, &s);
      Barycentric(x, parent, at.parent_weights, &px, &py);
      Barycentric(q, joint, at.joint_weights, &jx, &jy);
      for (std::size_t v = 0; v < p2; v += 2) {
        const double dx = q[v] - jx, dy = q[v + 1] - jy;
        q[v] = px + (c * dx - s * dy);
        q[v + 1] = py + (s * dx + c * dy);
      }
    }
    if (positions_f32.size)
      for (std::size_t k = 0; k < count * p2; ++k) positions_f32[out + k] = float(y[k]);
    out += count * p2;
  }
  return within;
}

}  // namespace posemorph
