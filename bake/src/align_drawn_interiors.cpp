// SPDX-License-Identifier: MIT
// Stage 7 of the mapping driver: the drawn interiors aligned (drawn_pose.h,
// DESIGN.md section 4).
#include <algorithm>
#include <cmath>

#include "drawing_memo.h"
#include "drawn_pose.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/mapping/interior_alignment.h"
#include "posemorph/bake/stage.h"

namespace posemorph::bake {

using mapping::Point;

// Why the drawings cannot align the interiors, or empty when they can: it
// needs two drawn poses or more, every one a PNG drawing that is also the
// texture drawn.
std::string AlignmentSkipped(const RigDescription& rig, const std::vector<DrawnPose>& drawn) {
  if (!rig.mapping.align_interiors) return "turned off (mapping.align_interiors)";
  if (drawn.size() < 2) return "one drawn pose";
  for (const DrawnPose& d : drawn) {
    const PoseDescription& pose = rig.poses[d.index];
    if (!IsRasterDrawing(pose.drawing)) return PoseLabel(pose.name, d.index) + " is not a PNG drawing";
    if (!pose.image.empty() && pose.image != pose.drawing)
      return PoseLabel(pose.name, d.index) + " draws another image than its drawing";
  }
  return "";
}

void AlignDrawnInteriors(const RigDescription& rig, const std::vector<DrawnPose>& drawn,
                         const mapping::CompatibleMesh& mesh, int working_halvings, MappedDrawings& result) {
  MappingReport& report = result.report;
  report.alignment_skipped = AlignmentSkipped(rig, drawn);
  if (!report.alignment_skipped.empty()) return;
  BakeStage stage("aligning the drawings' interiors");
  // One scale for every drawing: the largest brought to kAlignmentMaxSide,
  // and no finer than the level the outlines were traced on.
  int halvings = working_halvings;
  for (const DrawnPose& d : drawn)
    halvings = std::max(halvings, mapping::AlignmentHalvings(int(d.size.x()), int(d.size.y())));
  const double scale = std::ldexp(1.0, -halvings);
  std::vector<mapping::AlignmentImage> images;
  std::vector<Points> pixels;
  for (std::size_t k = 0; k < drawn.size(); ++k) {
    const DrawnPose& d = drawn[k];
    const PoseDescription& pose = rig.poses[d.index];
    images.push_back(AlignmentImageOf(pose.drawing_path, halvings,
                                      ErrorSource(rig.file, PoseLabel(pose.name, d.index) + ": " + pose.drawing_path)));
    pixels.emplace_back();
    for (const Point& p : result.meshes[k].vertices)
      pixels.back().push_back(scale * Point(p.x() - d.origin.x(), -p.y() - d.origin.y()));
  }
  const std::vector<char> boundary = mapping::BoundaryVertices(mesh);
  std::vector<bool> fixed(boundary.begin(), boundary.end());
  for (std::uint32_t v : result.feature_vertices) fixed[v] = true;
  mapping::AlignmentParameters parameters;
  parameters.rigidity = rig.mapping.align_rigidity;
  // The quality the description asks of the mesh holds through the
  // alignment (or what refinement reached, when that is less).
  parameters.min_angle_floor_degrees = rig.mapping.min_angle;
  mapping::AlignmentReport aligned;
  mapping::AlignInteriors(images, result.triangles, fixed, pixels, parameters, &aligned);
  for (std::size_t k = 0; k < drawn.size(); ++k) {
    const DrawnPose& d = drawn[k];
    PoseMesh& pose = result.meshes[k];
    for (std::size_t v = 0; v < pose.vertices.size(); ++v) {
      if (fixed[v]) continue;  // exactly where the mapping put it
      const Point q = pixels[k][v] / scale;
      const Point p(q.x() + d.origin.x(), 0.0 - (q.y() + d.origin.y()));
      pose.vertices[v] = p;
      pose.uvs[v] = Point((p.x() - d.origin.x()) / d.size.x(), (-p.y() - d.origin.y()) / d.size.y()).cast<float>();
    }
  }
  report.aligned = true;
  report.alignment_before = aligned.difference_before;
  report.alignment_after = aligned.difference_after;
  for (double m : aligned.max_move) report.alignment_max_move = std::max(report.alignment_max_move, m / scale);
  report.alignment_seconds = aligned.seconds;
  report.regions_found = aligned.regions_found;
  report.regions_matched = aligned.regions_matched;
}

}  // namespace posemorph::bake
