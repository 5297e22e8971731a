// Vertex positions for a weight vector (DESIGN.md section 3): blend each
// triangle's rotation angle (raw weights) and symmetric stretch (shear-limited
// weights), assemble the right-hand side of the normal equations, solve with
// the baked factor, then move the area-weighted centroid to sum_i w_i c_i.
#include <cmath>

#include "morph_kernel.h"
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

// Triangles go through the blend, sin/cos and A in blocks of kLanes (lane j
// is triangle t0 + j) and into the right-hand side one by one: per element
// the operations the batch performs with a character in each lane.
__attribute__((target_clones("avx512f", "avx2", "default")))
void Rigid(const Rig& rig, const double* w, const double* ws, double* work, double* x) {
  using detail::kLanes;
  using detail::Lanes;
  const std::uint32_t V = rig.vertex_count(), T = rig.triangle_count(), N = rig.pose_count();
  double* b = work;  // 2V: right-hand side, both coordinates
  for (std::size_t k = 0; k < 2 * std::size_t(V); ++k) b[k] = 0;

  const std::uint32_t* tri = rig.triangles().data;
  const double* grad = rig.gradients().data;
  const double* blocks = rig.blend_blocks().data;
  static_assert(kLanes == 8, "the loader builds blend blocks of 8 triangles");
  for (std::uint32_t t0 = 0; t0 < T; t0 += kLanes) {
    const std::uint32_t count = T - t0 < std::uint32_t(kLanes) ? T - t0 : std::uint32_t(kLanes);
    // Lane j is triangle t0 + j; per lane the same sums as BlendTriangle.
    const double* in = blocks + std::size_t(t0 / kLanes) * 4 * N * kLanes;
    Lanes alpha = w[0] * detail::Load(in), s11 = ws[0] * detail::Load(in + kLanes),
          s12 = ws[0] * detail::Load(in + 2 * kLanes), s22 = ws[0] * detail::Load(in + 3 * kLanes);
    for (std::uint32_t i = 1; i < N; ++i) {
      const double* p = in + std::size_t(i) * 4 * kLanes;
      alpha += w[i] * detail::Load(p);
      s11 += ws[i] * detail::Load(p + kLanes);
      s12 += ws[i] * detail::Load(p + 2 * kLanes);
      s22 += ws[i] * detail::Load(p + 3 * kLanes);
    }
    alignas(64) double block[4][kLanes];
    Lanes s, c, a11, a12, a21, a22;
    detail::SinCos(alpha, &s, &c);
    detail::TargetMatrix(c, s, s11, s12, s22, &a11, &a12, &a21, &a22);
    detail::Store(block[0], a11), detail::Store(block[1], a12), detail::Store(block[2], a21), detail::Store(block[3], a22);
    for (std::uint32_t j = 0; j < count; ++j) {
      const std::size_t t = t0 + j;
      detail::AddToRhs<double>(tri + 3 * t, grad + 6 * t, block[0][j], block[1][j], block[2][j], block[3][j], b);
    }
  }
  // Vertex 0 is pinned at the origin; the centroid shift places the mesh.
  detail::SolvePinnedKernel<double>(rig.factor(), b + 2, work + 2 * std::size_t(V), x + 2);
  x[0] = x[1] = 0;
  detail::PlaceCentroid<double>(rig, w, x);
}

}  // namespace

bool MorphJob::Run() const {
  if (!Validate()) return false;
  const Rig& r = *rig;
  const std::uint32_t V = r.vertex_count();
  double* x = positions.data;
  if (interpolation == Interpolation::kLinear) {
    Linear(r, weights.data, x);
  } else {
    Rigid(r, weights.data, shear_weights.data, workspace.data, x);
  }
  if (positions_f32.size)
    for (std::size_t k = 0; k < 2 * std::size_t(V); ++k) positions_f32[k] = float(x[k]);
  return true;
}

}  // namespace posemorph
