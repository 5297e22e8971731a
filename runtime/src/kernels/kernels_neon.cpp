// SPDX-License-Identifier: MIT
// The neon path (2 doubles per vector); its compiler flags are set in runtime/CMakeLists.txt.
#define POSEMORPH_KERNEL_WIDTH 2
#define POSEMORPH_KERNEL_NAMESPACE neon
#define POSEMORPH_KERNEL_ISA kNeon
#include "frame_kernels.h"
