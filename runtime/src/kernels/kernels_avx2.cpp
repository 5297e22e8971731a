// SPDX-License-Identifier: MIT
// The avx2 path (4 doubles per vector); its compiler flags are set in runtime/CMakeLists.txt.
#define POSEMORPH_KERNEL_WIDTH 4
#define POSEMORPH_KERNEL_NAMESPACE avx2
#define POSEMORPH_KERNEL_ISA kAvx2
#include "frame_kernels.h"
