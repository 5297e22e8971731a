// SPDX-License-Identifier: MIT
// The vector of this translation unit's path: POSEMORPH_KERNEL_WIDTH doubles
// as a GCC/Clang vector type (its arithmetic is the plain IEEE operation per
// lane), or a plain double for width 1. No include guard: each kernel
// translation unit includes it once, inside its own namespace.
#ifndef POSEMORPH_KERNEL_WIDTH
#error "define POSEMORPH_KERNEL_WIDTH before including vec.h"
#endif

// Every helper is forced inline: the same helper compiled for two instruction
// sets must never be merged into one out-of-line copy.
#if defined(_MSC_VER) && !defined(__clang__)
#define POSEMORPH_KERNEL_INLINE __forceinline
#else
#define POSEMORPH_KERNEL_INLINE inline __attribute__((always_inline))
#endif

constexpr int kWidth = POSEMORPH_KERNEL_WIDTH;

#if POSEMORPH_KERNEL_WIDTH == 1
typedef double Vec;
POSEMORPH_KERNEL_INLINE Vec Broadcast(double v) { return v; }
POSEMORPH_KERNEL_INLINE Vec LoadVec(const double* p) { return *p; }
POSEMORPH_KERNEL_INLINE void StoreVec(double* p, Vec v) { *p = v; }
#else
typedef double Vec __attribute__((vector_size(POSEMORPH_KERNEL_WIDTH * sizeof(double))));
POSEMORPH_KERNEL_INLINE Vec Broadcast(double v) { return Vec{} + v; }
POSEMORPH_KERNEL_INLINE Vec LoadVec(const double* p) {
  Vec v;
  std::memcpy(&v, p, sizeof(v));
  return v;
}
POSEMORPH_KERNEL_INLINE void StoreVec(double* p, Vec v) { std::memcpy(p, &v, sizeof(v)); }
#endif
