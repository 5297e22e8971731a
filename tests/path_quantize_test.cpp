// SPDX-License-Identifier: MIT
// Path playback and the 4-byte network encoding of a pose-space point.
#include <random>

#include "posemorph/path.h"
#include "posemorph/quantize.h"
#include "test_support.h"

using namespace posemorph;
using namespace posemorph::test;

namespace {

PathView MakePath(const std::vector<double>& keys, bool loop, PathInterpolation mode) {
  PathView p;
  p.loop = loop;
  p.interpolation = mode;
  p.keys = {keys.data(), keys.size()};
  return p;
}

}  // namespace

TEST_CASE("paths pass through their keys, hold or loop, and are smooth across a closed loop") {
  const std::vector<double> keys = {0, 0, 0, 0.5, 1, 0, 1.5, 1, 1, 2, 0, 0};  // closed: last = first
  for (PathInterpolation mode : {PathInterpolation::kLinear, PathInterpolation::kCatmullRom}) {
    const PathView p = MakePath(keys, true, mode);
    for (std::size_t k = 0; k + 1 < p.key_count(); ++k) {
      double x, y;
      REQUIRE(SamplePath(p, keys[3 * k], &x, &y));
      CHECK(x == doctest::Approx(keys[3 * k + 1]));
      CHECK(y == doctest::Approx(keys[3 * k + 2]));
    }
    // Looping: one period later is the same point; negative times wrap too.
    for (double t = -3; t < 3; t += 0.37) {
      double x0, y0, x1, y1;
      SamplePath(p, t, &x0, &y0);
      SamplePath(p, t + 2, &x1, &y1);
      CHECK(x0 == doctest::Approx(x1));
      CHECK(y0 == doctest::Approx(y1));
    }
  }
  // Catmull-Rom on a closed loop: the velocity just before the wrap matches the one just after.
  const PathView p = MakePath(keys, true, PathInterpolation::kCatmullRom);
  const double h = 1e-6;
  double xa, ya, xb, yb, xc, yc, xd, yd;
  SamplePath(p, 2 - 2 * h, &xa, &ya);
  SamplePath(p, 2 - h, &xb, &yb);
  SamplePath(p, 0, &xc, &yc);
  SamplePath(p, h, &xd, &yd);
  CHECK((xb - xa) / h == doctest::Approx((xd - xc) / h).epsilon(1e-3));
  CHECK((yb - ya) / h == doctest::Approx((yd - yc) / h).epsilon(1e-3));

  // Not looping: ends hold; the midpoint of a linear segment is the average.
  const PathView once = MakePath(keys, false, PathInterpolation::kLinear);
  double x, y;
  SamplePath(once, -10, &x, &y);
  CHECK((x == 0 && y == 0));
  SamplePath(once, 0.25, &x, &y);
  CHECK(x == doctest::Approx(0.5));
  SamplePath(once, 99, &x, &y);
  CHECK((x == 0 && y == 0));
  SamplePath(once, std::nan(""), &x, &y);
  CHECK((x == 0 && y == 0));
}

TEST_CASE("baked paths play back from the rig") {
  const Rig rig = Bake(samples::SnakeRig());
  const int slither = rig.FindPath("slither");
  REQUIRE(slither >= 0);
  CHECK(rig.FindPath("no such path") == -1);
  double x, y;
  REQUIRE(SamplePath(rig, std::uint32_t(slither), 0.5, &x, &y));
  CHECK(x == doctest::Approx(0));
  CHECK(y == doctest::Approx(-0.9));
  CHECK_FALSE(SamplePath(rig, 99, 0, &x, &y));
}

TEST_CASE("a pose-space point survives 4 bytes within half a quantisation step") {
  const Rig rig = Bake(samples::SnakeRig());
  const PoseSpaceGrid& g = rig.grid();
  const double step_x = g.cell * g.cells_x / 65535, step_y = g.cell * g.cells_y / 65535;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> ux(g.origin_x, g.origin_x + g.cell * g.cells_x);
  std::uniform_real_distribution<double> uy(g.origin_y, g.origin_y + g.cell * g.cells_y);
  for (int i = 0; i < 2000; ++i) {
    const double x = ux(rng), y = uy(rng);
    unsigned char wire[4];
    PackPoint(QuantizePoint(g, x, y), wire);
    double qx, qy;
    DequantizePoint(g, UnpackPoint(wire), &qx, &qy);
    CHECK(std::abs(qx - x) <= 0.5 * step_x * (1 + 1e-9));
    CHECK(std::abs(qy - y) <= 0.5 * step_y * (1 + 1e-9));
  }
  // Outside the grid clamps to its edge, where the weights are clamped anyway.
  const QuantizedPoint q = QuantizePoint(g, 1e9, -1e9);
  CHECK(q.x == 65535);
  CHECK(q.y == 0);
  unsigned char wire[4];
  PackPoint({0x1234, 0xABCD}, wire);
  CHECK(wire[0] == 0x34);
  CHECK(wire[1] == 0x12);
  CHECK(wire[2] == 0xCD);
  CHECK(wire[3] == 0xAB);
}
