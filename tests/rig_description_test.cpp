// SPDX-License-Identifier: MIT
// The rig-description writer is the inverse of the reader: what it writes
// reads back to the same description, and adding to a description keeps the
// rest of what it says. And the one command-line number parser.
#include <doctest/doctest.h>

#include <fstream>
#include <iterator>

#include "posemorph/bake/command_line.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/rig_description.h"

namespace pb = posemorph::bake;

namespace {

// A pose made by deforming `from` with the given handles.
pb::PoseDescription DeformedPose(const std::string& name, const Eigen::Vector2d& point, const std::string& from,
                                 const std::vector<pb::HandleDescription>& handles) {
  pb::PoseDescription p;
  p.name = name;
  p.point = point;
  p.deformed = true;
  p.deform.from = from;
  p.deform.handles = handles;
  return p;
}

pb::HandleDescription VertexHandle(std::uint32_t vertex, const Eigen::Vector2d& to) {
  pb::HandleDescription h;
  h.by_vertex = true;
  h.vertex = vertex;
  h.to = to;
  return h;
}

// Everything the writer can express, away from every default.
pb::RigDescription DrawnDescription() {
  pb::RigDescription d;
  d.name = "drawn \"quoted\" rig";
  d.nearest_filter = true;
  pb::PoseDescription a;
  a.name = "rest";
  a.point = {0.1, -0.3};
  a.drawn = true;
  a.drawing = "rest.png";
  a.origin = {12.5, 3};
  a.landmarks = {{1, 2}, {3.25, 4}};
  pb::PoseDescription b;
  b.name = "outline";
  b.point = {1.0 / 3, 2};
  b.drawn = true;
  b.outline = {{0, 0}, {10, 0}, {0, 10.000000000000002}};
  b.landmarks = {{0, 0}};
  pb::HandleDescription at;
  at.at = {-2, 3};
  at.to = {4, -5};
  const pb::PoseDescription c = DeformedPose("lean", {-1, 1e-7}, "rest", {VertexHandle(7, {0.5, 0.25}), at});
  d.poses = {a, b, c};
  d.mapping.simplify_tolerance = 1.5;
  d.mapping.max_steiner_points = 7;
  d.mapping.alpha_threshold = 0.1;
  d.parameters.grid_resolution = 32;
  d.parameters.epsilon = 2.5;
  d.parameters.compact = false;
  d.parameters.max_error_px = 0.02;
  d.parameters.allow_folds = true;
  d.mapping.map_again = false;
  pb::PathDescription p;
  p.name = "walk";
  p.catmull_rom = true;
  p.keys = {{0, 0.1, 0.2}, {0.7, -0.3, 0.4}};
  d.paths = {p};
  return d;
}

void CheckSame(const pb::RigDescription& x, const pb::RigDescription& y) {
  CHECK(x.name == y.name);
  CHECK(x.nearest_filter == y.nearest_filter);
  CHECK(x.triangles == y.triangles);
  REQUIRE(x.poses.size() == y.poses.size());
  for (std::size_t i = 0; i < x.poses.size(); ++i) {
    const pb::PoseDescription &p = x.poses[i], &q = y.poses[i];
    CHECK(p.name == q.name);
    CHECK(p.point == q.point);
    CHECK(p.vertices == q.vertices);
    CHECK(p.image == q.image);
    CHECK(p.uvs == q.uvs);
    CHECK(p.drawn == q.drawn);
    CHECK(p.drawing == q.drawing);
    CHECK(p.outline == q.outline);
    CHECK(p.landmarks == q.landmarks);
    CHECK(p.origin == q.origin);
    CHECK(p.deformed == q.deformed);
    CHECK(p.deform.from == q.deform.from);
    REQUIRE(p.deform.handles.size() == q.deform.handles.size());
    for (std::size_t h = 0; h < p.deform.handles.size(); ++h) {
      CHECK(p.deform.handles[h].by_vertex == q.deform.handles[h].by_vertex);
      CHECK(p.deform.handles[h].vertex == q.deform.handles[h].vertex);
      CHECK(p.deform.handles[h].at == q.deform.handles[h].at);
      CHECK(p.deform.handles[h].to == q.deform.handles[h].to);
    }
  }
  const pb::MappingParameters &m = x.mapping, &n = y.mapping;
  CHECK(m.simplify_tolerance == n.simplify_tolerance);
  CHECK(m.max_edge_length == n.max_edge_length);
  CHECK(m.min_angle == n.min_angle);
  CHECK(m.alpha_threshold == n.alpha_threshold);
  CHECK(m.curve_tolerance == n.curve_tolerance);
  CHECK(m.spacing == n.spacing);
  CHECK(m.landmark_distance == n.landmark_distance);
  CHECK(m.max_steiner_points == n.max_steiner_points);
  CHECK(m.max_vertices == n.max_vertices);
  CHECK(m.map_again == n.map_again);
  const pb::BakeParameters &b = x.parameters, &c = y.parameters;
  CHECK(b.grid_resolution == c.grid_resolution);
  CHECK(b.margin == c.margin);
  CHECK(b.epsilon == c.epsilon);
  CHECK(b.sigma == c.sigma);
  CHECK(b.compact == c.compact);
  CHECK(b.max_error_px == c.max_error_px);
  CHECK(b.pixels_per_unit == c.pixels_per_unit);
  CHECK(b.allow_folds == c.allow_folds);
  REQUIRE(x.paths.size() == y.paths.size());
  for (std::size_t i = 0; i < x.paths.size(); ++i) {
    CHECK(x.paths[i].name == y.paths[i].name);
    CHECK(x.paths[i].loop == y.paths[i].loop);
    CHECK(x.paths[i].catmull_rom == y.paths[i].catmull_rom);
    CHECK(x.paths[i].keys == y.paths[i].keys);
  }
}

}  // namespace

