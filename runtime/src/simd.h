// Lanes of doubles as GCC/Clang vector types: arithmetic on them is the same
// IEEE operation per lane as on a plain double, so a kernel written once over
// `double` and over `Lanes` gives bit-identical results per lane at any width
// and on any instruction set (contraction into FMA is off for the runtime).
#pragma once
#include <cstring>

namespace posemorph::detail {

// Every helper that takes or returns Lanes is forced inline: the kernels are
// compiled once per instruction set (target_clones), and an out-of-line call
// between code built for different sets would pass the vectors by different
// ABIs (GCC's -Wpsabi note), which breaks unoptimised builds.
#define POSEMORPH_LANES_INLINE inline __attribute__((always_inline))

constexpr int kLanes = 8;
typedef double Lanes __attribute__((vector_size(kLanes * sizeof(double))));

POSEMORPH_LANES_INLINE Lanes Broadcast(double v) {
  Lanes out;
  for (int i = 0; i < kLanes; ++i) out[i] = v;
  return out;
}

POSEMORPH_LANES_INLINE Lanes Load(const double* p) {
  Lanes v;
  std::memcpy(&v, p, sizeof(v));
  return v;
}

POSEMORPH_LANES_INLINE void Store(double* p, Lanes v) { std::memcpy(p, &v, sizeof(v)); }

}  // namespace posemorph::detail
