#include "ldlt_solve.h"

#include "morph_kernel.h"

namespace posemorph::detail {

// Cloned like the frame kernels, so that it measures what a frame runs.
__attribute__((target_clones("avx512f", "avx2", "default")))
void SolvePinned(const Factor& factor, const double* b, double* scratch, double* x) {
  SolvePinnedKernel<double>(factor, b, scratch, x);
}

}  // namespace posemorph::detail
