// SPDX-License-Identifier: MIT
// MorphBatchJob: MorphJob's rigid path over a vector's width of characters at
// a time (8 on AVX-512, 4 on AVX2, 2 on SSE2/NEON/WebAssembly, 1 scalar).
#include <cmath>
#include <cstdint>

#include "kernels/kernel_table.h"
#include "rig_internals.h"
#include "posemorph/jobs.h"

namespace posemorph {

using detail::kMaxLanes;

std::size_t Rig::batch_workspace_size() const {
  // b/x (2V lanes) and y (2n lanes), plus slack to align to the lane size;
  // also enough for MorphJob, which a small last group falls back to.
  return (4 * std::size_t(vertex_count_) + 1) * kMaxLanes;
}

bool MorphBatchJob::Validate() const {
  if (!rig || !rig->loaded()) return false;
  const std::size_t n = rig->pose_count(), v2 = 2 * std::size_t(rig->vertex_count());
  if (count == 0) return true;
  if (count > (std::size_t(-1) / 2) / (v2 + n)) return false;
  if (!weights.data || weights.size < count * n || !limited_weights.data || limited_weights.size < count * n)
    return false;
  if (!workspace.data || workspace.size < rig->batch_workspace_size()) return false;
  if (positions.size == 0 && positions_f32.size == 0) return false;
  if (positions.size != 0 && (!positions.data || positions.size < count * v2)) return false;
  if (positions_f32.size != 0 && (!positions_f32.data || positions_f32.size < count * v2)) return false;
  for (std::size_t k = 0; k < count * n; ++k)
    if (!(std::fabs(weights[k]) <= kMaxJobWeight) || !(std::fabs(limited_weights[k]) <= kMaxJobWeight)) return false;
  return true;
}

bool MorphBatchJob::Run() const {
  if (!Validate()) return false;
  if (count == 0) return true;  // nothing to do: the spans may all be empty
  const Rig& r = *rig;
  const std::uint32_t N = r.pose_count();
  const std::size_t v2 = 2 * std::size_t(r.vertex_count());
  const detail::KernelTable& kernels = *detail::RigInternals::Kernels(r);
  const std::size_t width = std::size_t(kernels.lanes);
  // A group costs about (3 + width) / 4 single evaluations on AVX-512 and
  // less on narrower paths; a last group below 3/8 of the width (3 of 8,
  // 2 of 4) goes one by one instead (the same arithmetic, so the same bits).
  const std::size_t min_lanes = (3 * width + 7) / 8;
  const std::uintptr_t base = reinterpret_cast<std::uintptr_t>(workspace.data);
  const std::uintptr_t aligned = (base + 63) / 64 * 64;
  double* x = reinterpret_cast<double*>(aligned);            // 2V x width
  double* y = x + v2 * width;                                // 2(V-1) x width
  alignas(64) double W[64 * kMaxLanes], WS[64 * kMaxLanes];  // N <= 64, the format's limit
  bool within = true;                                        // every character's solve within kMaxPosition
  for (std::size_t g = 0; g < count; g += width) {
    const std::size_t lanes = count - g < width ? count - g : width;
    if (lanes < min_lanes) {
      // Doubles go to the caller's array, or to the spare half of the workspace.
      for (std::size_t k = g; k < count; ++k) {
        MorphJob one;
        one.rig = rig;
        one.weights = weights.subspan(k * N, N);
        one.limited_weights = limited_weights.subspan(k * N, N);
        one.workspace = {workspace.data, r.morph_workspace_size()};
        one.positions =
            positions.size ? positions.subspan(k * v2, v2) : workspace.subspan(r.morph_workspace_size(), v2);
        if (positions_f32.size) one.positions_f32 = positions_f32.subspan(k * v2, v2);
        within &= one.Run();
      }
      break;
    }
    // A short last group repeats its last character in the spare lanes.
    for (std::uint32_t i = 0; i < N; ++i)
      for (std::size_t l = 0; l < width; ++l) {
        const std::size_t ch = g + (l < lanes ? l : lanes - 1);
        W[i * width + l] = weights[ch * N + i];
        WS[i * width + l] = limited_weights[ch * N + i];
      }
    kernels.group(r, W, WS, x, y);
    // A lane whose solve goes beyond kMaxPosition (jobs.h) gets zeros.
    bool lane_within[kMaxLanes];
    for (std::size_t l = 0; l < width; ++l) lane_within[l] = true;
    for (std::size_t k = 0; k < v2; ++k)
      for (std::size_t l = 0; l < lanes; ++l) lane_within[l] &= std::fabs(x[k * width + l]) <= kMaxPosition;
    for (std::size_t l = 0; l < lanes; ++l)
      if (!lane_within[l]) {
        within = false;
        for (std::size_t k = 0; k < v2; ++k) x[k * width + l] = 0;
      }
    // One pass over the lanes, writing each character's array in order.
    if (positions.size) {
      double* out = positions.data + g * v2;
      for (std::size_t k = 0; k < v2; ++k)
        for (std::size_t l = 0; l < lanes; ++l) out[l * v2 + k] = x[k * width + l];
    }
    if (positions_f32.size) {
      float* out32 = positions_f32.data + g * v2;
      for (std::size_t k = 0; k < v2; ++k)
        for (std::size_t l = 0; l < lanes; ++l) out32[l * v2 + k] = float(x[k * width + l]);
    }
  }
  return within;
}

}  // namespace posemorph
