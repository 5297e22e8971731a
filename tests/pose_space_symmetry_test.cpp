// SPDX-License-Identifier: MIT
// The pose-space weight field has no preferred direction: layouts that are
// mirror images or quarter turns of each other get correspondingly
// permuted weights, and inside the pose points' hull the field stays close
// to a thin-plate spline through the same points (docs/DESIGN.md section 7:
// each grid cell is four triangles meeting at its centre, and near the hull
// the grid holds the spline). The spline here is this test's own.
#include <Eigen/Dense>
#include <functional>
#include <limits>
#include <random>

#include "gingerbread_rig.h"
#include "test_support.h"

using namespace posemorph;
using namespace posemorph::test;

namespace {

using Layout = std::vector<Eigen::Vector2d>;

// A rig whose only interesting part is its pose-space layout: one triangle, a
// slightly different copy per pose.
bake::RigDescription LayoutDescription(const Layout& points, int resolution = 64) {
  bake::RigDescription d;
  d.file = "layout";
  d.name = "layout";
  d.triangles = {{0, 1, 2}};
  for (std::size_t i = 0; i < points.size(); ++i) {
    bake::PoseDescription p;
    p.name = "p" + std::to_string(i);
    p.point = points[i];
    p.vertices = {{0, 0}, {1, 0.01 * double(i)}, {0.5, 1}};
    d.poses.push_back(p);
  }
  d.parameters.grid_resolution = resolution;
  return d;
}

Rig LayoutRig(const Layout& points, int resolution = 64) { return Bake(LayoutDescription(points, resolution)); }

std::vector<double> Raw(const Rig& rig, const Eigen::Vector2d& p) { return WeightsAt(rig, p.x(), p.y()).raw; }

// Largest |w_a(p)[perm[i]] - w_b(map(p))[i]| over a 61 x 61 sample of [-2, 2]^2.
double PermutedDifference(const Rig& a, const Rig& b, const std::function<Eigen::Vector2d(Eigen::Vector2d)>& map,
                          const std::vector<int>& perm) {
  double worst = 0;
  for (int j = 0; j <= 60; ++j)
    for (int i = 0; i <= 60; ++i) {
      const Eigen::Vector2d p(-2 + 4.0 * i / 60, -2 + 4.0 * j / 60);
      const std::vector<double> wa = Raw(a, p), wb = Raw(b, map(p));
      for (std::size_t k = 0; k < wa.size(); ++k) worst = std::max(worst, std::abs(wa[std::size_t(perm[k])] - wb[k]));
    }
  return worst;
}

// Thin-plate spline through (p_i, e_i): w(x) = sum_j a_j phi(|x - p_j|) + affine, phi(r) = r^2 log r.
struct ThinPlate {
  Layout points;
  Eigen::MatrixXd coefficients;  // (N + 3) x N
  explicit ThinPlate(const Layout& p) : points(p) {
    const int n = int(p.size());
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n + 3, n + 3);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) A(i, j) = Phi((p[size_t(i)] - p[size_t(j)]).norm());
      A(i, n) = A(n, i) = 1;
      A(i, n + 1) = A(n + 1, i) = p[size_t(i)].x();
      A(i, n + 2) = A(n + 2, i) = p[size_t(i)].y();
    }
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n + 3, n);
    rhs.topRows(n).setIdentity();
    coefficients = A.fullPivLu().solve(rhs);
  }
  static double Phi(double r) { return r > 0 ? r * r * std::log(r) : 0.0; }
  std::vector<double> operator()(const Eigen::Vector2d& x) const {
    const int n = int(points.size());
    std::vector<double> w(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) {
      double v = coefficients(n, k) + coefficients(n + 1, k) * x.x() + coefficients(n + 2, k) * x.y();
      for (int j = 0; j < n; ++j) v += coefficients(j, k) * Phi((x - points[size_t(j)]).norm());
      w[size_t(k)] = v;
    }
    return w;
  }
};

bool InsideHull(const Layout& pts, const Eigen::Vector2d& x) {
  // Convex hull by gift wrapping (few points), then a side test.
  std::vector<Eigen::Vector2d> hull;
  std::size_t start = 0;
  for (std::size_t i = 1; i < pts.size(); ++i)
    if (pts[i].x() < pts[start].x() || (pts[i].x() == pts[start].x() && pts[i].y() < pts[start].y())) start = i;
  std::size_t at = start;
  do {
    hull.push_back(pts[at]);
    std::size_t next = (at + 1) % pts.size();
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const Eigen::Vector2d a = pts[next] - pts[at], b = pts[i] - pts[at];
      if (a.x() * b.y() - a.y() * b.x() < 0) next = i;
    }
    at = next;
  } while (at != start && hull.size() <= pts.size());
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d a = hull[(i + 1) % hull.size()] - hull[i], b = x - hull[i];
    if (a.x() * b.y() - a.y() * b.x() < -1e-12) return false;
  }
  return true;
}

