// SPDX-License-Identifier: MIT
// Features: points inside the shape that correspond across poses (an eye's
// centre) become one shared mesh vertex at exactly that point in every pose,
// with every triangle positive in every pose; bad feature lists are refused
// naming the pose and the feature (interior_features.h).
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "posemorph/bake/bake.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/mapping/nway_mapping.h"
#include "posemorph/bake/rig_description.h"
#include "posemorph/rig.h"

namespace pb = posemorph::bake;
namespace pm = posemorph::bake::mapping;
using pm::Point;
using pm::Polygon;

namespace {

// A head-like ellipse centred at c with half-axes a, b, starting at its right.
Polygon Ellipse(Point c, double a, double b, int samples = 96) {
  Polygon p;
  for (int k = 0; k < samples; ++k) {
    const double t = 2 * M_PI * k / samples;
    p.push_back(c + Point(a * std::cos(t), b * std::sin(t)));
  }
  return p;
}

// Three poses of a head whose eyes move inside it: level, looking left and
// down (the head squashed), looking up-right (the head moved and tilted).
struct Head {
  std::vector<Polygon> outlines{Ellipse({0, 0}, 60, 50), Ellipse({0, -5}, 70, 42), Ellipse({12, 8}, 55, 56)};
  std::vector<std::vector<Point>> landmarks{{{60, 0}}, {{70, -5}}, {{67, 8}}};
  std::vector<std::vector<Point>> eyes{{{-20, 12}, {20, 12}}, {{-42, 0}, {-4, -2}}, {{6, 30}, {44, 26}}};
  std::vector<std::string> labels{"pose 'level' (index 0)", "pose 'left' (index 1)", "pose 'up' (index 2)"};
};

bool AllPositive(const pm::CompatibleMesh& mesh) {
  for (const Polygon& pos : mesh.vertices)
    for (const auto& t : mesh.triangles) {
      const Point u = pos[t[1]] - pos[t[0]], v = pos[t[2]] - pos[t[0]];
      if (!(u.x() * v.y() - u.y() * v.x() > 0)) return false;
    }
  return true;
}

pb::RigDescription HeadDescription(const Head& h) {
  pb::RigDescription d;
  d.file = "head.json";
  for (std::size_t k = 0; k < h.outlines.size(); ++k) {
    pb::PoseDescription p;
    p.name = h.labels[k].substr(6, h.labels[k].find('\'', 6) - 6);
    p.point = Eigen::Vector2d(double(k), k == 2 ? 1.0 : 0.0);
    p.drawn = true;
    p.outline = h.outlines[k];
    p.landmarks = h.landmarks[k];
    p.features = h.eyes[k];
    d.poses.push_back(p);
  }
  d.parameters.compact = false;
  return d;
}

}  // namespace

TEST_CASE("features: each is one shared vertex at its point in every pose, every triangle positive") {
  const Head h;
  pb::MappingParameters prm;
  const pm::MappingStages st = pm::MapPolygons(h.outlines, h.landmarks, h.eyes, prm, h.labels, "head.json");
  REQUIRE(st.mesh.features.size() == 2);
  CHECK(AllPositive(st.mesh));
  double worst = 0;
  for (std::size_t k = 0; k < 3; ++k)
    for (std::size_t f = 0; f < 2; ++f)
      worst = std::max(worst, (st.mesh.vertices[k][st.mesh.features[f]] / st.grid_scale - h.eyes[k][f]).norm());
  const double angle = pm::MinAngleDegrees(st.mesh);
  MESSAGE("features: largest distance from its point " << worst << " (grid step " << 1 / st.grid_scale
                                                       << "), smallest angle " << angle << " degrees, "
                                                       << st.mesh.vertices[0].size() << " vertices");
  CHECK(worst <= 0.5 / st.grid_scale);  // the grid's rounding, about 1e-5 here
  CHECK(angle > 10);
  // Without features the eyes' points land elsewhere in the other poses: the
  // outline's correspondence alone does not put them there.
  const pm::MappingStages plain = pm::MapPolygons(h.outlines, h.landmarks, {}, prm, h.labels, "head.json");
  CHECK(plain.mesh.features.empty());
}

TEST_CASE("features: the baked rig holds them, and a rig without them does not") {
  const Head h;
  const std::vector<unsigned char> bytes = pb::BakeRig(HeadDescription(h));
  posemorph::Rig rig;
  posemorph::Error err;
  REQUIRE_MESSAGE(posemorph::LoadRig(bytes.data(), bytes.size(), &rig, &err), err.message);
  // The vertex at each eye in pose 0 is at that eye in every pose.
  for (std::size_t f = 0; f < 2; ++f) {
    CAPTURE(f);
    const posemorph::Span<const double> p0 = rig.pose_positions(0);
    std::uint32_t nearest = 0;
    for (std::uint32_t v = 1; v < rig.vertex_count(); ++v)
      if (std::hypot(p0[2 * v] - h.eyes[0][f].x(), p0[2 * v + 1] - h.eyes[0][f].y()) <
          std::hypot(p0[2 * nearest] - h.eyes[0][f].x(), p0[2 * nearest + 1] - h.eyes[0][f].y()))
        nearest = v;
    for (std::uint32_t k = 0; k < 3; ++k) {
      const posemorph::Span<const double> p = rig.pose_positions(k);
      CHECK(std::hypot(p[2 * nearest] - h.eyes[k][f].x(), p[2 * nearest + 1] - h.eyes[k][f].y()) <= 1e-4);
    }
  }
}

