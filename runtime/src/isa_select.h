// SPDX-License-Identifier: MIT
// Choosing a rig's kernel path at load.
#pragma once
#include <cstdio>

#include "kernels/kernel_table.h"
#include "posemorph/error.h"
#include "posemorph/isa.h"

namespace posemorph::detail {

// Resolves `requested` (kAuto: POSEMORPH_ISA if set, else BestIsa()) to a
// table. False, with kUnsupportedIsa and a message, for an unknown
// POSEMORPH_ISA or a path this build or CPU cannot run.
bool SelectKernels(Isa requested, const KernelTable** out, Error* err);

// The available paths' names, space-separated.
const char* AvailableIsaNames();

}  // namespace posemorph::detail
