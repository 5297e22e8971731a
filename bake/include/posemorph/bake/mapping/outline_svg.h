// SPDX-License-Identifier: MIT
// A drawing's outline from an SVG path or polygon (stage 1 of N-way mapping).
#pragma once
#include <string>
#include <vector>

#include "posemorph/bake/error.h"
#include "posemorph/bake/mapping/polygon.h"

namespace posemorph::bake::mapping {

struct SvgOutline {
  Polygon outline;            // user units, y down; either orientation
  Point canvas_origin{0, 0};  // viewBox origin (or 0, 0)
  Point canvas_size{0, 0};    // viewBox size (or width, height)
};
// Which part of the document the outline comes from: the group (<g>) whose
// inkscape:label or id is `name` (an Inkscape layer, or a plain group), or
// the whole document when `name` is empty. When no group has the name: the
// whole document if `required` is false and the drawing has at most one
// Inkscape layer (a layered character's part takes the layer named like
// itself, or its own file), else an error listing the groups that are named.
struct SvgLayer {
  std::string name;
  bool required = false;
};
// Within the layer, the element with id="outline" if there is one, else the
// first <path> or <polygon>: M/L/H/V/C/Q/Z (absolute and relative) and
// polygon points; curves flattened to `tolerance`. Throws BakeError naming
// the file, or as `source` says (in a bake: "DESCRIPTION: POSE: DRAWING:
// problem"); two groups with the layer's name are an error.
SvgOutline OutlineFromSvg(const std::string& path, double tolerance);
SvgOutline OutlineFromSvg(const std::string& path, double tolerance, const ErrorSource& source,
                          const SvgLayer& layer = {});
SvgOutline OutlineFromSvgText(const std::string& text, double tolerance, const ErrorSource& source,
                              const SvgLayer& layer = {});
// The names of a drawing's top-level groups (the <svg> element's <g>
// children: an Inkscape layer by its inkscape:label, a plain group by its
// id), in document order, leaving out unnamed and hidden ones
// (style="display:none", Inkscape's hidden layer): the parts `posemorph-bake
// init` makes of one SVG per pose. Throws BakeError naming the file when it
// is not an SVG document.
std::vector<std::string> SvgLayerNames(const std::string& path, const ErrorSource& source);

// Path data alone ("M 0 0 L 10 0 ..."), first subpath.
Polygon FlattenSvgPath(const std::string& d, double tolerance, const ErrorSource& source);

}  // namespace posemorph::bake::mapping