double ThinPlateDistance(const Layout& points, int resolution = 64) {
  const Rig rig = LayoutRig(points, resolution);
  const ThinPlate tps(points);
  double worst = 0;
  for (int j = 0; j <= 80; ++j)
    for (int i = 0; i <= 80; ++i) {
      const Eigen::Vector2d x(-1.5 + 3.0 * i / 80, -1.5 + 3.0 * j / 80);
      if (!InsideHull(points, x)) continue;
      const std::vector<double> w = Raw(rig, x), t = tps(x);
      for (std::size_t k = 0; k < w.size(); ++k) worst = std::max(worst, std::abs(w[k] - t[k]));
    }
  return worst;
}

// The closest two points' distance in grid cells at this resolution.
double ClosestPairInCells(const Layout& points, int resolution) {
  const double cell = LayoutRig(points, resolution).grid().cell;
  double closest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < points.size(); ++i)
    for (std::size_t j = i + 1; j < points.size(); ++j) closest = std::min(closest, (points[i] - points[j]).norm());
  return closest / cell;
}

Layout Points(const bake::RigDescription& d) {
  Layout p;
  for (const auto& pose : d.poses) p.push_back(pose.point);
  return p;
}

Layout RandomLayout(unsigned seed, int n) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Layout p;
  for (int i = 0; i < n; ++i) p.emplace_back(u(rng), u(rng));
  return p;
}

}  // namespace

TEST_CASE("pose space: the snake's mirror-symmetric layout gets mirror-symmetric weights") {
  // rest (0,0), left (-1,0), right (1,0), curl (0,1), wave (0,-1).
  const Rig rig = LayoutRig(Points(samples::SnakeRig()));
  const double mirror_x =
      PermutedDifference(rig, rig, [](Eigen::Vector2d p) { return Eigen::Vector2d(-p.x(), p.y()); }, {0, 2, 1, 3, 4});
  const double mirror_y =
      PermutedDifference(rig, rig, [](Eigen::Vector2d p) { return Eigen::Vector2d(p.x(), -p.y()); }, {0, 1, 2, 4, 3});
  // A quarter turn counter-clockwise takes left to wave, right to curl, curl to left, wave to right.
  const double quarter =
      PermutedDifference(rig, rig, [](Eigen::Vector2d p) { return Eigen::Vector2d(-p.y(), p.x()); }, {0, 3, 4, 2, 1});
  const double rest_up = Raw(rig, {0.5, 0.5})[0], rest_down = Raw(rig, {0.5, -0.5})[0];
  MESSAGE("snake: mirror x " << mirror_x << ", mirror y " << mirror_y << ", quarter turn " << quarter
                             << "; rest at (0.5, 0.5) " << rest_up << ", at (0.5, -0.5) " << rest_down);
  CHECK(mirror_x <= 1e-9);
  CHECK(mirror_y <= 1e-9);
  CHECK(quarter <= 1e-9);
  CHECK(std::abs(rest_up - rest_down) <= 1e-9);
}

TEST_CASE("pose space: a mirrored or quarter-turned layout gets the same weights at the mapped points") {
  for (unsigned seed : {1u, 2u, 3u}) {
    CAPTURE(seed);
    const Layout base = RandomLayout(seed, 6);
    Layout mirrored, turned;
    for (const auto& p : base) mirrored.emplace_back(-p.x(), p.y()), turned.emplace_back(-p.y(), p.x());
    const Rig a = LayoutRig(base), m = LayoutRig(mirrored), t = LayoutRig(turned);
    const std::vector<int> same = {0, 1, 2, 3, 4, 5};
    const double dm = PermutedDifference(
        a, m, [](Eigen::Vector2d p) { return Eigen::Vector2d(-p.x(), p.y()); }, same);
    const double dt = PermutedDifference(
        a, t, [](Eigen::Vector2d p) { return Eigen::Vector2d(-p.y(), p.x()); }, same);
    MESSAGE("random layout " << seed << ": mirrored " << dm << ", quarter turn " << dt);
    CHECK(dm <= 1e-9);
    CHECK(dt <= 1e-9);
  }
}

