// SPDX-License-Identifier: MIT
// Vertex positions for a weight vector (DESIGN.md section 3): blend each
// triangle's rotation angle (raw weights) and symmetric stretch (limited
// weights), assemble the right-hand side of the normal equations, solve with
// the baked factor, then move the area-weighted centroid to sum_i w_i c_i.
// The rigid arithmetic lives in kernels/ (one copy per instruction set).
#include <cmath>

#include "kernels/kernel_table.h"
#include "rig_internals.h"
#include "posemorph/jobs.h"

namespace posemorph {

bool MorphJob::Validate() const {
  if (!rig || !rig->loaded()) return false;
  const std::size_t n = rig->pose_count(), v2 = 2 * std::size_t(rig->vertex_count());
  if (!weights.data || weights.size < n || !limited_weights.data || limited_weights.size < n) return false;
  if (!workspace.data || workspace.size < rig->morph_workspace_size()) return false;
  if (!positions.data || positions.size < v2) return false;
  if (positions_f32.size != 0 && (!positions_f32.data || positions_f32.size < v2)) return false;
  if (interpolation != Interpolation::kRigid && interpolation != Interpolation::kLinear) return false;
  for (std::size_t i = 0; i < n; ++i)
    if (!(std::fabs(weights[i]) <= kMaxJobWeight) || !(std::fabs(limited_weights[i]) <= kMaxJobWeight)) return false;
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

}  // namespace

bool MorphJob::Run() const {
  if (!Validate()) return false;
  const Rig& r = *rig;
  const std::uint32_t V = r.vertex_count();
  double* x = positions.data;
  if (interpolation == Interpolation::kLinear) {
    Linear(r, weights.data, x);
  } else {
    detail::RigInternals::Kernels(r)->rigid(r, weights.data, limited_weights.data, workspace.data, x);
  }
  // A solve beyond kMaxPosition (a factor that amplifies, jobs.h) gives zeros and fails.
  bool within = true;
  for (std::size_t k = 0; k < 2 * std::size_t(V); ++k) within &= std::fabs(x[k]) <= kMaxPosition;
  if (!within)
    for (std::size_t k = 0; k < 2 * std::size_t(V); ++k) x[k] = 0;
  if (positions_f32.size)
    for (std::size_t k = 0; k < 2 * std::size_t(V); ++k) positions_f32[k] = float(x[k]);
  return within;
}

}  // namespace posemorph
