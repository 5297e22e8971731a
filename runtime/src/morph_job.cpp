// Vertex positions for a weight vector (DESIGN.md section 3): blend each
// triangle's rotation angle (raw weights) and symmetric stretch (shear-limited
// weights), assemble the right-hand side of the normal equations, solve with
// the baked factor, then move the area-weighted centroid to sum_i w_i c_i.
#include <cmath>

#include "ldlt_solve.h"
#include "posemorph/jobs.h"

namespace posemorph {

bool MorphJob::Validate() const {
  if (!rig || !rig->loaded()) return false;
  const std::size_t n = rig->pose_count(), v2 = 2 * std::size_t(rig->vertex_count());
  if (!weights.data || weights.size < n || !shear_weights.data || shear_weights.size < n) return false;
  if (!workspace.data || workspace.size < rig->morph_workspace_size()) return false;
  if (!positions.data || positions.size < v2) return false;
  if (positions_f32.size != 0 && (!positions_f32.data || positions_f32.size < v2)) return false;
  if (interpolation != Interpolation::kRigid && interpolation != Interpolation::kLinear) return false;
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(weights[i]) || !std::isfinite(shear_weights[i])) return false;
  return true;
}

namespace {

void Linear(const Rig& rig, const double* w, double* x) {
  const std::size_t v2 = 2 * std::size_t(rig.vertex_count());
  for (std::size_t k = 0; k < v2; ++k) x[k] = 0;
  for (std::uint32_t i = 0; i < rig.pose_count(); ++i) {
    const double* q = rig.pose_positions(i).data;
    for (std::size_t k = 0; k < v2; ++k) x[k] += w[i] * q[k];
  }
}

void Rigid(const Rig& rig, const double* w, const double* ws, double* work, double* x) {
  const std::uint32_t V = rig.vertex_count(), T = rig.triangle_count(), N = rig.pose_count();
  double* b = work;  // 2V: right-hand side, both coordinates
  for (std::size_t k = 0; k < 2 * std::size_t(V); ++k) b[k] = 0;

  const std::uint32_t* tri = rig.triangles().data;
  const double* grad = rig.gradients().data;
  const double* angle = rig.angles().data;
  const double* shear = rig.shears().data;
  for (std::uint32_t t = 0; t < T; ++t, tri += 3, grad += 6, angle += N, shear += 3 * N) {
    double alpha = 0, s11 = 0, s12 = 0, s22 = 0;
    for (std::uint32_t i = 0; i < N; ++i) {
      alpha += w[i] * angle[i];
      s11 += ws[i] * shear[3 * i];
      s12 += ws[i] * shear[3 * i + 1];
      s22 += ws[i] * shear[3 * i + 2];
    }
    const double c = std::cos(alpha), s = std::sin(alpha);
    // A = R(alpha) S; row d of A pulls the three vertices through grad (3x2).
    const double a11 = c * s11 - s * s12, a12 = c * s12 - s * s22;
    const double a21 = s * s11 + c * s12, a22 = s * s12 + c * s22;
    for (int k = 0; k < 3; ++k) {
      const double g0 = grad[2 * k], g1 = grad[2 * k + 1];
      b[2 * tri[k]] += g0 * a11 + g1 * a12;
      b[2 * tri[k] + 1] += g0 * a21 + g1 * a22;
    }
  }
  // Vertex 0 is pinned at the origin; the centroid shift below places the mesh.
  detail::SolvePinned(rig.factor(), b + 2, work + 2 * std::size_t(V), x + 2);
  x[0] = x[1] = 0;
}

}  // namespace

bool MorphJob::Run() const {
  if (!Validate()) return false;
  const Rig& r = *rig;
  const std::uint32_t V = r.vertex_count(), N = r.pose_count();
  double* x = positions.data;
  if (interpolation == Interpolation::kLinear) {
    Linear(r, weights.data, x);
  } else {
    Rigid(r, weights.data, shear_weights.data, workspace.data, x);
    double cx = 0, cy = 0, tx = 0, ty = 0;
    const double* m = r.vertex_masses().data;
    for (std::uint32_t v = 0; v < V; ++v) {
      cx += m[v] * x[2 * v];
      cy += m[v] * x[2 * v + 1];
    }
    const double* c = r.pose_centroids().data;
    for (std::uint32_t i = 0; i < N; ++i) {
      tx += weights[i] * c[2 * i];
      ty += weights[i] * c[2 * i + 1];
    }
    const double dx = tx - cx, dy = ty - cy;
    for (std::uint32_t v = 0; v < V; ++v) {
      x[2 * v] += dx;
      x[2 * v + 1] += dy;
    }
  }
  if (positions_f32.size)
    for (std::size_t k = 0; k < 2 * std::size_t(V); ++k) positions_f32[k] = float(x[k]);
  return true;
}

}  // namespace posemorph
