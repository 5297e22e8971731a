// SPDX-License-Identifier: MIT
#include "posemorph/bake/pose_meshes.h"

namespace posemorph::bake {

PoseMeshes GivenPoseMeshes(const RigDescription& description) {
  PoseMeshes meshes;
  meshes.triangles = description.triangles;
  for (const PoseDescription& p : description.poses) {
    PoseMesh m;
    m.name = p.name;
    m.point = p.point;
    m.vertices = p.vertices;
    m.uvs = p.uvs;
    m.image = p.image;
    meshes.poses.push_back(std::move(m));
  }
  return meshes;
}

RigDescription WithPoseMeshes(const RigDescription& description, const PoseMeshes& meshes) {
  RigDescription out = description;
  out.triangles = meshes.triangles;
  for (std::size_t i = 0; i < out.poses.size() && i < meshes.poses.size(); ++i) {
    PoseDescription& p = out.poses[i];
    const PoseMesh& m = meshes.poses[i];
    p.vertices = m.vertices;
    p.uvs = m.uvs;
    p.image = m.image;
    p.deformed = false;
    p.deform = DeformDescription{};
    p.drawn = false;
    p.drawing.clear();
    p.drawing_path.clear();
    p.outline.clear();
    p.landmarks.clear();
    p.origin = Eigen::Vector2d::Zero();
  }
  return out;
}

}  // namespace posemorph::bake
