// SPDX-License-Identifier: MIT
// The scalar path (1 double per vector); its compiler flags are set in runtime/CMakeLists.txt.
#define POSEMORPH_KERNEL_WIDTH 1
#define POSEMORPH_KERNEL_NAMESPACE scalar
#define POSEMORPH_KERNEL_ISA kScalar
#include "frame_kernels.h"
