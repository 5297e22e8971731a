// SPDX-License-Identifier: MIT
// The pose-space weight field and the weight maps on top of it.
#include "test_support.h"

using namespace posemorph;
using namespace posemorph::test;

TEST_CASE("weights sum to 1 everywhere and are e_i at the pose points") {
  for (const bake::RigDescription& desc : {samples::SnakeRig(), samples::WormLineRig()}) {
    const Rig rig = Bake(desc);
    const std::uint32_t N = rig.pose_count();
    const PoseSpaceGrid& g = rig.grid();
    // A dense sample of the grid and well beyond it (clamped).
    const double x0 = g.origin_x - 2, x1 = g.origin_x + g.cell * g.cells_x + 2;
    const double y0 = g.origin_y - 2, y1 = g.origin_y + g.cell * g.cells_y + 2;
    double worst_sum = 0, worst_limited = 0, worst_texture = 0;
    for (int j = 0; j <= 200; ++j)
      for (int i = 0; i <= 200; ++i) {
        const Weights w = WeightsAt(rig, x0 + (x1 - x0) * i / 200, y0 + (y1 - y0) * j / 200, 0.6);
        double s = 0, ss = 0, st = 0;
        for (std::uint32_t k = 0; k < N; ++k) {
          s += w.raw[k], ss += w.limited[k], st += w.texture[k];
          CHECK(w.limited[k] >= 0);
          CHECK(w.limited[k] <= 1);
        }
        worst_sum = std::max(worst_sum, std::abs(s - 1));
        worst_limited = std::max(worst_limited, std::abs(ss - 1));
        worst_texture = std::max(worst_texture, std::abs(st - 1));
      }
    CAPTURE(desc.name);
    CHECK(worst_sum <= 1e-12);
    CHECK(worst_limited <= 1e-12);
    CHECK(worst_texture <= 1e-12);
    for (std::uint32_t i = 0; i < N; ++i) {
      const Weights w = WeightsAt(rig, desc.poses[i].point.x(), desc.poses[i].point.y(), 0.5);
      for (std::uint32_t k = 0; k < N; ++k) {
        CHECK(std::abs(w.raw[k] - (k == i ? 1.0 : 0.0)) <= 1e-12);
        CHECK(std::abs(w.limited[k] - (k == i ? 1.0 : 0.0)) <= 1e-12);
        CHECK(std::abs(w.texture[k] - (k == i ? 1.0 : 0.0)) <= 1e-12);
      }
    }
  }
}

TEST_CASE("far from the pose points the weight field levels out") {
  const Rig rig = Bake(samples::SnakeRig());
  // Compare the change of the weights over one unit step next to the data
  // (between rest and right) with the same step at the edge of the grid.
  auto change = [&](double xa, double xb, double y) {
    const Weights a = WeightsAt(rig, xa, y), b = WeightsAt(rig, xb, y);
    double d = 0;
    for (std::size_t k = 0; k < a.raw.size(); ++k) d += std::abs(a.raw[k] - b.raw[k]);
    return d;
  };
  const double edge = rig.grid().origin_x + rig.grid().cell * rig.grid().cells_x;
  CHECK(change(edge - 0.25, edge, 0) < 0.5 * change(0.25, 0.5, 0));
}

TEST_CASE("non-finite pose-space points give finite, defined weights") {
  const Rig rig = Bake(samples::SnakeRig());
  const double inf = std::numeric_limits<double>::infinity(), nan = std::nan("");
  const double points[][2] = {{nan, nan}, {inf, 0}, {-inf, -inf}, {nan, 1}, {0, inf}};
  for (const auto& p : points) {
    const Weights w = WeightsAt(rig, p[0], p[1], 0.3);
    double s = 0;
    for (double v : w.raw) {
      CHECK(std::isfinite(v));
      s += v;
    }
    CHECK(s == doctest::Approx(1));
    const std::vector<double> x = Morph(rig, w.raw, w.limited);
    for (double v : x) CHECK(std::isfinite(v));
  }
  // NaN means "pose 0's coordinate": (NaN, NaN) is the rest pose exactly.
  const Weights w = WeightsAt(rig, nan, nan);
  CHECK(w.raw[0] == doctest::Approx(1).epsilon(1e-12));
}

TEST_CASE("weight limiting and texture sharpening follow the paper's maps") {
  // phi: smoothstep clamped to [0, 1] with phi(0) = 0, phi(1) = 1, flat ends.
  CHECK(LimitWeight(-3) == 0);
  CHECK(LimitWeight(0) == 0);
  CHECK(LimitWeight(1) == 1);
  CHECK(LimitWeight(7) == 1);
  CHECK(LimitWeight(0.5) == doctest::Approx(0.5));
  CHECK(LimitWeight(0.25) == doctest::Approx(0.15625));
  CHECK((LimitWeight(1e-4) - LimitWeight(0)) / 1e-4 < 1e-3);  // zero slope at 0

  const double in[] = {0.7, 0.2, 0.1};
  double out[3];
  // sigma = 0: a plain linear cross-fade, the weights unchanged.
  TextureWeights(Span<const double>(in, 3), 0, Span<double>(out, 3));
  for (int i = 0; i < 3; ++i) CHECK(out[i] == doctest::Approx(in[i]));
  // sigma near 1: the dominant pose takes (nearly) everything.
  TextureWeights(Span<const double>(in, 3), 0.95, Span<double>(out, 3));
  CHECK(out[0] > 0.95);
  // sigma = 1 with no weight above 1/2 (the paper's formula is 0/0 there):
  // the limit of sigma -> 1, which is the input itself, so w'' is continuous
  // in sigma (it used to jump to the dominant pose: issue "Fidelity").
  const double flat[] = {0.3, 0.45, 0.25};
  TextureWeights(Span<const double>(flat, 3), 1, Span<double>(out, 3));
  for (int i = 0; i < 3; ++i) CHECK(out[i] == doctest::Approx(flat[i]).epsilon(1e-15));
  // Sharpening grows the dominant weight monotonically with sigma.
  double last = 0;
  for (double sigma = 0; sigma <= 1; sigma += 0.1) {
    TextureWeights(Span<const double>(in, 3), sigma, Span<double>(out, 3));
    CHECK(out[0] >= last - 1e-12);
    last = out[0];
  }
}
