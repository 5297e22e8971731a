// SPDX-License-Identifier: MIT
// A drawn pose as the mapping driver (map_drawings.cpp) carries it between
// its stages, and the stage that aligns the drawn interiors
// (align_drawn_interiors.cpp). Internal to the bake.
#pragma once

#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

#include "mapping/geometry.h"
#include "posemorph/bake/import/layered_reference.h"
#include "posemorph/bake/map_drawings.h"
#include "posemorph/bake/mapping/compatible_triangulation.h"
#include "posemorph/bake/rig_description.h"

namespace posemorph::bake {

// Whether s ends with suffix, ASCII letters in either case (".PNG" too).
inline bool EndsWith(std::string s, const std::string& suffix) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// A drawing the bake reads as pixels: a PNG, or a layer of a layered file
// (NAME.ora#Group/Layer, import/layered_reference.h).
inline bool IsRasterDrawing(const std::string& drawing) {
  return EndsWith(drawing, ".png") || import::ParseLayeredReference(drawing);
}

struct DrawnPose {
  std::size_t index = 0;     // in rig.poses
  mapping::Polygon outline;  // rig coordinates (y up), counter-clockwise
  std::vector<mapping::Point> landmarks;
  std::vector<mapping::Point> features;
  // uv = ((x - origin.x) / size.x, (-y - origin.y) / size.y) for drawings (rows go down)
  bool from_drawing = false;
  mapping::Point origin{0, 0}, size{1, 1};
};

// Why the drawings cannot align the interiors, or empty when they can: it
// needs two drawn poses or more, every one a PNG drawing that is also the
// texture drawn.
std::string AlignmentSkipped(const RigDescription& rig, const std::vector<DrawnPose>& drawn);

// Stage 7: every drawn pose's interior vertices (all but the boundary's and
// the features') move so that the drawings agree through the meshes
// (interior_alignment.h), in each drawing's pixels, on pyramid level
// working_halvings or a coarser one; uvs follow. Fills the alignment fields
// of result.report.
void AlignDrawnInteriors(const RigDescription& rig, const std::vector<DrawnPose>& drawn,
                         const mapping::CompatibleMesh& mesh, int working_halvings, MappedDrawings& result);

}  // namespace posemorph::bake
