// SPDX-License-Identifier: MIT
#include "posemorph/bake/reproduction_check.h"

#include <algorithm>

#include "posemorph/bake/error.h"
#include "posemorph/bake/pose_space_samples.h"
#include "posemorph/bake/serialise_rig.h"
#include "runtime_oracle.h"

namespace posemorph::bake {

double MeasureReproduction(const Rig& rig, const PoseMeshes& meshes, double tolerance, const std::string& file,
                           const std::string& what) {
  const std::string subject = what.empty() ? "the baked rig" : "the baked rig's " + what;
  if (rig.pose_count() != meshes.poses.size())
    throw BakeError(file, "internal error: " + subject + " does not hold the poses and vertices baked");
  std::vector<double> x;
  double worst = 0;
  for (const PoseMesh& pose : meshes.poses) {
    if (rig.vertex_count() != pose.vertices.size())
      throw BakeError(file, "internal error: " + subject + " does not hold the poses and vertices baked");
    if (!EvaluateFrame(rig, pose.point, x)) throw BakeError(file, "internal error: " + subject + " does not evaluate");
    for (std::size_t v = 0; v < pose.vertices.size(); ++v)
      worst = std::max(worst, (Eigen::Vector2d(x[2 * v], x[2 * v + 1]) - pose.vertices[v]).norm());
  }
  const double error = worst / RigBoundingBoxDiagonal(meshes);
  if (!(error <= tolerance))
    throw BakeError(
        file, "internal error: " + subject + " reproduces its poses only to " + std::to_string(error) + " of its size");
  return error;
}

ReproductionCheck CheckReproduction(const std::vector<unsigned char>& bytes, const PoseMeshes& meshes, double tolerance,
                                    const std::string& file) {
  ReproductionCheck check;
  check.rig = LoadWithRuntime(bytes, file, "internal error: the baked rig does not load");
  check.max_error = MeasureReproduction(check.rig, meshes, tolerance, file, "");
  check.tolerance = tolerance;
  return check;
}

}  // namespace posemorph::bake