TEST_CASE("features: bad lists are refused naming the pose and the feature") {
  const Head h;
  pb::MappingParameters prm;
  auto error = [&](const std::vector<std::vector<Point>>& eyes) {
    try {
      pm::MapPolygons(h.outlines, h.landmarks, eyes, prm, h.labels, "head.json");
    } catch (const pb::BakeError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  std::vector<std::vector<Point>> eyes = h.eyes;
  eyes[1].pop_back();
  CHECK(error(eyes) ==
        "head.json: pose 'left' (index 1): gives 1 feature(s) but pose 'level' (index 0) gives 2; every drawn pose "
        "lists the same features in the same order");
  eyes = h.eyes;
  eyes[2][1] = {80, 26};  // beyond the head's right side
  CHECK(error(eyes) ==
        "head.json: pose 'up' (index 2): feature 1 lies outside the outline (or on it): features are points inside "
        "the shape");
  eyes = h.eyes;
  eyes[0][1] = {-18, 12};  // 2 units from the other eye; the mesh's longest edge is 15.6 (a tenth of the size)
  const std::string close = error(eyes);
  CHECK(close.find("head.json: pose 'level' (index 0): features 0 and 1 are 2 apart, closer than the mesh "
                   "resolution") == 0);
  // Listed in the other order in one pose: the eyes would have to pass
  // through each other.
  eyes = h.eyes;
  std::swap(eyes[1][0], eyes[1][1]);
  const std::string swapped = error(eyes);
  CHECK(swapped.find("head.json: pose 'left' (index 1): feature ") == 0);
  CHECK(swapped.find("cannot be moved to its point without turning a triangle over") != std::string::npos);
  CHECK(swapped.find("in the same order in every pose") != std::string::npos);
  // A mesh pose has no features.
  CHECK_THROWS_WITH(
      pb::ParseRigDescription(R"({"posemorph": 1, "triangles": [[0, 1, 2]], "poses": [
        {"name": "a", "point": [0, 0], "vertices": [[0, 0], [1, 0], [0, 1]], "features": [[0.2, 0.2]]},
        {"name": "b", "point": [1, 0], "vertices": [[0, 0], [1, 0], [0, 1]]}]})",
                              "mesh.json", "."),
      "mesh.json: poses[0].features: only a drawn pose (a drawing or an outline) has features; a mesh's vertices "
      "correspond already");
}

TEST_CASE("features: Pip's eye centres are one vertex each, on the drawn eyes in every pose") {
  // The eyes' centres in Pip's SVG sources (assets/pip/*.svg: the white
  // circles; squash draws closed eyes, the chevrons' centres), drawing
  // coordinates; Pip's rig coordinates are (x, -y).
  const double eyes[5][2][2] = {{{110, 108}, {146, 108}},
                                {{114, 70}, {142, 70}},
                                {{108, 156}, {148, 156}},
                                {{110, 106}, {146, 106}},
                                {{98, 104}, {133, 100}}};
  pb::RigDescription d = pb::ReadRigDescription(std::string(POSEMORPH_DRAWN_SAMPLES) + "/pip/pip.json");
  d.parameters.compact = false;
  const std::vector<unsigned char> bytes = pb::BakeRig(d);
  posemorph::Rig rig;
  posemorph::Error err;
  REQUIRE_MESSAGE(posemorph::LoadRig(bytes.data(), bytes.size(), &rig, &err), err.message);
  REQUIRE(rig.pose_count() == 5);
  for (int f = 0; f < 2; ++f) {
    CAPTURE(f);
    // The vertex nearest the eye in the rest pose.
    const posemorph::Span<const double> rest = rig.pose_positions(0);
    std::uint32_t v = 0;
    auto distance = [&](const posemorph::Span<const double>& p, std::uint32_t u, int k) {
      return std::hypot(p[2 * u] - eyes[k][f][0], p[2 * u + 1] + eyes[k][f][1]);
    };
    for (std::uint32_t u = 1; u < rig.vertex_count(); ++u)
      if (distance(rest, u, 0) < distance(rest, v, 0)) v = u;
    double worst = 0;
    for (int k = 0; k < 5; ++k) worst = std::max(worst, distance(rig.pose_positions(std::uint32_t(k)), v, k));
    MESSAGE("eye " << f << ": vertex " << v << ", largest distance from the drawn eye " << worst << " px");
    CHECK(worst <= 1e-4);  // the mapping grid's rounding
  }
}
