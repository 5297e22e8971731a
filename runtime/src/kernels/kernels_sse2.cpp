// SPDX-License-Identifier: MIT
// The sse2 path (2 doubles per vector); its compiler flags are set in runtime/CMakeLists.txt.
#define POSEMORPH_KERNEL_WIDTH 2
#define POSEMORPH_KERNEL_NAMESPACE sse2
#define POSEMORPH_KERNEL_ISA kSse2
#include "frame_kernels.h"
