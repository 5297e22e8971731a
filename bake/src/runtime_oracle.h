// SPDX-License-Identifier: MIT
// The bake's one door to the runtime's loader. The runtime is the oracle for
// what a rig's bytes mean: the verification of what the bake writes
// (reproduction_check.cpp, and the file of a character with channels) and
// the compact search, which measures each trial encoding with the runtime
// (compact_rig.cpp), load through here; no other step of the bake reads
// bytes it wrote.
#pragma once
#include <string>
#include <vector>

#include "posemorph/rig.h"

namespace posemorph::bake {

// The rig those bytes hold, as the runtime loads them; false (with the
// loader's message in *message when given) when they do not load.
bool LoadWithRuntime(const std::vector<unsigned char>& bytes, Rig* rig, std::string* message = nullptr);

// As above, but a rig that does not load throws BakeError(file, what + ": " + the loader's message).
Rig LoadWithRuntime(const std::vector<unsigned char>& bytes, const std::string& file, const std::string& what);

}  // namespace posemorph::bake
