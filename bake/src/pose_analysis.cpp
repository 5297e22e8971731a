// SPDX-License-Identifier: MIT
#include "posemorph/bake/pose_analysis.h"

#include <cmath>

namespace posemorph::bake {

PoseAnalysis AnalysePoses(const PoseMeshes& rig) {
  const std::size_t T = rig.triangles.size(), N = rig.poses.size();
  const auto neighbours = EdgeNeighbours(rig.triangles);
  PoseAnalysis out;
  out.angles.assign(T * N, 0);
  out.stretches.assign(T * N * 3, 0);
  std::vector<Eigen::Matrix2d> rest_inverse(T);
  std::vector<double> rest_areas(T);
  for (std::size_t t = 0; t < T; ++t) {
    rest_inverse[t] = EdgeMatrix(rig.poses[0].vertices, rig.triangles[t]).inverse();
    rest_areas[t] = std::abs(SignedArea(rig.poses[0].vertices, rig.triangles[t]));
  }
  std::vector<double> pose_angles(T);
  for (std::size_t i = 0; i < N; ++i) {
    std::vector<Eigen::Matrix2d> S(T);
    for (std::size_t t = 0; t < T; ++t) {
      const PolarSplit split = PolarDecompose(EdgeMatrix(rig.poses[i].vertices, rig.triangles[t]) * rest_inverse[t]);
      pose_angles[t] = split.alpha;
      S[t] = split.S;
    }
    UnwrapAngles(neighbours, rest_areas, pose_angles);
    for (std::size_t t = 0; t < T; ++t) {
      out.angles[t * N + i] = pose_angles[t];
      out.stretches[(t * N + i) * 3 + 0] = S[t](0, 0);
      out.stretches[(t * N + i) * 3 + 1] = S[t](0, 1);
      out.stretches[(t * N + i) * 3 + 2] = S[t](1, 1);
    }
  }
  return out;
}

}  // namespace posemorph::bake
