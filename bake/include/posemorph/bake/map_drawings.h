// SPDX-License-Identifier: MIT
// Step 1 of the bake: drawn poses (a PNG or SVG drawing, or an outline, with
// landmarks) become compatible meshes by N-way mapping (DESIGN.md section 4;
// the stages are in bake/include/posemorph/bake/mapping/).
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "posemorph/bake/pose_meshes.h"
#include "posemorph/bake/rig_description.h"

namespace posemorph::bake {

// What mapping made, for the bake report and the closing figures.
struct MappingReport {
  bool mapped = false;
  std::vector<std::size_t> outline_vertices;  // per drawn pose, as extracted
  std::size_t matched_vertices = 0;           // corresponding boundary points before simplification
  std::size_t boundary_vertices = 0;          // after simplification
  std::size_t steiner_points = 0;             // interior points the compatible triangulation added
  std::size_t vertices = 0, triangles = 0;    // after refinement
  double min_angle_degrees = 0;               // over all triangles and drawn poses
  double simplification_error = 0;            // drawing units
  double seconds = 0;
  std::vector<std::string> warnings;  // "FILE: ...", e.g. specks dropped from a drawing
};

struct MappedDrawings {
  Triangles triangles;             // shared by every drawn pose; empty when none is drawn
  std::vector<std::size_t> poses;  // the drawn poses' indices in the description
  std::vector<PoseMesh> meshes;    // one per entry of `poses`: vertices, uvs into its drawing, image, canvas
  MappingReport report;
};

// Outlines, boundary matching, enclosing simplification, compatible
// triangulation and refinement of every drawn pose of `description` that has
// no vertices. Returns nothing mapped when no pose is drawn. Throws BakeError
// naming the file, the pose and the problem.
MappedDrawings MapDrawings(const RigDescription& description);

}  // namespace posemorph::bake
