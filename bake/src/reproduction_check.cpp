// SPDX-License-Identifier: MIT
#include "posemorph/bake/reproduction_check.h"

#include <algorithm>

#include "posemorph/bake/error.h"
#include "posemorph/bake/pose_space_samples.h"
#include "posemorph/bake/serialise_rig.h"
#include "runtime_oracle.h"

namespace posemorph::bake {

ReproductionCheck CheckReproduction(const std::vector<unsigned char>& bytes, const PoseMeshes& meshes, double tolerance,
                                    const std::string& file) {
  ReproductionCheck check;
  check.rig = LoadWithRuntime(bytes, file, "internal error: the baked rig does not load");
  std::vector<double> x;
  double worst = 0;
  for (const PoseMesh& pose : meshes.poses) {
    if (!EvaluateFrame(check.rig, pose.point, x))
      throw BakeError(file, "internal error: the baked rig does not evaluate");
    for (std::size_t v = 0; v < pose.vertices.size(); ++v)
      worst = std::max(worst, (Eigen::Vector2d(x[2 * v], x[2 * v + 1]) - pose.vertices[v]).norm());
  }
  check.max_error = worst / RigBoundingBoxDiagonal(meshes);
  if (!(check.max_error <= tolerance))
    throw BakeError(file, "internal error: the baked rig reproduces its poses only to " +
                              std::to_string(check.max_error) + " of its size");
  return check;
}

}  // namespace posemorph::bake
