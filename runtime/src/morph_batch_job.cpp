// MorphBatchJob: MorphJob's rigid path over kLanes characters at a time.
#include <cmath>
#include <cstdint>

#include "morph_kernel.h"
#include "posemorph/jobs.h"

namespace posemorph {

using detail::kLanes;
using detail::Lanes;

// Groups with fewer characters than this are evaluated one by one.
constexpr std::size_t kMinLanes = 3;

std::size_t Rig::batch_workspace_size() const {
  // b/x (2V lanes) and y (2n lanes), plus slack to align to the lane size;
  // also enough for MorphJob, which a small last group falls back to.
  return (4 * std::size_t(vertex_count_) + 1) * kLanes;
}

bool MorphBatchJob::Validate() const {
  if (!rig || !rig->loaded()) return false;
  const std::size_t n = rig->pose_count(), v2 = 2 * std::size_t(rig->vertex_count());
  if (count == 0) return true;
  if (count > (std::size_t(-1) / 2) / (v2 + n)) return false;
  if (!weights.data || weights.size < count * n || !shear_weights.data || shear_weights.size < count * n) return false;
  if (!workspace.data || workspace.size < rig->batch_workspace_size()) return false;
  if (positions.size == 0 && positions_f32.size == 0) return false;
  if (positions.size != 0 && (!positions.data || positions.size < count * v2)) return false;
  if (positions_f32.size != 0 && (!positions_f32.data || positions_f32.size < count * v2)) return false;
  for (std::size_t k = 0; k < count * n; ++k)
    if (!std::isfinite(weights[k]) || !std::isfinite(shear_weights[k])) return false;
  return true;
}

namespace {

// One group: W and WS hold N lanes of weights; x (2V lanes) receives the
// positions, y is scratch (2n lanes).
__attribute__((target_clones("avx512f", "avx2", "default")))
void RunGroup(const Rig& rig, const Lanes* W, const Lanes* WS, Lanes* x, Lanes* y) {
  const std::uint32_t V = rig.vertex_count(), T = rig.triangle_count(), N = rig.pose_count();
  const Lanes zero = detail::Broadcast(0.0);
  for (std::size_t k = 0; k < 2 * std::size_t(V); ++k) x[k] = zero;
  const std::uint32_t* tri = rig.triangles().data;
  const double* grad = rig.gradients().data;
  const double* angle = rig.angles().data;
  const double* shear = rig.shears().data;
  for (std::size_t t = 0; t < T; ++t) {
    Lanes alpha, s11, s12, s22, s, c, a11, a12, a21, a22;
    detail::BlendTriangle<Lanes>(angle + t * N, shear + 3 * t * N, W, WS, N, &alpha, &s11, &s12, &s22);
    detail::SinCos(alpha, &s, &c);
    detail::TargetMatrix(c, s, s11, s12, s22, &a11, &a12, &a21, &a22);
    detail::AddToRhs<Lanes>(tri + 3 * t, grad + 6 * t, a11, a12, a21, a22, x);
  }
  detail::SolvePinnedKernel<Lanes>(rig.factor(), x + 2, y, x + 2);
  x[0] = x[1] = zero;
  detail::PlaceCentroid<Lanes>(rig, W, x);
}

}  // namespace

bool MorphBatchJob::Run() const {
  if (!Validate()) return false;
  const Rig& r = *rig;
  const std::uint32_t N = r.pose_count();
  const std::size_t v2 = 2 * std::size_t(r.vertex_count());
  const std::uintptr_t base = reinterpret_cast<std::uintptr_t>(workspace.data);
  const std::uintptr_t aligned = (base + sizeof(Lanes) - 1) / sizeof(Lanes) * sizeof(Lanes);
  Lanes* x = reinterpret_cast<Lanes*>(aligned);
  Lanes* y = x + v2;
  alignas(sizeof(Lanes)) Lanes W[64], WS[64];  // N <= 64, the format's limit
  for (std::size_t g = 0; g < count; g += kLanes) {
    const std::size_t lanes = count - g < std::size_t(kLanes) ? count - g : std::size_t(kLanes);
    if (lanes < kMinLanes) {
      // A group costs about four single evaluations; below that, evaluate
      // one by one (the same arithmetic, so the same bits).
      // Doubles go to the caller's array, or to the spare half of the workspace.
      for (std::size_t k = g; k < count; ++k) {
        MorphJob one;
        one.rig = rig;
        one.weights = {weights.data + k * N, N};
        one.shear_weights = {shear_weights.data + k * N, N};
        one.workspace = {workspace.data, r.morph_workspace_size()};
        one.positions = positions.size ? Span<double>(positions.data + k * v2, v2)
                                       : Span<double>(workspace.data + r.morph_workspace_size(), v2);
        if (positions_f32.size) one.positions_f32 = {positions_f32.data + k * v2, v2};
        one.Run();
      }
      break;
    }
    // A short last group repeats its last character in the spare lanes.
    for (std::uint32_t i = 0; i < N; ++i)
      for (int l = 0; l < kLanes; ++l) {
        const std::size_t ch = g + (std::size_t(l) < lanes ? std::size_t(l) : lanes - 1);
        W[i][l] = weights[ch * N + i];
        WS[i][l] = shear_weights[ch * N + i];
      }
    RunGroup(r, W, WS, x, y);
    // One pass over the lanes, writing each character's array in order.
    if (positions.size) {
      double* out = positions.data + g * v2;
      for (std::size_t k = 0; k < v2; ++k)
        for (std::size_t l = 0; l < lanes; ++l) out[l * v2 + k] = x[k][l];
    }
    if (positions_f32.size) {
      float* out32 = positions_f32.data + g * v2;
      for (std::size_t k = 0; k < v2; ++k)
        for (std::size_t l = 0; l < lanes; ++l) out32[l * v2 + k] = float(x[k][l]);
    }
  }
  return true;
}

}  // namespace posemorph
