// SPDX-License-Identifier: MIT
// posemorph-bake import FILE... -o DIR [--flatten]: a character's layered
// files (OpenRaster, Photoshop) as the PNG drawings a description names,
// one per part and pose (POSE-PART.png) or one per pose (POSE.png).
#include "import_command.h"

#include <filesystem>

#include "command_args.h"
#include "commands.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/import/layered_image.h"
#include "posemorph/bake/input_file.h"
#include "posemorph/bake/output_file.h"

namespace posemorph::bake::cli {

namespace fs = std::filesystem;

std::vector<std::string> WriteLayeredCharacter(const import::LayeredCharacter& c, const std::string& folder,
                                               bool overwrite, std::ostream& warnings) {
  for (const std::string& note : c.notes) warnings << "posemorph-bake: warning: " << Printable(note) << "\n";
  return import::WriteLayeredDrawings(c, folder, overwrite);
}

int ImportCommand(const Arguments& a, std::size_t from, std::ostream& out, std::ostream& err) {
  std::string output;
  bool flatten = false;
  std::vector<std::string> files;
  for (std::size_t i = from; i < a.size(); ++i) {
    if (a[i] == "-o") {
      if (i + 1 >= a.size()) throw UsageError("-o needs a value");
      output = a[++i];
    } else if (a[i] == "--flatten") {
      flatten = true;
    } else if (!a[i].empty() && a[i][0] == '-') {
      throw UsageError("unknown option " + a[i]);
    } else {
      files.push_back(a[i]);
    }
  }
  if (output.empty()) throw UsageError("import needs -o DIR (the folder the drawings are written to)");
  if (files.empty()) throw UsageError("import needs a layered file (.ora or .psd)");
  for (const std::string& f : files)
    if (!import::IsLayeredImagePath(f)) throw BakeError(f, "not a layered file import reads (.ora or .psd)");
  if (fs::exists(output) && !fs::is_directory(output)) throw BakeError(output, "is not a folder");
  const import::LayeredCharacter c = import::ImportLayeredCharacter(files, flatten);
  std::error_code ec;
  fs::create_directories(output, ec);
  if (ec) throw BakeError(output, "cannot create the folder: " + ec.message());
  const std::vector<std::string> written = WriteLayeredCharacter(c, output, true, err);
  out << "wrote " << written.size() << " drawings of " << c.width << " x " << c.height << " pixels to " << output
      << ": " << c.poses.size() << (c.poses.size() == 1 ? " pose" : " poses");
  if (!c.parts.empty()) out << " of " << c.parts.size() << " parts (POSE-PART.png)";
  out << "\n";
  return 0;
}

}  // namespace posemorph::bake::cli
