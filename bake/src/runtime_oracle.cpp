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

}  // namespace posemorph::bake
