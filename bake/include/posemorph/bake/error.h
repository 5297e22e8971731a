// SPDX-License-Identifier: MIT
// The bake's one error type: which file, and what is wrong with it.
#pragma once
#include <stdexcept>
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

}  // namespace posemorph::bake
