// SPDX-License-Identifier: MIT
// posemorph-bake import FILE... -o DIR [--flatten]: a character's layered
// files (OpenRaster, Photoshop) as the PNG drawings a description names,
// one per part and pose (POSE-PART.png) or one per pose (POSE.png); and
// import SHEET.png -o DIR --frames CxR | --cell WxH [--name NAME]: a sprite
// sheet's frames, one PNG each (NAME_K.png).
#include "import_command.h"

#include <cctype>
#include <filesystem>
#include <string>

#include "command_args.h"
#include "commands.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/import/layered_image.h"
#include "posemorph/bake/import/sprite_sheet.h"
#include "posemorph/bake/input_file.h"
#include "posemorph/bake/output_file.h"

namespace posemorph::bake::cli {

namespace fs = std::filesystem;

std::vector<std::string> WriteLayeredCharacter(const import::LayeredCharacter& c, const std::string& folder,
                                               bool overwrite, std::ostream& warnings) {
  for (const std::string& note : c.notes) warnings << "posemorph-bake: warning: " << Printable(note) << "\n";
  return import::WriteLayeredDrawings(c, folder, overwrite);
}

namespace {

// "AxB": two whole numbers in 1..16384, for `option`.
void ReadPair(const std::string& option, const std::string& text, int* a, int* b) {
  const std::size_t x = text.find('x');
  auto number = [&](const std::string& s) {
    if (s.empty() || s.size() > 5 || s.find_first_not_of("0123456789") != std::string::npos) return 0;
    const int n = std::stoi(s);
    return n <= 16384 ? n : 0;
  };
  *a = x == std::string::npos ? 0 : number(text.substr(0, x));
  *b = x == std::string::npos ? 0 : number(text.substr(x + 1));
  if (*a < 1 || *b < 1) throw UsageError(option + " takes AxB, two whole numbers in 1..16384 (" + text + ")");
}

bool IsPng(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".png";
}

}  // namespace

int ImportCommand(const Arguments& a, std::size_t from, std::ostream& out, std::ostream& err) {
  std::string output, name;
  bool flatten = false;
  import::SheetCut cut;
  std::vector<std::string> files;
  for (std::size_t i = from; i < a.size(); ++i) {
    if (a[i] == "-o" || a[i] == "--frames" || a[i] == "--cell" || a[i] == "--name") {
      if (i + 1 >= a.size()) throw UsageError(a[i] + " needs a value");
      const std::string& v = a[++i];
      if (a[i - 1] == "-o") output = v;
      if (a[i - 1] == "--name") name = v;
      if (a[i - 1] == "--frames") ReadPair("--frames", v, &cut.columns, &cut.rows);
      if (a[i - 1] == "--cell") ReadPair("--cell", v, &cut.cell_width, &cut.cell_height);
    } else if (a[i] == "--flatten") {
      flatten = true;
    } else if (!a[i].empty() && a[i][0] == '-') {
      throw UsageError("unknown option " + a[i]);
    } else {
      files.push_back(a[i]);
    }
  }
  if (output.empty()) throw UsageError("import needs -o DIR (the folder the drawings are written to)");
  if (files.empty()) throw UsageError("import needs a layered file (.ora or .psd) or a sprite sheet (.png)");
  const bool sheet = files.size() == 1 && IsPng(files[0]);
  const bool cutting = cut.columns > 0 || cut.cell_width > 0;
  if (sheet) {
    if (!cutting) throw UsageError("a sprite sheet is cut by --frames COLUMNSxROWS or --cell WIDTHxHEIGHT");
    if (cut.columns > 0 && cut.cell_width > 0) throw UsageError("--frames and --cell cut a sheet two ways: give one");
    if (flatten) throw UsageError("--flatten is for layered files; a sprite sheet's frames are flat");
  } else if (cutting || !name.empty()) {
    throw UsageError("--frames, --cell and --name cut one sprite sheet (.png)");
  }
  if (fs::exists(output) && !fs::is_directory(output)) throw BakeError(output, "is not a folder");
  if (sheet) {
    const import::LayeredCharacter c =
        import::ImportSpriteSheet(files[0], cut, name.empty() ? fs::path(files[0]).stem().string() : name);
    std::error_code ec;
    fs::create_directories(output, ec);
    if (ec) throw BakeError(output, "cannot create the folder: " + ec.message());
    const std::vector<std::string> written = WriteLayeredCharacter(c, output, true, err);
    out << "wrote " << written.size() << (written.size() == 1 ? " frame" : " frames") << " of " << c.width << " x "
        << c.height << " pixels to " << output << ": " << fs::path(written.front()).filename().string()
        << (written.size() > 1 ? " .. " + fs::path(written.back()).filename().string() : "") << "\n";
    return 0;
  }
  for (const std::string& f : files)
    if (!import::IsLayeredImagePath(f))
      throw BakeError(f, "not a layered file import reads (.ora or .psd); a sprite sheet (.png) is imported alone");
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
