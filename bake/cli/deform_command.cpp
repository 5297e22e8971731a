// SPDX-License-Identifier: MIT
// posemorph-bake deform RIG.json --pose NAME: a deformation-made pose as a mesh file.
#include "commands.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "command_args.h"
#include "posemorph/bake/bake.h"
#include "posemorph/bake/deform_poses.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/input_file.h"
#include "posemorph/bake/stage.h"
#include "posemorph/path.h"
#include "posemorph/rig.h"
#include "posemorph/rig_format.h"
#include "preview.h"
#include "textured_sheet.h"

namespace posemorph::bake::cli {

int DeformCommand(const std::vector<std::string>& a, std::size_t from, std::ostream& out) {
  const Args args = Args::Parse(a, from, {"-o", "--pose"}, {});
  if (args.positional.empty()) throw UsageError("no rig description given");
  const std::string *output = args.Get("-o"), *name = args.Get("--pose");
  if (!output || !name) throw UsageError("deform needs --pose NAME and -o MESH.json");
  const RigDescription rig = ReadRigDescription(args.positional);
  const PoseMeshes meshes = ResolvePoseMeshes(rig);
  const auto it =
      std::find_if(rig.poses.begin(), rig.poses.end(), [&](const PoseDescription& p) { return p.name == *name; });
  if (it == rig.poses.end()) throw BakeError(args.positional, "has no pose named '" + *name + "'");
  const Points& vertices = meshes.poses[std::size_t(it - rig.poses.begin())].vertices;
  // The same mesh-file format a description's "mesh" reads, so the pose can be
  // edited by hand and used in place of its "deform" entry.
  std::ostringstream json;
  json.precision(17);
  json << "{\"vertices\": [";
  for (std::size_t v = 0; v < vertices.size(); ++v)
    json << (v ? ", [" : "[") << vertices[v].x() << ", " << vertices[v].y() << "]";
  json << "],\n \"triangles\": [";
  for (std::size_t t = 0; t < meshes.triangles.size(); ++t)
    json << (t ? ", [" : "[") << meshes.triangles[t][0] << ", " << meshes.triangles[t][1] << ", "
         << meshes.triangles[t][2] << "]";
  json << "]}\n";
  WriteText(*output, json.str());
  out << "wrote " << *output << " (pose '" << *name << "', " << vertices.size() << " vertices"
      << (it->deformed ? ", made from '" + it->deform.from + "'" : std::string(", given directly")) << ")\n";
  return 0;
}

}  // namespace posemorph::bake::cli
