// SPDX-License-Identifier: MIT
// A drawing's outline from an SVG path or polygon (stage 1 of N-way mapping).
#pragma once
#include <string>

#include "posemorph/bake/error.h"
#include "posemorph/bake/mapping/polygon.h"

namespace posemorph::bake::mapping {

struct SvgOutline {
  Polygon outline;            // user units, y down; either orientation
  Point canvas_origin{0, 0};  // viewBox origin (or 0, 0)
  Point canvas_size{0, 0};    // viewBox size (or width, height)
};
// The element with id="outline" if there is one, else the first <path> or
// <polygon>: M/L/H/V/C/Q/Z (absolute and relative) and polygon points; curves
// flattened to `tolerance`. Throws BakeError naming the file, or as `source`
// says (in a bake: "DESCRIPTION: POSE: DRAWING: problem").
SvgOutline OutlineFromSvg(const std::string& path, double tolerance);
SvgOutline OutlineFromSvg(const std::string& path, double tolerance, const ErrorSource& source);
SvgOutline OutlineFromSvgText(const std::string& text, double tolerance, const ErrorSource& source);
// Path data alone ("M 0 0 L 10 0 ..."), first subpath.
Polygon FlattenSvgPath(const std::string& d, double tolerance, const ErrorSource& source);

}  // namespace posemorph::bake::mapping
