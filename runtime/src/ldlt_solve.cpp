#include "ldlt_solve.h"

#include "morph_kernel.h"

namespace posemorph::detail {

void SolvePinned(const Factor& factor, const double* b, double* scratch, double* x) {
  SolvePinnedKernel<double>(factor, b, scratch, x);
}

}  // namespace posemorph::detail
