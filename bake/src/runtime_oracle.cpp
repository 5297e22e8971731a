// SPDX-License-Identifier: MIT
#include "runtime_oracle.h"

#include "posemorph/bake/error.h"

namespace posemorph::bake {

bool LoadWithRuntime(const std::vector<unsigned char>& bytes, Rig* rig, std::string* message) {
  Error err;
  if (!bytes.empty() && LoadRig(bytes.data(), bytes.size(), rig, &err)) return true;
  if (message) *message = bytes.empty() ? std::string("no bytes") : err.message;
  return false;
}

Rig LoadWithRuntime(const std::vector<unsigned char>& bytes, const std::string& file, const std::string& what) {
  Rig rig;
  std::string message;
  if (!LoadWithRuntime(bytes, &rig, &message)) throw BakeError(file, what + ": " + message);
  return rig;
}

bool RuntimeArena::Load(const std::vector<unsigned char>& bytes, Rig* rig) {
  std::size_t needed = 0;
  Error err;
  if (bytes.empty() || !RigMemorySize(bytes.data(), bytes.size(), &needed, &err)) return false;
  const std::size_t chunks = (needed + sizeof(Chunk) - 1) / sizeof(Chunk);
  if (chunks_ < chunks) memory_.reset(new Chunk[chunks]), chunks_ = chunks;
  return LoadRigInPlace(bytes.data(), bytes.size(), memory_.get(), chunks_ * sizeof(Chunk), rig, &err);
}

}  // namespace posemorph::bake
