// SPDX-License-Identifier: MIT
// posemorph-bake outline RIG.json -o DIR: per drawn pose, a picture of what
// the bake traces and meshes (outline_picture.h), so a landmark can be put on
// the outline the bake uses.
#include <filesystem>

#include "command_args.h"
#include "commands.h"
#include "outline_picture.h"
#include "posemorph/bake/bake.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/join_parts.h"
#include "posemorph/bake/map_drawings.h"
#include "posemorph/bake/rig_description.h"

namespace posemorph::bake::cli {
namespace {

// DIR/NAME.png for a pose, NAME made of the pose name's letters, digits, '-' and '_'.
std::string PicturePath(const std::string& dir, const PoseDescription& pose, std::size_t index) {
  std::string name;
  for (char c : pose.name) name += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_') ? c : '_';
  if (name.empty()) name = "pose";
  return (std::filesystem::path(dir) / (std::to_string(index) + "-" + name + ".png")).string();
}

}  // namespace

int OutlineCommand(const std::vector<std::string>& a, std::size_t from, std::ostream& out, std::ostream& err) {
  const Args args = Args::Parse(a, from, {"-o", "--part"}, {});
  if (args.positional.empty()) throw UsageError("no rig description given");
  const std::string* dir = args.Get("-o");
  if (!dir) throw UsageError("outline needs -o DIR (a folder for one picture per drawn pose)");
  std::error_code ec;
  if (!std::filesystem::is_directory(*dir, ec)) throw BakeError(*dir, "is not a folder (create it first)");
  RigDescription rig = ReadRigDescription(args.positional);
  // A layered character: one part's drawings at a time (--part NAME).
  const std::string* part = args.Get("--part");
  if (!rig.parts.empty() || part) {
    std::string names;
    for (const PartDescription& p : rig.parts) names += (names.empty() ? "'" : ", '") + p.name + "'";
    std::size_t index = rig.parts.size();
    for (std::size_t p = 0; part && p < rig.parts.size(); ++p)
      if (rig.parts[p].name == *part) index = p;
    if (rig.parts.empty()) throw BakeError(args.positional, "has no parts (--part is for a layered character)");
    if (!part) throw BakeError(args.positional, "has parts: trace one with --part NAME (" + names + ")");
    if (index == rig.parts.size()) throw BakeError(args.positional, "has no part '" + *part + "' (" + names + ")");
    rig = PartRigDescription(rig, index);
  }
  const DrawnOutlines traced = TraceDrawings(rig);
  if (traced.poses.empty()) throw BakeError(args.positional, "has no drawn pose (nothing to trace)");
  // Every picture is made before any is written: a drawing that fails leaves nothing behind.
  std::vector<std::pair<std::string, std::vector<unsigned char>>> pictures;
  for (const DrawnPoseOutline& pose : traced.poses) {
    const PoseDescription& description = rig.poses[pose.pose];
    const RgbaImage drawing = pose.png_path.empty() ? RgbaImage{} : ReadRgbaPng(pose.png_path);
    int scale = 1;
    const RgbaImage picture = OutlinePicture(pose, traced.triangles, drawing, &scale);
    const std::string path = PicturePath(*dir, description, pose.pose);
    pictures.emplace_back(path, EncodePng(picture, path));
    out << "wrote " << path << " (" << pose.label << ", x" << scale << ", " << pose.traced.size() << " outline points, "
        << pose.boundary.size() << " boundary vertices, " << pose.landmarks.size() << " landmarks"
        << (pose.features.empty() ? std::string() : ", " + std::to_string(pose.features.size()) + " features") << ")\n";
  }
  for (const auto& [path, bytes] : pictures) WriteFileAtomic(path, bytes);
  out << "cyan: the traced outline; magenta: the mesh boundary (simplify_tolerance " << traced.simplify_tolerance
      << "), grey: the mesh; discs: landmarks as given (numbered, ring: how far off the outline one may lie), "
         "white: where each lands on the outline; green: the start landmark, its arrow the way the landmarks go; "
         "amber crosses: features (numbered)\n";
  if (!traced.mapping_error.empty()) {
    err << "posemorph-bake: error: " << Printable(traced.mapping_error)
        << " (the pictures show the outlines and landmarks as traced)\n";
    return 1;
  }
  return 0;
}

}  // namespace posemorph::bake::cli
