// SPDX-License-Identifier: MIT
// The rig as meshes: one triangle list and every pose's vertices, uvs and
// drawing. The first two steps of the bake make it from a description
// (map_drawings.h, deform_poses.h); every later step reads it.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "posemorph/bake/rig_description.h"
#include "posemorph/bake/triangle_math.h"

namespace posemorph::bake {

struct PoseMesh {
  std::string name;
  Eigen::Vector2d point = Eigen::Vector2d::Zero();  // in pose space
  Points vertices;
  std::vector<Eigen::Vector2f> uvs;  // empty, or one per vertex
  std::string image;                 // reference written into the rig
  // The drawing's canvas and where the rig origin sits on it (drawing units,
  // y down); zero when the pose has no drawing.
  Eigen::Vector2d canvas_size = Eigen::Vector2d::Zero(), canvas_pivot = Eigen::Vector2d::Zero();
};

// A layered character's part in the joined mesh (join_parts.h): a run of
// the triangles, drawn in order with its own drawings.
struct MeshPart {
  std::string name;
  int order = 0;                 // pose 0's when pose_orders is given
  std::vector<int> pose_orders;  // empty: fixed; else one per pose
  std::uint32_t first_triangle = 0, triangle_count = 0;
  std::vector<std::string> images;  // per pose, as written into the rig
};

struct PoseMeshes {
  Triangles triangles;
  std::vector<PoseMesh> poses;  // in the description's order
  std::vector<MeshPart> parts;  // empty: one shape, drawn with the poses' images
};

// The description's poses as they are, drawn or deformed ones without vertices
// included (what the later steps fill in).
PoseMeshes GivenPoseMeshes(const RigDescription& description);

// The description with every pose given as vertices (drawings, deformations
// and their outlines replaced by the meshes): what `posemorph-bake deform`
// writes, and what a test compares with. A description holds no canvases: a
// rig baked from it has none (its frames are the same).
RigDescription WithPoseMeshes(const RigDescription& description, const PoseMeshes& meshes);

}  // namespace posemorph::bake
