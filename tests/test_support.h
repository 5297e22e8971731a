// SPDX-License-Identifier: MIT
// Helpers shared by the bake-side tests: bake a description in memory (the
// runtime-only helpers are in runtime/runtime_support.h).
#pragma once
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "posemorph/bake/bake.h"
#include "posemorph/bake/deform_poses.h"
#include "runtime_support.h"
#include "strip_rig.h"

namespace posemorph::test {

// Exact encoding: these tests hold the math to 1e-9 (the compact encoding
// has its own tests, compact_rig_test.cpp).
inline Rig Bake(bake::RigDescription desc) {
  desc.parameters.compact = false;
  const std::vector<unsigned char> bytes = bake::BakeRig(desc);
  Rig rig;
  Error err;
  REQUIRE_MESSAGE(LoadRig(bytes.data(), bytes.size(), &rig, &err), err.message);
  return rig;
}

inline double MaxVertexDistance(const std::vector<double>& x, const std::vector<Eigen::Vector2d>& q) {
  double worst = 0;
  for (std::size_t v = 0; v < q.size(); ++v)
    worst = std::max(worst, std::hypot(x[2 * v] - q[v].x(), x[2 * v + 1] - q[v].y()));
  return worst;
}

// Two-pose strip rig: straight, and bent by `turn` radians of constant curvature.
inline bake::RigDescription BentStripRig(double turn, int segments = 24, int across = 3) {
  samples::StripShape shape;
  shape.segments = segments;
  shape.across = across;
  bake::RigDescription rig;
  rig.file = "bent-strip";
  rig.triangles = samples::StripTriangles(shape);
  rig.poses.push_back(samples::StripPose("straight", 0, 0, shape, [](double) { return 0.0; }));
  rig.poses.push_back(samples::StripPose("bent", 1, 0, shape, [=](double) { return turn / shape.length; }));
  return rig;
}

}  // namespace posemorph::test
