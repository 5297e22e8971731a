// SPDX-License-Identifier: MIT
// Step 1 of the bake: drawn poses (a PNG or SVG drawing, or an outline, with
// landmarks) become compatible meshes by N-way mapping (DESIGN.md section 4;
// the stages are in bake/include/posemorph/bake/mapping/).
#pragma once
#include <cstddef>
#include <cstdint>
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
  std::size_t features = 0;                   // corresponding interior points given (shared vertices)
  std::size_t filled_notch_corners = 0;       // corners of thin notches filled in the PNG outlines (fill_notches)
  std::size_t vertices = 0, triangles = 0;    // after refinement
  double min_angle_degrees = 0;               // over all triangles and drawn poses (after alignment)
  double min_angle_before_alignment = 0;      // the same, as refinement left it
  double simplification_error = 0;            // drawing units
  double seconds = 0;
  // Interior alignment by the drawings (mapping/interior_alignment.h): done,
  // or why not; per drawn pose the mean colour difference (of 1) against the
  // first over its mesh, before and after; the longest move (drawing units).
  bool aligned = false;
  std::string alignment_skipped;
  std::vector<double> alignment_before, alignment_after;
  double alignment_max_move = 0, alignment_seconds = 0;
  // Per drawn pose its flat-colour regions (mapping/interior_regions.h), and
  // how many of them were paired with the first pose's (0 for the first).
  std::vector<int> regions_found, regions_matched;
  // The bake maps again, coarser, when the in-betweens fold (bake.h): the
  // mappings tried before the one written (0: the first was kept).
  int fold_retries = 0;
  // The bake refines further when the smallest angle stays below its quality
  // floor (bake.h): the smallest angle before, when the finer mesh was kept
  // (0: it was not).
  double refined_further_from = 0;
  std::string refined_further_by;  // how (map_again.cpp, kFurtherRefinements)
  // The meshes were made by deforming pose 0's mesh onto the others
  // (mapping/mesh_registration.h), and with them the smallest angle the
  // compatible triangulation gave, when the bake chose that mapping because
  // it was better (bake.h; 0: it did not).
  bool registered = false;
  double registered_over = 0;
  // The outlines were matched resisting stretch (MappingParameters::
  // stretch_cost), and the smallest angle the usual matching gave, when the
  // bake chose that mapping because it was better (0: it did not).
  double stretch_cost = 0;
  double matched_stiffer_over = 0;
  std::vector<std::string> warnings;  // "FILE: ...", e.g. specks dropped from a drawing
};

struct MappedDrawings {
  Triangles triangles;                          // shared by every drawn pose; empty when none is drawn
  std::vector<std::uint32_t> feature_vertices;  // the features' vertex ids, in the description's order
  std::vector<std::size_t> poses;               // the drawn poses' indices in the description
  std::vector<PoseMesh> meshes;  // one per entry of `poses`: vertices, uvs into its drawing, image, canvas
  MappingReport report;
};

// Outlines, boundary matching, enclosing simplification, compatible
// triangulation and refinement of every drawn pose of `description` that has
// no vertices. Returns nothing mapped when no pose is drawn. Throws BakeError
// naming the file, the pose and the problem.
MappedDrawings MapDrawings(const RigDescription& description);
// Whether some outline is traced from a PNG drawing (or, with parts, may
// be): what filling thin notches (mapping.fill_notches) can change.
bool TracesPngOutline(const RigDescription& description);

// What the mapping sees in one drawn pose, in that drawing's coordinates
// (drawing units, y down, before the pose's origin is applied): for
// `posemorph-bake outline`, so an animator can place landmarks on the
// outline the bake actually traces.
struct DrawnPoseOutline {
  std::size_t pose = 0;                    // index in the description
  std::string label;                       // "pose 'rest' (index 0)"
  std::string png_path;                    // the PNG drawing, resolved; empty for an SVG or an outline
  std::vector<Eigen::Vector2d> traced;     // the outline as traced or read, counter-clockwise as seen
  std::vector<Eigen::Vector2d> landmarks;  // as given; the first is the start point
  std::vector<Eigen::Vector2d> features;   // as given (points inside the shape)
  double landmark_distance = 0;            // how far a landmark may lie off the outline
  // From the mapping, empty when it failed: the landmarks placed on the
  // outline, the simplified (enclosing) boundary, the mesh's triangles.
  std::vector<Eigen::Vector2d> placed, boundary, vertices;
};
struct DrawnOutlines {
  std::vector<DrawnPoseOutline> poses;
  Triangles triangles;            // into each pose's `vertices`
  double simplify_tolerance = 0;  // as used (automatic values resolved)
  std::string mapping_error;      // why the mapping failed after tracing, or empty
};
// Traces every drawn pose (throws BakeError when a drawing cannot be traced)
// and then maps them; a mapping failure is returned, not thrown, with what
// was traced, since that is what an animator needs to see.
DrawnOutlines TraceDrawings(const RigDescription& description);

}  // namespace posemorph::bake
