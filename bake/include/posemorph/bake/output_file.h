// SPDX-License-Identifier: MIT
// Writing the tools' outputs so that nothing is ever half-written.
#pragma once
#include <optional>
#include <string>
#include <vector>

namespace posemorph::bake {

// What is wrong with `path` as the name of a file to write, before anything
// is done: an empty name, or a file name longer than the file system allows
// (255 bytes). Nothing when it may be written.
std::optional<std::string> OutputNameProblem(const std::string& path);

// A path as messages show it: whole up to 80 bytes, else its first 60 and its length.
std::string ShownPath(const std::string& path);

// Writes bytes to path via a temporary file in the same folder and a rename,
// so readers never see a partial file. Throws BakeError naming the path and
// the cause (the system's text: "No space left on device", "File too large",
// "Permission denied", ...); the temporary is removed on every failure. A
// write past the process's file-size limit (ulimit -f) fails with "File too
// large" instead of killing the process: SIGXFSZ is held for the calling
// thread while it writes, and taken back.
void WriteFileAtomic(const std::string& path, const std::vector<unsigned char>& bytes);

}  // namespace posemorph::bake
