// SPDX-License-Identifier: MIT
#include "posemorph/bake/orient_triangles.h"

#include <utility>

namespace posemorph::bake {

Triangles OrientTriangles(const PoseMeshes& meshes) {
  Triangles triangles = meshes.triangles;
  if (meshes.poses.empty()) return triangles;
  const Points& rest = meshes.poses[0].vertices;
  double total = 0;
  for (const auto& t : triangles)
    if (t[0] < rest.size() && t[1] < rest.size() && t[2] < rest.size()) total += SignedArea(rest, t);
  if (total < 0)
    for (auto& t : triangles) std::swap(t[1], t[2]);
  return triangles;
}

}  // namespace posemorph::bake