TEST_CASE("a drawn description written and read back is the same description, every value exact") {
  const pb::RigDescription d = DrawnDescription();
  const std::string text = pb::RigDescriptionText(d);
  const pb::RigDescription back = pb::ParseRigDescription(text, "written.json", "/drawings");
  CHECK(back.warnings.empty());
  CHECK(back.poses[0].drawing_path == "/drawings/rest.png");
  CheckSame(d, back);
  CHECK(pb::RigDescriptionText(back) == text);
}

TEST_CASE("a description of vertices, uvs and images written and read back is the same description") {
  pb::RigDescription d;
  d.name = "plate";
  d.triangles = {{0, 1, 2}, {0, 2, 3}};
  for (int i = 0; i < 2; ++i) {
    pb::PoseDescription p;
    p.name = "p" + std::to_string(i);
    p.point = {double(i), 0};
    p.vertices = {{0, 0}, {1 + 0.1 * i, 0}, {1, 1}, {0, 1.0 / 7}};
    p.image = "p" + std::to_string(i) + ".png";
    p.uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0.125f}};
    d.poses.push_back(p);
  }
  const pb::RigDescription back = pb::ParseRigDescription(pb::RigDescriptionText(d), "plate.json", ".");
  CHECK(back.warnings.empty());
  CheckSame(d, back);
}

TEST_CASE("a mesh file is written with its vertices and triangles, doubles exact to the last digit") {
  const std::vector<Eigen::Vector2d> vertices = {{0, 0}, {0.1, 0}, {0, 1.0 / 3}};
  const std::string mesh = pb::MeshFileText(vertices, {{0, 1, 2}});
  CHECK(mesh == "{\"triangles\":[[0,1,2]],\"vertices\":[[0.0,0.0],[0.1,0.0],[0.0,0.3333333333333333]]}\n");
}

TEST_CASE("adding poses and paths keeps the rest of the description and gives each a fresh name") {
  const std::string text =
      R"({"posemorph": 1, "studio_note": "kept", "triangles": [[0, 1, 2]],
          "poses": [{"name": "a", "point": [0, 0], "vertices": [[0, 0], [1, 0], [0, 1]]},
                    {"name": "edit-1", "point": [1, 0], "vertices": [[0, 0], [2, 0], [0, 1]]}]})";
  const pb::PoseDescription pose = DeformedPose("edit", {0.5, 0.5}, "a", {VertexHandle(1, {3, 0})});
  pb::PathDescription path;
  path.name = "gesture";
  path.loop = true;
  path.keys = {{0, 0, 0}, {1, 1, 0}};
  const pb::DescriptionAddition added = pb::AddToRigDescription(text, "rig.json", {pose, pose}, {path});
  CHECK(added.pose_names == std::vector<std::string>{"edit-2", "edit-3"});
  CHECK(added.path_names == std::vector<std::string>{"gesture-1"});
  CHECK(added.text.find("\"studio_note\": \"kept\"") != std::string::npos);
  const pb::RigDescription back = pb::ParseRigDescription(added.text, "rig.json", ".");
  REQUIRE(back.poses.size() == 4);
  CHECK(back.poses[3].name == "edit-3");
  CHECK(back.poses[3].deform.handles[0].to == Eigen::Vector2d(3, 0));
  REQUIRE(back.paths.size() == 1);
  CHECK(back.paths[0].keys == path.keys);
  CHECK(back.warnings == std::vector<std::string>{"rig.json: unknown key \"studio_note\" ignored "
                                                  "(bake/RIG_DESCRIPTION.md lists the keys)"});
}

