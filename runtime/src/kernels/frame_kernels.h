// SPDX-License-Identifier: MIT
// The per-frame kernels, compiled once per path: a translation unit defines
// POSEMORPH_KERNEL_WIDTH (doubles per vector), POSEMORPH_KERNEL_NAMESPACE and
// POSEMORPH_KERNEL_ISA, is built with that path's compiler flags, and
// includes this file, which defines that path's KernelTable. Everything else
// here has internal linkage, so code built for one instruction set can never
// be shared with another path.
#include <cstdint>
#include <cstring>

#include "kernel_table.h"
#include "../rig_internals.h"
#include "posemorph/rig.h"

namespace posemorph::detail::POSEMORPH_KERNEL_NAMESPACE {
namespace {

#include "vec.h"
#include "sincos.h"
#include "morph_math.h"

// The loader groups angles and stretches in blocks of 8 triangles
// (RigInternals::BlendBlocks); a path with narrower vectors takes a block in parts.
constexpr int kBlock = 8;
static_assert(kBlock % kWidth == 0, "a blend block is a whole number of vectors");

// One character. Triangles go through the blend, sin/cos and A a vector at
// a time (lane j is triangle t0 + j) and into the right-hand side one by
// one: per element the operations the batch performs with a character in
// each lane.
void Rigid(const Rig& rig, const double* w, const double* ws, double* work, double* x) {
  const std::uint32_t V = rig.vertex_count(), T = rig.triangle_count(), N = rig.pose_count();
  double* b = work;  // 2V: right-hand side, both coordinates
  for (std::size_t k = 0; k < 2 * std::size_t(V); ++k) b[k] = 0;

  const std::uint32_t* tri = rig.triangles().data;
  const double* grad = rig.gradients().data;
  const double* blocks = RigInternals::BlendBlocks(rig).data;
  for (std::uint32_t t0 = 0; t0 < T; t0 += kBlock) {
    const std::uint32_t count = T - t0 < std::uint32_t(kBlock) ? T - t0 : std::uint32_t(kBlock);
    const double* in = blocks + std::size_t(t0 / kBlock) * 4 * N * kBlock;
    double block[4][kBlock];
    for (int part = 0; part < kBlock; part += kWidth) {
      // Lane j is triangle t0 + part + j; per lane the same sums as BlendTriangle.
      const double* p = in + part;
      Vec alpha = w[0] * LoadVec(p), s11 = ws[0] * LoadVec(p + kBlock), s12 = ws[0] * LoadVec(p + 2 * kBlock),
          s22 = ws[0] * LoadVec(p + 3 * kBlock);
      for (std::uint32_t i = 1; i < N; ++i) {
        p += 4 * kBlock;
        alpha += w[i] * LoadVec(p);
        s11 += ws[i] * LoadVec(p + kBlock);
        s12 += ws[i] * LoadVec(p + 2 * kBlock);
        s22 += ws[i] * LoadVec(p + 3 * kBlock);
      }
      Vec s, c, a11, a12, a21, a22;
      SinCos(alpha, &s, &c);
      TargetMatrix(c, s, s11, s12, s22, &a11, &a12, &a21, &a22);
      StoreVec(block[0] + part, a11), StoreVec(block[1] + part, a12);
      StoreVec(block[2] + part, a21), StoreVec(block[3] + part, a22);
    }
    for (std::uint32_t j = 0; j < count; ++j) {
      const std::size_t t = t0 + j;
      AddToRhs<double>(tri + 3 * t, grad + 6 * t, block[0][j], block[1][j], block[2][j], block[3][j], b);
    }
  }
  // Vertex 0 is pinned at the origin; the centroid shift places the mesh.
  SolvePinnedKernel<double>(RigInternals::Solve(rig), b + 2, work + 2 * std::size_t(V), x + 2);
  x[0] = x[1] = 0;
  PlaceCentroid<double>(rig, w, x);
}

// kWidth characters, one per lane.
void Group(const Rig& rig, const double* w_in, const double* ws_in, double* x_out, double* y_out) {
  const Vec* W = reinterpret_cast<const Vec*>(w_in);
  const Vec* WS = reinterpret_cast<const Vec*>(ws_in);
  Vec* x = reinterpret_cast<Vec*>(x_out);
  Vec* y = reinterpret_cast<Vec*>(y_out);
  const std::uint32_t V = rig.vertex_count(), T = rig.triangle_count(), N = rig.pose_count();
  for (std::size_t k = 0; k < 2 * std::size_t(V); ++k) x[k] = Vec{};
  const std::uint32_t* tri = rig.triangles().data;
  const double* grad = rig.gradients().data;
  const double* angle = rig.angles().data;
  const double* stretch = rig.stretches().data;
  for (std::size_t t = 0; t < T; ++t) {
    Vec alpha, s11, s12, s22, s, c, a11, a12, a21, a22;
    BlendTriangle<Vec>(angle + t * N, stretch + 3 * t * N, W, WS, N, &alpha, &s11, &s12, &s22);
    SinCos(alpha, &s, &c);
    TargetMatrix(c, s, s11, s12, s22, &a11, &a12, &a21, &a22);
    AddToRhs<Vec>(tri + 3 * t, grad + 6 * t, a11, a12, a21, a22, x);
  }
  SolvePinnedKernel<Vec>(RigInternals::Solve(rig), x + 2, y, x + 2);
  x[0] = x[1] = Vec{};
  PlaceCentroid<Vec>(rig, W, x);
}

void Solve(const SolveLayout& factor, const double* b, double* scratch, double* x) {
  SolvePinnedKernel<double>(factor, b, scratch, x);
}

}  // namespace

extern const KernelTable kKernels;
const KernelTable kKernels = {Isa::POSEMORPH_KERNEL_ISA, kWidth, Rigid, Group, Solve};

}  // namespace posemorph::detail::POSEMORPH_KERNEL_NAMESPACE