TEST_CASE("pose space: inside the hull the weights stay within 0.05 of a thin-plate spline") {
  const Layout snake = Points(samples::SnakeRig()), gingerbread = Points(samples::GingerbreadRig());
  const double ds = ThinPlateDistance(snake), dg = ThinPlateDistance(gingerbread);
  MESSAGE("largest distance from a thin-plate spline inside the hull: snake " << ds << ", gingerbread " << dg);
  CHECK(ds <= 0.05);
  CHECK(dg <= 0.05);
  // Uneven layouts too: points clustered on one side, thin hulls. The grid
  // interpolates the spline linearly, so between two points closer than two
  // cells the weight, going from 1 to 0, is coarse: the bake warns about such
  // pairs (raise bake.grid_resolution), and they are measured here at the
  // resolution that puts them two cells apart.
  for (unsigned seed = 1; seed <= 8; ++seed) {
    CAPTURE(seed);
    const Layout layout = RandomLayout(seed, 6);
    int resolution = 64;
    while (ClosestPairInCells(layout, resolution) < 2) resolution *= 2;
    const double dr = ThinPlateDistance(layout, resolution);
    MESSAGE("random 6-point layout " << seed << ": " << dr << " (closest pair " << ClosestPairInCells(layout, 64)
                                     << " cells apart at 64 cells, measured at " << resolution << ")");
    CHECK(dr <= 0.05);
  }
}

TEST_CASE("pose space: the bake warns about pose points closer than two grid cells") {
  // Random layout 4 puts p1 and p4 0.107 apart: 1.26 cells of 0.0844 at 64 cells.
  const Layout layout = RandomLayout(4, 6);
  auto warnings = [&](int resolution) {
    bake::RigDescription d = LayoutDescription(layout, resolution);
    d.file = "close.json";
    bake::BakeReport report;
    bake::BakeRig(d, &report);
    return report.warnings;
  };
  const std::vector<std::string> at64 = warnings(64);
  REQUIRE(at64.size() == 1);
  CHECK(at64[0] ==
        "close.json: pose points 'p1' and 'p4' are 1.26 pose-space grid cells apart: the weights between them are "
        "interpolated coarsely; bake.grid_resolution 102 (now 64) puts them two cells apart");
  CHECK(warnings(102).empty());
}

TEST_CASE("pose space: the kink at a pose point shrinks with the cell size") {
  // The jump of the slope across a pose point, each slope taken over one
  // cell: a field smooth through the point (the thin-plate spline is C1 there,
  // its jump over h is about 2 a h log h) has a jump that shrinks with the
  // cells; a kink keeps its jump. 'left' is a corner of the hull, so the
  // steps also cross from the spline into the field around it.
  const Layout snake = Points(samples::SnakeRig());
  const ThinPlate tps(snake);
  struct Jump {
    double field, spline;
  };
  auto jump = [&](int resolution) {
    const Rig rig = LayoutRig(snake, resolution);
    const double h = rig.grid().cell;
    Jump worst{0, 0};
    for (const Eigen::Vector2d& d : {Eigen::Vector2d(1, 0), Eigen::Vector2d(0, 1), Eigen::Vector2d(0.6, 0.8)}) {
      const std::vector<double> a = Raw(rig, snake[1] + h * d), b = Raw(rig, snake[1] - h * d), c = Raw(rig, snake[1]);
      const std::vector<double> ta = tps(snake[1] + h * d), tb = tps(snake[1] - h * d), tc = tps(snake[1]);
      for (std::size_t k = 0; k < a.size(); ++k) {
        worst.field = std::max(worst.field, std::abs(a[k] + b[k] - 2 * c[k]) / h);
        worst.spline = std::max(worst.spline, std::abs(ta[k] + tb[k] - 2 * tc[k]) / h);
      }
    }
    return worst;
  };
  const Jump coarse = jump(32), medium = jump(64), fine = jump(128);
  MESSAGE("slope jump at 'left' over one cell (field / thin-plate spline): 32 cells "
          << coarse.field << " / " << coarse.spline << ", 64 " << medium.field << " / " << medium.spline << ", 128 "
          << fine.field << " / " << fine.spline);
  CHECK(medium.field < 0.75 * coarse.field);
  CHECK(fine.field < 0.75 * medium.field);
  // No kink of its own: the field's jump is the spline's.
  CHECK(std::abs(fine.field - fine.spline) <= 0.1 * fine.spline);
}
