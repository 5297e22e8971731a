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

// Whom an error names, so that the step that finds a problem throws it
// complete and nobody catches it to add the file or the pose: the file (the
// rig description, or a drawing read on its own), the place within it
// ("pose 'arm' (index 3)", then a drawing's path), and a note on why the
// input is as it is, appended in parentheses.
struct ErrorSource {
  std::string file, place, note;
  // Implicit: a file name is a source.
  ErrorSource(std::string file_name = "") : file(std::move(file_name)) {}
  ErrorSource(const char* file_name) : file(file_name) {}
  ErrorSource(std::string file_name, std::string place_in_it, std::string why = "")
      : file(std::move(file_name)), place(std::move(place_in_it)), note(std::move(why)) {}
  // BakeError(file, "PLACE: problem (note)").
  BakeError Error(const std::string& problem) const {
    return BakeError(file,
                     (place.empty() ? problem : place + ": " + problem) + (note.empty() ? "" : " (" + note + ")"));
  }
};

// How every message names a pose: "pose 'NAME' (index I)", I its index in the
// description.
inline std::string PoseLabel(const std::string& name, std::size_t index) {
  return "pose '" + name + "' (index " + std::to_string(index) + ")";
}

}  // namespace posemorph::bake
