// SPDX-License-Identifier: MIT
// posemorph-bake deform RIG.json --pose NAME: a deformation-made pose as a mesh file.
#include "commands.h"

#include <algorithm>

#include "command_args.h"
#include "posemorph/bake/deform_poses.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/rig_description.h"

namespace posemorph::bake::cli {

int DeformCommand(const std::vector<std::string>& a, std::size_t from, std::ostream& out) {
  const Args args = Args::Parse(a, from, {"-o", "--pose"}, {});
  if (args.positional.empty()) throw UsageError("no rig description given");
  const std::string *output = args.Get("-o"), *name = args.Get("--pose");
  if (!output || !name) throw UsageError("deform needs --pose NAME and -o MESH.json");
  const RigDescription rig = ReadRigDescription(args.positional);
  if (!rig.parts.empty())
    throw BakeError(args.positional, "has parts: deform makes poses of one shape (parts cannot be deformed yet)");
  const PoseMeshes meshes = ResolvePoseMeshes(rig);
  const auto it =
      std::find_if(rig.poses.begin(), rig.poses.end(), [&](const PoseDescription& p) { return p.name == *name; });
  if (it == rig.poses.end()) throw BakeError(args.positional, "has no pose named '" + *name + "'");
  const Points& vertices = meshes.poses[std::size_t(it - rig.poses.begin())].vertices;
  // The mesh-file format a description's "mesh" reads, so the pose can be
  // edited and used in place of its "deform" entry.
  WriteText(*output, MeshFileText(vertices, meshes.triangles));
  out << "wrote " << *output << " (pose '" << *name << "', " << vertices.size() << " vertices"
      << (it->deformed ? ", made from '" + it->deform.from + "'" : std::string(", given directly")) << ")\n";
  return 0;
}

}  // namespace posemorph::bake::cli
