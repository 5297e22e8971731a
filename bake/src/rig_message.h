// SPDX-License-Identifier: MIT
// What the bake's messages about a baked rig share (inbetween_check.cpp,
// mesh_quality.cpp): a rig's string as a std::string, a number to three
// significant digits with tiny values as 0, a point as "(x, y)", the part a
// triangle is in, and a rig point in a pose's drawing pixels.
#pragma once
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>

#include "posemorph/rig.h"

namespace posemorph::bake {

inline std::string RigString(StringView s) { return std::string(s.data, s.size); }

inline std::string MessageNumber(double v) {
  std::ostringstream s;
  s.precision(3);
  s << (std::abs(v) < 5e-4 ? 0.0 : v);
  return s.str();
}

// A point (anything with x() and y(): an Eigen::Vector2d) as "(x, y)", each
// coordinate as a stream prints it.
template <class Point>
std::string PointText(const Point& p) {
  std::ostringstream s;
  s << "(" << p.x() << ", " << p.y() << ")";
  return s.str();
}

// The part holding triangle t (0 on a rig without parts).
inline std::uint32_t PartOfTriangle(const Rig& rig, std::uint32_t t) {
  std::uint32_t part = 0;
  for (std::uint32_t k = 0; k < rig.part_count(); ++k) {
    const PartView pv = rig.part(k);
    if (t >= pv.first_triangle && t < pv.first_triangle + pv.triangle_count) part = k;
  }
  return part;
}

// Rig point (x, y) in pose i's drawing pixels, y down from the canvas's
// corner, as landmarks are given (the canvas pivot added back); as it is
// when the pose has no drawing.
inline void InDrawingPixels(const Rig& rig, std::uint32_t i, double x, double y, double* px, double* py) {
  const DrawingCanvas canvas = rig.pose_canvas(i);
  const bool drawn = canvas.width > 0;
  *px = x + (drawn ? canvas.pivot_x : 0.0);
  *py = drawn ? canvas.pivot_y - y : y;
}

}  // namespace posemorph::bake
