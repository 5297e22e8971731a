// SPDX-License-Identifier: MIT
// The avx512 path (8 doubles per vector); its compiler flags are set in runtime/CMakeLists.txt.
#define POSEMORPH_KERNEL_WIDTH 8
#define POSEMORPH_KERNEL_NAMESPACE avx512
#define POSEMORPH_KERNEL_ISA kAvx512
#include "frame_kernels.h"
