// SPDX-License-Identifier: MIT
// Writing the tools' outputs so that nothing is ever half-written.
#pragma once
#include <string>
#include <vector>

namespace posemorph::bake {

// Writes bytes to path via a temporary file in the same folder and a rename,
// so readers never see a partial file. Throws BakeError.
void WriteFileAtomic(const std::string& path, const std::vector<unsigned char>& bytes);

}  // namespace posemorph::bake
