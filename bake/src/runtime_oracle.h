// SPDX-License-Identifier: MIT
// The bake's one door to the runtime's loader. The runtime is the oracle for
// what a rig's bytes mean: the verification of what the bake writes
// (reproduction_check.cpp, and the file of a character with channels) and
// the compact search, which measures each trial encoding with the runtime
// (compact_rig.cpp), load through here; no other step of the bake reads
// bytes it wrote.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "posemorph/rig.h"

namespace posemorph::bake {

// The rig those bytes hold, as the runtime loads them; false (with the
// loader's message in *message when given) when they do not load.
bool LoadWithRuntime(const std::vector<unsigned char>& bytes, Rig* rig, std::string* message = nullptr);

// As above, but a rig that does not load throws BakeError(file, what + ": " + the loader's message).
Rig LoadWithRuntime(const std::vector<unsigned char>& bytes, const std::string& file, const std::string& what);

// Memory kept from one load to the next (LoadRigInPlace): a search that
// loads rig after rig of one size faults its arena in once, not once per
// load. A rig loaded here is valid until the next Load.
class RuntimeArena {
 public:
  bool Load(const std::vector<unsigned char>& bytes, Rig* rig);

 private:
  struct alignas(16) Chunk {
    unsigned char bytes[16];
  };
  std::unique_ptr<Chunk[]> memory_;  // not cleared: the loader writes what it reads
  std::size_t chunks_ = 0;
};

}  // namespace posemorph::bake