TEST_CASE("a path added to a rig with channels goes to the first channel's paths, a pose is refused") {
  std::ifstream in(std::string(POSEMORPH_SOURCE_DIR) + "/assets/pell/pell-face.json");
  REQUIRE(in.good());
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  pb::PathDescription path;
  path.name = "gesture";
  path.keys = {{0, 0, 0}, {1, 1, 0}};
  const pb::DescriptionAddition added = pb::AddToRigDescription(text, "pell-face.json", {}, {path});
  CHECK(added.path_names == std::vector<std::string>{"gesture-1"});
  const pb::RigDescription back = pb::ParseRigDescription(added.text, "pell-face.json", ".");
  REQUIRE(back.channels.size() == 2);
  REQUIRE(back.channels[0].paths.size() == 2);  // greet, then the gesture
  CHECK(back.channels[0].paths[1].name == "gesture-1");
  CHECK(back.channels[1].paths.size() == 1);
  CHECK(back.paths.size() == 2);
  try {
    pb::AddToRigDescription(text, "pell-face.json", {DeformedPose("edit", {0.5, 0.5}, "rest", {})}, {});
    FAIL("a pose was added to a rig with channels");
  } catch (const pb::BakeError& e) {
    CHECK(std::string(e.what()).find("pell-face.json: a rig with channels takes a new pose") == 0);
  }
}

TEST_CASE("adding to text that is not a description object names the file and the problem") {
  auto message = [](const std::string& text) {
    try {
      pb::AddToRigDescription(text, "rig.json", {}, {pb::PathDescription{}});
    } catch (const pb::BakeError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(message("[1, 2]") == "rig.json: expected a JSON object at the top level");
  CHECK(message("{\"paths\": 3}") == "rig.json: paths: expected an array");
  CHECK(message("{").rfind("rig.json: invalid JSON: ", 0) == 0);
}

TEST_CASE("command-line numbers: one parser for posemorph-bake and posemorph-view") {
  using posemorph::bake::ParseNumber;
  using posemorph::bake::ParseNumbers;
  using posemorph::bake::ParseWholeNumber;
  CHECK(ParseNumber("2") == 2.0);
  CHECK(ParseNumber("-0.5") == -0.5);
  CHECK(ParseNumber("+.25") == 0.25);
  CHECK(ParseNumber("1e-3") == 1e-3);
  CHECK(ParseNumber("0.1") == 0.1);  // the nearest double, as the compiler reads it
  for (const char* refused :
       {"", " 1", "1 ", "1x", "0x10", "inf", "-inf", "nan", ".", "e5", "1e", "1e+", "--1", "1e400"})
    CHECK_MESSAGE(!ParseNumber(refused), refused);
  CHECK(ParseWholeNumber("3", 1, 5) == 3);
  CHECK(ParseWholeNumber("3.0", 1, 5) == 3);
  CHECK(ParseWholeNumber("1e2", 0, 100) == 100);
  CHECK(!ParseWholeNumber("3.5", 1, 5));
  CHECK(!ParseWholeNumber("6", 1, 5));
  CHECK(!ParseWholeNumber("0", 1, 5));
  CHECK(ParseNumbers("0.4,-0.6", ',') == std::vector<double>{0.4, -0.6});
  CHECK(ParseNumbers("7", ',') == std::vector<double>{7});
  CHECK(!ParseNumbers("0.4,", ','));
  CHECK(!ParseNumbers(",1", ','));
  CHECK(!ParseNumbers("1,,2", ','));
}
