// SPDX-License-Identifier: MIT
#include "posemorph/bake/mesh_quality.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "rig_message.h"

namespace posemorph::bake {
namespace {

double EdgeLength(const double* x, std::uint32_t a, std::uint32_t b) {
  return std::hypot(x[2 * b] - x[2 * a], x[2 * b + 1] - x[2 * a + 1]);
}

}  // namespace

SmallestAngle FindSmallestAngle(const Rig& rig) {
  SmallestAngle s;
  const std::uint32_t* tris = rig.triangles().data;
  for (std::uint32_t i = 0; i < rig.pose_count(); ++i) {
    const double* x = rig.pose_positions(i).data;
    for (std::uint32_t t = 0; t < rig.triangle_count(); ++t) {
      const std::uint32_t* v = tris + 3 * t;
      // The smallest angle is opposite the shortest edge (law of sines).
      const double l[3] = {EdgeLength(x, v[1], v[2]), EdgeLength(x, v[2], v[0]), EdgeLength(x, v[0], v[1])};
      const int k = int(std::min_element(l, l + 3) - l);
      const double b = l[(k + 1) % 3], c = l[(k + 2) % 3];
      if (b <= 0 || c <= 0) continue;
      const double cosine = std::clamp((b * b + c * c - l[k] * l[k]) / (2 * b * c), -1.0, 1.0);
      const double degrees = std::acos(cosine) * 180 / M_PI;
      if (degrees >= s.degrees) continue;
      s.degrees = degrees;
      s.triangle = t;
      s.pose = i;
      s.short_edge = l[k];
      // The same edge (opposite corner k) in every pose: where it is longest.
      const std::uint32_t a = v[(k + 1) % 3], e = v[(k + 2) % 3];
      s.long_edge = 0;
      for (std::uint32_t j = 0; j < rig.pose_count(); ++j) {
        const double len = EdgeLength(rig.pose_positions(j).data, a, e);
        if (len > s.long_edge) s.long_edge = len, s.long_pose = j;
      }
    }
  }
  return s;
}

bool Squeezed(const SmallestAngle& s) {
  return s.long_pose != s.pose && s.short_edge > 0 && s.long_edge >= 2 * s.short_edge;
}

std::string DescribeSmallestAngle(const Rig& rig, const SmallestAngle& s, double floor) {
  const std::uint32_t* v = rig.triangles().data + 3 * s.triangle;
  const double* x = rig.pose_positions(s.pose).data;
  const bool drawn = rig.pose_canvas(s.pose).width > 0;
  double px = 0, py = 0;
  InDrawingPixels(rig, s.pose, (x[2 * v[0]] + x[2 * v[1]] + x[2 * v[2]]) / 3,
                  (x[2 * v[0] + 1] + x[2 * v[1] + 1] + x[2 * v[2] + 1]) / 3, &px, &py);
  const std::uint32_t part = PartOfTriangle(rig, s.triangle);
  const bool layered = rig.part_count() > 1;
  const StringView image = layered ? rig.part_image(part, s.pose) : rig.pose_image(s.pose);
  std::ostringstream o;
  o << "the mesh's smallest angle is " << MessageNumber(s.degrees) << " degrees, below " << MessageNumber(floor)
    << " (half of mapping.min_angle): triangle " << s.triangle << " in pose '" << RigString(rig.pose_name(s.pose))
    << "'";
  if (layered) o << ", part '" << RigString(rig.part(part).name) << "'";
  o << ", at (" << MessageNumber(px) << ", " << MessageNumber(py) << ") in "
    << (drawn && image.size ? RigString(image) : "'" + RigString(rig.pose_name(s.pose)) + "'");
  const double squeeze = s.short_edge > 0 ? s.long_edge / s.short_edge : 0;
  const char* unit = drawn ? " px" : " units";
  if (Squeezed(s)) {
    o << ", where pose '" << RigString(rig.pose_name(s.pose)) << "' squeezes it " << MessageNumber(squeeze)
      << "x against pose '" << RigString(rig.pose_name(s.long_pose)) << "' (an edge of " << MessageNumber(s.short_edge)
      << unit << " there, " << MessageNumber(s.long_edge) << unit
      << " in the other); where one drawing squeezes the outline this much (a limb against the body in one "
         "pose and away from it in another) no single-layer mesh keeps its shape in both: draw that limb as its "
         "own part (\"parts\"), or a landmark at each end of the squeezed stretch if the outlines are matched "
         "wrongly there";
  } else {
    o << "; a landmark on the outline near it, or a smaller mapping.max_edge_length, may lift it";
  }
  return o.str();
}

}  // namespace posemorph::bake
