// N-way mapping: outlines, correspondence, enclosing simplification and
// compatible triangulation, on shapes generated here and on the drawn samples.
#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <map>

#include "posemorph/bake/bake.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/mapping/nway_mapping.h"
#include "posemorph/bake/rig_description.h"

namespace pb = posemorph::bake;
namespace pm = posemorph::bake::mapping;
using pm::Point;
using pm::Polygon;

namespace {

Polygon Star(int points, double r_out, double r_in, double turn) {
  Polygon p;
  for (int k = 0; k < 2 * points; ++k) {
    const double a = turn + M_PI * k / points;
    const double r = k % 2 ? r_in : r_out;
    p.push_back({r * std::cos(a), r * std::sin(a)});
  }
  return p;
}

// A band around a centre line c(t), t in [0, 1], of half-width w: one side out, the other back.
Polygon Band(const std::function<Point(double)>& c, double w, int samples) {
  Polygon left, right;
  for (int k = 0; k <= samples; ++k) {
    const double t = double(k) / samples, h = 1e-4;
    const Point d = (c(std::min(1.0, t + h)) - c(std::max(0.0, t - h))).normalized();
    const Point n(-d.y(), d.x());
    right.push_back(c(t) - w * n);
    left.push_back(c(t) + w * n);
  }
  Polygon p = right;
  p.insert(p.end(), left.rbegin(), left.rend());
  return p;
}

Polygon Spiral(double turns, double width) {
  return Band([&](double t) {
    const double a = t * turns * 2 * M_PI, r = 20 + 60 * t;
    return Point(r * std::cos(a), r * std::sin(a));
  }, width, 160);
}

Polygon SShape(double amplitude, double width) {
  return Band([&](double t) { return Point(200 * t, amplitude * std::sin(2 * M_PI * t)); }, width, 120);
}

Polygon Comb(int teeth, double bend) {
  // Spine along the bottom, teeth up, each tooth leaning by `bend` (x offset at its tip).
  Polygon p{{0, 0}, {20.0 * teeth, 0}};
  for (int k = teeth - 1; k >= 0; --k) {
    const double x0 = 20.0 * k;
    p.push_back({x0 + 14, 12});
    p.push_back({x0 + 14 + bend, 80});
    p.push_back({x0 + 6 + bend, 80});
    p.push_back({x0 + 6, 12});
  }
  p.push_back({0, 12});
  return p;
}

Polygon DeepC(double opening) {  // a C whose mouth narrows to `opening`
  Polygon p;
  const int n = 90;
  for (int k = 0; k <= n; ++k) {
    const double a = opening + (2 * M_PI - 2 * opening) * k / n;
    p.push_back({100 * std::cos(a), 100 * std::sin(a)});
  }
  for (int k = n; k >= 0; --k) {
    const double a = opening + (2 * M_PI - 2 * opening) * k / n;
    p.push_back({60 * std::cos(a), 60 * std::sin(a)});
  }
  return p;
}

Polygon Transformed(const Polygon& p, double angle, double scale, const Point& shift) {
  Polygon out;
  const double c = std::cos(angle), s = std::sin(angle);
  for (const Point& q : p) out.push_back(Point(c * q.x() - s * q.y(), s * q.x() + c * q.y()) * scale + shift);
  return out;
}

pb::RigDescription OutlineRig(const std::vector<Polygon>& outlines) {
  pb::RigDescription rig;
  rig.file = "corpus.json";
  for (std::size_t i = 0; i < outlines.size(); ++i) {
    pb::PoseDescription pose;
    pose.name = "pose" + std::to_string(i);
    pose.point = Point(std::cos(2.0 * M_PI * i / outlines.size()), std::sin(2.0 * M_PI * i / outlines.size()));
    pose.drawn = true;
    pose.outline = outlines[i];
    pose.landmarks = {outlines[i][0]};
    rig.poses.push_back(pose);
  }
  return rig;
}

double Orient2(const Point& a, const Point& b, const Point& c) {
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

// Every triangle positive in every pose, one connectivity (shared by construction), and the rig bakes.
void CheckCompatible(pb::RigDescription& rig) {
  for (const auto& pose : rig.poses) {
    REQUIRE(pose.vertices.size() == rig.poses[0].vertices.size());
    for (const auto& t : rig.triangles)
      REQUIRE(Orient2(pose.vertices[t[0]], pose.vertices[t[1]], pose.vertices[t[2]]) > 0);
  }
  pb::BakeReport report;
  CHECK_NOTHROW(pb::BakeRig(rig, &report));
}

}  // namespace

TEST_CASE("mapping: robustness corpus triangulates compatibly") {
  std::map<std::string, std::vector<Polygon>> corpus;
  for (int n = 2; n <= 8; ++n) {
    std::vector<Polygon> stars;
    for (int i = 0; i < n; ++i) stars.push_back(Star(5 + (n % 3), 100, 30 + 6 * i, 0.15 * i));
    corpus["star x" + std::to_string(n)] = stars;
  }
  corpus["spirals"] = {Spiral(1.2, 8), Spiral(1.5, 7), Spiral(0.9, 9), Spiral(1.7, 6)};
  corpus["thin S"] = {SShape(40, 3), SShape(-30, 3), SShape(5, 4), SShape(60, 2.5)};
  corpus["combs"] = {Comb(6, 0), Comb(6, 12), Comb(6, -10), Comb(6, 5), Comb(6, -4)};
  corpus["deep C"] = {DeepC(0.6), DeepC(0.08), DeepC(1.2)};
  corpus["spiral vs S"] = {Spiral(1.5, 8), SShape(50, 8)};
  for (auto& [name, shapes] : corpus) {
    CAPTURE(name);
    pb::RigDescription rig = OutlineRig(shapes);
    REQUIRE_NOTHROW(pb::MapDrawings(rig));
    const pb::MappingReport& r = rig.mapping_report;
    MESSAGE(name << ": " << r.matched_vertices << " matched -> " << r.boundary_vertices << " boundary, "
                 << r.steiner_points << " Steiner, " << r.vertices << " vertices, " << r.triangles
                 << " triangles, min angle " << r.min_angle_degrees << ", " << r.seconds * 1e3 << " ms");
    CheckCompatible(rig);
  }
}
