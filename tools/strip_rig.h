// SPDX-License-Identifier: MIT
// Procedural strip-shaped characters (snakes, worms) for the bundled samples
// and the tests: a band of quads along a centreline whose curvature is a
// function of arclength, so each pose is "the same body, bent differently".
#pragma once
#include <cmath>
#include <functional>
#include <string>

#include "posemorph/bake/rig_description.h"
#include "posemorph/bake/triangle_math.h"

namespace posemorph::samples {

struct StripShape {
  double length = 10;
  double width = 1;
  int segments = 40;                    // quads along the body
  int across = 4;                       // quads across it
  std::function<double(double)> taper;  // width factor at arclength fraction s in [0, 1]
};

// Vertex positions of the strip bent by curvature kappa(s) (radians per unit
// length, s in [0, length]); the first station sits at the origin heading +x.
inline std::vector<Eigen::Vector2d> BentStrip(const StripShape& shape, const std::function<double(double)>& kappa) {
  std::vector<Eigen::Vector2d> out;
  const double ds = shape.length / shape.segments;
  const int substeps = 64;
  Eigen::Vector2d c(0, 0);
  double heading = 0;
  for (int k = 0; k <= shape.segments; ++k) {
    if (k > 0) {
      // Midpoint integration of heading and position over the segment.
      for (int q = 0; q < substeps; ++q) {
        const double s = (k - 1) * ds + (q + 0.5) * ds / substeps;
        const double h = heading + 0.5 * kappa(s) * ds / substeps;
        c += ds / substeps * Eigen::Vector2d(std::cos(h), std::sin(h));
        heading += kappa(s) * ds / substeps;
      }
    }
    const Eigen::Vector2d normal(-std::sin(heading), std::cos(heading));
    const double w = shape.width * (shape.taper ? shape.taper(double(k) / shape.segments) : 1.0);
    for (int j = 0; j <= shape.across; ++j) out.push_back(c + (double(j) / shape.across - 0.5) * w * normal);
  }
  return out;
}

inline bake::Triangles StripTriangles(const StripShape& shape) {
  bake::Triangles tris;
  const std::uint32_t stride = std::uint32_t(shape.across + 1);
  for (std::uint32_t k = 0; k < std::uint32_t(shape.segments); ++k)
    for (std::uint32_t j = 0; j < std::uint32_t(shape.across); ++j) {
      const std::uint32_t v00 = k * stride + j, v10 = v00 + stride;
      tris.push_back({v00, v10, v10 + 1});
      tris.push_back({v00, v10 + 1, v00 + 1});
    }
  return tris;
}

inline bake::PoseDescription StripPose(const std::string& name, double x, double y, const StripShape& shape,
                                       const std::function<double(double)>& kappa) {
  bake::PoseDescription p;
  p.name = name;
  p.point = {x, y};
  p.vertices = BentStrip(shape, kappa);
  return p;
}

inline double Degrees(double d) { return d * M_PI / 180; }

// The snake: 5 poses around a cross in pose space, one curled past 300 degrees.
inline bake::RigDescription SnakeRig() {
  StripShape shape;
  shape.taper = [](double s) { return 1.0 - 0.7 * std::pow(s, 1.5); };
  const double L = shape.length;
  bake::RigDescription rig;
  rig.name = "snake";
  rig.triangles = StripTriangles(shape);
  rig.poses.push_back(StripPose("rest", 0, 0, shape, [](double) { return 0.0; }));
  rig.poses.push_back(StripPose("left", -1, 0, shape, [=](double) { return Degrees(120) / L; }));
  rig.poses.push_back(StripPose("right", 1, 0, shape, [=](double) { return -Degrees(120) / L; }));
  // Curvature ramping up to the tail (a clothoid): 300 degrees in all.
  rig.poses.push_back(StripPose("curl", 0, 1, shape, [=](double s) { return 2 * Degrees(300) * s / (L * L); }));
  rig.poses.push_back(StripPose("wave", 0, -1, shape,
                                [=](double s) { return Degrees(75) * 2 * M_PI / L * std::sin(2 * M_PI * s / L); }));
  rig.parameters.grid_resolution = 64;
  rig.parameters.grid_resolution_given = true;  // written into the description, as committed
  rig.parameters.sigma = 0.25;
  rig.paths.push_back(
      {"slither", true, true, {{0, -0.9, 0}, {0.5, 0, -0.9}, {1, 0.9, 0}, {1.5, 0, -0.9}, {2, -0.9, 0}}, {}});
  rig.paths.push_back({"curl-up", false, false, {{0, 0, 0}, {1, 0, 1}, {1.5, 0.3, 1.2}, {2.5, 0, 0}}, {}});
  return rig;
}

// The worm: 3 poses on a line in pose space (a 1D arrangement).
inline bake::RigDescription WormLineRig() {
  StripShape shape;
  shape.length = 6;
  shape.width = 0.8;
  shape.segments = 30;
  shape.across = 3;
  shape.taper = [](double s) { return 0.6 + 0.4 * std::sin(M_PI * s); };
  const double L = shape.length;
  bake::RigDescription rig;
  rig.name = "worm-line";
  rig.triangles = StripTriangles(shape);
  rig.poses.push_back(StripPose("rest", 0, 0, shape, [](double) { return 0.0; }));
  rig.poses.push_back(StripPose("arch-left", -1, 0, shape, [=](double) { return Degrees(150) / L; }));
  rig.poses.push_back(StripPose("arch-right", 1, 0, shape, [=](double) { return -Degrees(150) / L; }));
  rig.parameters.grid_resolution = 64;
  rig.parameters.grid_resolution_given = true;  // written into the description, as committed
  rig.paths.push_back({"sway", true, true, {{0, -1.3, 0}, {1, 1.3, 0}, {2, -1.3, 0}}, {}});
  return rig;
}

// A plate of 2 across x across cells (one bend per pose; rest first), the
// benchmarks' and the compact-size test's large rig: across 22 gives 1035
// vertices.
inline bake::RigDescription PlateRig(int across, int poses) {
  StripShape shape;
  shape.length = 10, shape.width = 5, shape.segments = 2 * across, shape.across = across;
  const double L = shape.length;
  // Bends keep the radius above half the width (no flips).
  const std::function<double(double)> kappa[] = {
      [](double) { return 0.0; },
      [=](double) { return Degrees(90) / L; },
      [=](double) { return -Degrees(90) / L; },
      [=](double s) { return 2 * Degrees(100) * s / (L * L); },
      [=](double s) { return -2 * Degrees(100) * s / (L * L); },
      [=](double s) { return 0.3 * std::sin(2 * M_PI * s / L); },
      [=](double s) { return -0.3 * std::sin(2 * M_PI * s / L); },
      [=](double s) { return 0.25 * std::sin(M_PI * s / L); },
  };
  bake::RigDescription rig;
  rig.name = "plate";
  rig.triangles = StripTriangles(shape);
  for (int i = 0; i < poses; ++i) {
    const double a = 2 * M_PI * (i - 1) / (poses - 1);
    rig.poses.push_back(StripPose("p" + std::to_string(i), i ? std::cos(a) : 0, i ? std::sin(a) : 0, shape, kappa[i]));
  }
  return rig;
}

}  // namespace posemorph::samples
