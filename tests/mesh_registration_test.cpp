// SPDX-License-Identifier: MIT
// Mapping by deformation (mapping/mesh_registration.h): pose 0's mesh
// deformed onto the other poses' outlines keeps every triangle the right way
// round, puts the boundary on the outlines, follows a rigid motion exactly,
// and keeps the triangles' shapes where a limb turns far.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "posemorph/bake/mapping/mesh_registration.h"
#include "posemorph/bake/mapping/nway_mapping.h"
#include "posemorph/bake/rig_description.h"

namespace pb = posemorph::bake;
namespace pm = posemorph::bake::mapping;
using pm::Point;
using pm::Polygon;

namespace {

// An arm 100 long and 20 wide along a circular arc that turns by `bend`
// radians (0: straight), from its shoulder at the origin: one side out, the
// other back, counter-clockwise.
Polygon BentArm(double bend) {
  const int samples = 200;
  auto centre = [&](double t) -> Point {
    if (std::abs(bend) < 1e-9) return {100 * t, 0};
    const double r = 100 / bend;
    return {r * std::sin(bend * t), r * (1 - std::cos(bend * t))};
  };
  Polygon right, left;
  for (int k = 0; k <= samples; ++k) {
    const double t = double(k) / samples;
    const Point d(std::cos(bend * t), std::sin(bend * t));
    const Point n(-d.y(), d.x());
    right.push_back(centre(t) - 10 * n);
    left.push_back(centre(t) + 10 * n);
  }
  Polygon p = right;
  p.insert(p.end(), left.rbegin(), left.rend());
  return p;
}

// The stages up to the simplified polygons (compatible triangulation, as the default).
pm::MappingStages ArmStages(const std::vector<Polygon>& outlines, const std::vector<std::vector<Point>>& landmarks,
                            bool registration) {
  pb::MappingParameters prm;
  prm.registration = registration;
  std::vector<std::string> labels;
  for (std::size_t k = 0; k < outlines.size(); ++k) labels.push_back("pose " + std::to_string(k));
  return pm::MapPolygons(outlines, landmarks, {}, prm, labels, "arm.json");
}

// Every triangle counter-clockwise in every pose, exactly (grid coordinates).
bool EveryTrianglePositive(const pm::CompatibleMesh& m) {
  for (const pm::Polygon& v : m.vertices)
    for (const auto& t : m.triangles)
      if (pm::Orient(v[t[0]], v[t[1]], v[t[2]]) <= 0) return false;
  return true;
}

std::vector<std::vector<Point>> ArmLandmarks(const std::vector<Polygon>& arms) {
  std::vector<std::vector<Point>> landmarks;
  for (const Polygon& a : arms) landmarks.push_back({a[0], a[200], a[201]});  // shoulder, the tip's two corners
  return landmarks;
}

}  // namespace

TEST_CASE("registration: a rigid motion of the outline moves the mesh rigidly") {
  const Polygon arm = BentArm(0.6);
  const double angle = 2.0;
  const Point shift(40, -25);
  Polygon moved;
  for (const Point& p : arm)
    moved.push_back(Point(std::cos(angle) * p.x() - std::sin(angle) * p.y() + shift.x(),
                          std::sin(angle) * p.x() + std::cos(angle) * p.y() + shift.y()));
  const pm::MappingStages st = ArmStages({arm, moved}, ArmLandmarks({arm, moved}), false);
  const std::vector<Polygon>& polygons = st.simplified.polygons;
  pm::RefinementParameters rp;
  rp.max_edge_length = st.sizes.max_edge_length * st.grid_scale;
  const pm::CompatibleMesh m = pm::RegisterCompatibly(
      polygons, rp, {pb::ErrorSource("arm.json", "pose 0"), pb::ErrorSource("arm.json", "pose 1")}, 100);
  REQUIRE(m.vertices.size() == 2);
  CHECK(EveryTrianglePositive(m));
  CHECK(m.vertices[0].size() > polygons[0].size());  // an interior to follow
  // The polygon's corners go to their corners; every vertex, interior too,
  // where the motion takes it (to the grid's rounding, against the arm's
  // 20-unit width on the grid).
  for (std::size_t v = 0; v < polygons[0].size(); ++v) CHECK(m.vertices[1][v] == polygons[1][v]);
  const double s = st.grid_scale;
  double worst = 0;
  for (std::size_t v = 0; v < m.vertices[0].size(); ++v) {
    const Point p = m.vertices[0][v] / s;
    const Point q(std::cos(angle) * p.x() - std::sin(angle) * p.y() + shift.x(),
                  std::sin(angle) * p.x() + std::cos(angle) * p.y() + shift.y());
    worst = std::max(worst, (m.vertices[1][v] / s - q).norm());
  }
  MESSAGE("rigid motion: the deformed mesh within " << worst << " of the moved one (arm 20 wide)");
  CHECK(worst < 1e-3);
}

TEST_CASE("registration: an arm that turns by 90 and 180 degrees keeps its triangles' shapes") {
  for (double bend : {M_PI / 2, M_PI}) {
    CAPTURE(bend);
    const std::vector<Polygon> arms = {BentArm(0), BentArm(bend)};
    const pm::MappingStages compatible = ArmStages(arms, ArmLandmarks(arms), false);
    const pm::MappingStages registered = ArmStages(arms, ArmLandmarks(arms), true);
    const pm::CompatibleMesh& m = registered.mesh;
    CHECK(EveryTrianglePositive(m));
    CHECK(EveryTrianglePositive(compatible.mesh));
    // The boundary on (or just outside) each pose's simplified polygon: it
    // encloses the outline as the polygon does.
    for (std::size_t k = 0; k < 2; ++k) {
      Polygon boundary;
      for (std::size_t v = 0; v < registered.simplified.polygons[k].size(); ++v) boundary.push_back(m.vertices[k][v]);
      CHECK(boundary == registered.simplified.polygons[k]);
    }
    const double a = pm::MinAngleDegrees(m), b = pm::MinAngleDegrees(compatible.mesh);
    MESSAGE("arm bent by " << bend * 180 / M_PI << " degrees: smallest angle " << a << " by registration ("
                           << m.vertices[0].size() << " vertices), " << b << " triangulated compatibly ("
                           << compatible.mesh.vertices[0].size() << " vertices)");
    CHECK(a >= 15);
    CHECK(a >= b);
  }
}

TEST_CASE("registration: a pose its mesh cannot reach is named") {
  // Pose 1 is pose 0's mirror image, its corners in the same order (so
  // clockwise): only a mesh turned over reaches it.
  const Polygon arm = BentArm(0.6);
  const pm::MappingStages st = ArmStages({arm, arm}, ArmLandmarks({arm, arm}), false);
  Polygon target;
  for (const Point& p : st.simplified.polygons[1]) target.push_back({-p.x(), p.y()});
  pm::RefinementParameters rp;
  rp.max_edge_length = st.sizes.max_edge_length * st.grid_scale;
  const std::vector<pb::ErrorSource> poses = {pb::ErrorSource("arm.json", "pose 'rest' (index 0)"),
                                              pb::ErrorSource("arm.json", "pose 'mirror' (index 1)")};
  try {
    (void)pm::RegisterCompatibly({st.simplified.polygons[0], target}, rp, poses, 100);
    FAIL("a pose that needs a fold was reached");
  } catch (const pb::BakeError& e) {
    CHECK(std::string(e.what()) ==
          "arm.json: pose 'mirror' (index 1): the first pose's mesh cannot be deformed onto this pose's outline "
          "without turning a triangle over");
  }
}
