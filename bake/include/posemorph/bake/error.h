// SPDX-License-Identifier: MIT
// The bake's one error type: which file, and what is wrong with it.
#pragma once
#include <stdexcept>
#include <cstddef>
#include <string>

namespace posemorph::bake {

class BakeError : public std::runtime_error {
 public:
  BakeError(std::string file, const std::string& problem)
      : std::runtime_error(file.empty() ? problem : file + ": " + problem), file_(std::move(file)) {}
  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

// How every message names a pose: "pose 'NAME' (index I)", I its index in the
// description.
inline std::string PoseLabel(const std::string& name, std::size_t index) {
  return "pose '" + name + "' (index " + std::to_string(index) + ")";
}

}  // namespace posemorph::bake
