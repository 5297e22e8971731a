// Helpers shared by the tests: bake a description in memory, evaluate frames.
#pragma once
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "posemorph/bake/bake.h"
#include "posemorph/jobs.h"
#include "posemorph/rig.h"
#include "strip_rig.h"

namespace posemorph::test {

inline Rig Bake(bake::RigDescription desc) {
  const std::vector<unsigned char> bytes = bake::BakeRig(desc);
  Rig rig;
  Error err;
  REQUIRE_MESSAGE(LoadRig(bytes.data(), bytes.size(), &rig, &err), err.message);
  return rig;
}

struct Weights {
  std::vector<double> raw, shear, texture;
};

inline Weights WeightsAt(const Rig& rig, double x, double y, double sigma = 0, bool shear_limit = true) {
  Weights w;
  w.raw.resize(rig.pose_count());
  w.shear.resize(rig.pose_count());
  w.texture.resize(rig.pose_count());
  WeightsJob job;
  job.rig = &rig;
  job.x = x, job.y = y, job.sigma = sigma, job.shear_limit = shear_limit;
  job.raw = MakeSpan(w.raw), job.shear = MakeSpan(w.shear), job.texture = MakeSpan(w.texture);
  REQUIRE(job.Run());
  return w;
}

inline std::vector<double> Morph(const Rig& rig, const std::vector<double>& w, const std::vector<double>& ws,
                                 Interpolation mode = Interpolation::kRigid) {
  std::vector<double> work(rig.morph_workspace_size()), x(2 * std::size_t(rig.vertex_count()));
  MorphJob job;
  job.rig = &rig;
  job.weights = MakeSpan(w), job.shear_weights = MakeSpan(ws);
  job.interpolation = mode;
  job.workspace = MakeSpan(work), job.positions = MakeSpan(x);
  REQUIRE(job.Run());
  return x;
}

inline std::vector<double> MorphAt(const Rig& rig, double px, double py, bool shear_limit = true) {
  const Weights w = WeightsAt(rig, px, py, 0, shear_limit);
  return Morph(rig, w.raw, w.shear);
}

inline double MaxVertexDistance(const std::vector<double>& x, const std::vector<Eigen::Vector2d>& q) {
  double worst = 0;
  for (std::size_t v = 0; v < q.size(); ++v) worst = std::max(worst, std::hypot(x[2 * v] - q[v].x(), x[2 * v + 1] - q[v].y()));
  return worst;
}

// Smallest signed triangle area of positions x, relative to the same triangle at rest.
inline double MinAreaRatio(const Rig& rig, const std::vector<double>& x) {
  const auto t = rig.triangles();
  const double* r = rig.pose_positions(0).data;
  double worst = 1e300;
  auto area = [&](const double* p, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    return 0.5 * ((p[2 * b] - p[2 * a]) * (p[2 * c + 1] - p[2 * a + 1]) - (p[2 * c] - p[2 * a]) * (p[2 * b + 1] - p[2 * a + 1]));
  };
  for (std::uint32_t k = 0; k < rig.triangle_count(); ++k) {
    const std::uint32_t a = t[3 * k], b = t[3 * k + 1], c = t[3 * k + 2];
    worst = std::min(worst, area(x.data(), a, b, c) / area(r, a, b, c));
  }
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
