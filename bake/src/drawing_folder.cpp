// SPDX-License-Identifier: MIT
#include "posemorph/bake/drawing_folder.h"

#include <filesystem>
#include <system_error>

namespace posemorph::bake {

std::string DefaultDrawingFolder(const std::string& rig_file, const Rig& rig) {
  std::string rig_folder = std::filesystem::path(rig_file).parent_path().generic_string();
  if (rig_folder.empty()) rig_folder = ".";
  const StringView recorded = rig.drawing_folder();
  if (recorded.size == 0) return rig_folder;
  const std::string folder(recorded.data, recorded.size);
  // The bake writes a relative '/'-separated path; anything else is not its.
  if (folder.front() == '/' || folder.find_first_of("\\:") != std::string::npos) return rig_folder;
  for (const char c : folder)
    if (static_cast<unsigned char>(c) < 0x20) return rig_folder;
  const std::string joined = rig_folder + "/" + folder;
  std::error_code ec;
  return std::filesystem::is_directory(joined, ec) ? joined : rig_folder;
}

}  // namespace posemorph::bake
