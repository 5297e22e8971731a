// SPDX-License-Identifier: MIT
// Layered characters in the bake ("parts" and "glue"): the joint held by one
// shared vertex against the same parts solved independently, draw order,
// the compact encoding, and every bad-input message naming part and pose.
#include <doctest/doctest.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <filesystem>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli.h"
#include "posemorph/bake/bake.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/rig_description.h"
#include "posemorph/draw_list.h"
#include "posemorph/jobs.h"
#include "posemorph/path.h"
#include "posemorph/rig.h"
#include "posemorph/rig_format.h"

using namespace posemorph;
using nlohmann::json;

namespace {

// tests/runtime/rigs/arm.json (make_arm.py): a body and an arm glued at the
// shoulder; the arm turns 120 degrees about it from rest to up.
json ArmRig() {
  std::ifstream in(std::string(POSEMORPH_SOURCE_DIR) + "/tests/runtime/rigs/arm.json");
  REQUIRE(in.good());
  return json::parse(in);
}

Rig Bake(const json& description, bool exact = true) {
  json d = description;
  d["bake"]["precision"] = exact ? "exact" : "compact";
  const bake::RigDescription rig = bake::ParseRigDescription(d.dump(), "arm.json", ".");
  const std::vector<unsigned char> bytes = bake::BakeRig(rig);
  Rig out;
  Error err;
  REQUIRE_MESSAGE(LoadRig(bytes.data(), bytes.size(), &out, &err), err.message);
  return out;
}

std::vector<double> LayeredMorphAt(const Rig& rig, double px, double py) {
  const std::size_t N = rig.pose_count();
  std::vector<double> w(N), ws(N), tex(N), work(rig.morph_workspace_size()), x(2 * std::size_t(rig.vertex_count()));
  WeightsJob weights;
  weights.rig = &rig;
  weights.x = px, weights.y = py;
  weights.raw = {w.data(), N}, weights.limited = {ws.data(), N}, weights.texture = {tex.data(), N};
  REQUIRE(weights.Run());
  MorphJob morph;
  morph.rig = &rig;
  morph.weights = {w.data(), N}, morph.limited_weights = {ws.data(), N};
  morph.workspace = {work.data(), work.size()}, morph.positions = {x.data(), x.size()};
  REQUIRE(morph.Run());
  return x;
}

// The vertex at `at` in pose 0.
std::uint32_t VertexAt(const Rig& rig, double x, double y) {
  const double* p = rig.pose_positions(0).data;
  for (std::uint32_t v = 0; v < rig.vertex_count(); ++v)
    if (std::hypot(p[2 * v] - x, p[2 * v + 1] - y) < 1e-9) return v;
  FAIL("no vertex at (" << x << ", " << y << ")");
  return 0;
}

json OnePart(const json& rig, int part) {
  json one = rig;
  one["parts"] = json::array({rig["parts"][part]});
  one.erase("glue");
  return one;
}

std::string LayeredBakeError(const json& description, const char* file = nullptr) {
  try {
    const bake::RigDescription rig = bake::ParseRigDescription(description.dump(), file ? file : "arm.json", ".");
    bake::BakeRig(rig);
  } catch (const bake::BakeError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("layered: the glued shoulder holds along the path, where the same parts solved independently drift apart") {
  const json description = ArmRig();
  const double jx = description["glue"][0]["at"][0][0], jy = description["glue"][0]["at"][0][1];
  const Rig glued = Bake(description), body = Bake(OnePart(description, 0)), arm = Bake(OnePart(description, 1));
  const std::uint32_t joint = VertexAt(glued, jx, jy), body_joint = VertexAt(body, jx, jy),
                      arm_joint = VertexAt(arm, jx, jy);
  // Every triangle touching the joint on either part uses this one vertex.
  int users_body = 0, users_arm = 0;
  for (std::uint32_t t = 0; t < glued.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k)
      if (glued.triangles()[3 * t + k] == joint) (t < glued.part(1).first_triangle ? users_body : users_arm)++;
  CHECK(users_body > 0);
  CHECK(users_arm > 0);
  // Along the path: the glued arm's joint is where the glued body's is (the
  // residual is exactly 0); independent solves place each part by its own
  // centroid, and the arm's end slides off the shoulder along a chord.
  const PathView path = glued.path(0);
  double drift = 0, tip_error = 0;
  const double* rest = glued.pose_positions(0).data;
  const std::uint32_t glued_tip = glued.vertex_count() - 1;  // the arm's far corner (u = 40, v = 5 in make_arm.py)
  const double rest_length =
      std::hypot(rest[2 * glued_tip] - rest[2 * joint], rest[2 * glued_tip + 1] - rest[2 * joint + 1]);
  for (int k = 0; k <= 40; ++k) {
    double px = 0, py = 0;
    REQUIRE(SamplePath(path, path.end_time() * k / 40.0, &px, &py));
    const std::vector<double> b = LayeredMorphAt(body, px, py), a = LayeredMorphAt(arm, px, py),
                              g = LayeredMorphAt(glued, px, py);
    drift =
        std::max(drift, std::hypot(a[2 * arm_joint] - b[2 * body_joint], a[2 * arm_joint + 1] - b[2 * body_joint + 1]));
    const double length = std::hypot(g[2 * glued_tip] - g[2 * joint], g[2 * glued_tip + 1] - g[2 * joint + 1]);
    tip_error = std::max(tip_error, std::fabs(length - rest_length));
  }
  MESSAGE("independent solves: the shoulder drifts up to " << drift
                                                           << " units apart; glued: 0 (one vertex); the glued "
                                                              "arm's tip stays within "
                                                           << tip_error << " units of its length " << rest_length);
  // About 1.9 units (7.6 px at the rig's 4 px per unit) between the poses,
  // where the arm's end slides along a chord: 30 times the 0.25 px bound.
  CHECK(drift > 1.0);
  CHECK(tip_error < 0.01 * rest_length);
}

TEST_CASE("layered: each part's base poses are reproduced, exact and compact, and the part table survives both") {
  const json description = ArmRig();
  for (bool exact : {true, false}) {
    CAPTURE(exact);
    const Rig rig = Bake(description, exact);
    CHECK(rig.compact_encoding() == !exact);
    REQUIRE(rig.part_count() == 2);
    CHECK(rig.part(1).triangle_count == 16);
    const double tolerance = exact ? 1e-9 * rig.bounding_box_diagonal() : 0.01 / 4;  // 0.01 px at 4 px per unit
    for (std::uint32_t i = 0; i < rig.pose_count(); ++i) {
      const std::vector<double> x = LayeredMorphAt(rig, rig.pose_points()[2 * i], rig.pose_points()[2 * i + 1]);
      double worst = 0;
      for (std::size_t k = 0; k < x.size(); ++k) worst = std::max(worst, std::fabs(x[k] - rig.pose_positions(i)[k]));
      CHECK(worst <= tolerance);
    }
  }
}

TEST_CASE("layered: draw order is the parts' order, lower first, ties in part order") {
  json description = ArmRig();
  description["parts"][0]["order"] = 5;  // the body in front of the arm
  Rig rig = Bake(description);
  REQUIRE(rig.draw_sequence().size == 2);
  CHECK(rig.draw_sequence()[0] == 1);
  CHECK(rig.draw_sequence()[1] == 0);
  CHECK(rig.part(0).draw_order == 5);
  description["parts"][0]["order"] = -3;
  description["parts"][1]["order"] = -3;
  rig = Bake(description);
  CHECK(rig.draw_sequence()[0] == 0);
  CHECK(rig.draw_sequence()[1] == 1);
  CHECK(rig.part(1).draw_order == -3);
}

TEST_CASE("layered: the draw order may change with the pose, and the dominant drawing's pose decides each frame's") {
  json description = ArmRig();
  description["parts"][1]["order"] = json::array({-1, -1, 1});  // the arm behind the body, then in front when up
  for (bool exact : {true, false}) {
    CAPTURE(exact);
    const Rig rig = Bake(description, exact);
    REQUIRE(rig.draw_order_changes());
    CHECK(rig.part(1).draw_order == -1);  // pose 0's
    CHECK(rig.part_draw_order(1, 0) == -1);
    CHECK(rig.part_draw_order(1, 2) == 1);
    CHECK(rig.part_draw_order(0, 2) == 0);
    CHECK(rig.part_draw_order(2, 0) == 0);  // beyond the parts
    CHECK(rig.draw_sequence(3).size == 0);  // beyond the poses
    const std::vector<std::vector<std::uint32_t>> expected = {{1, 0}, {1, 0}, {0, 1}};
    for (std::uint32_t i = 0; i < 3; ++i) {
      const Span<const std::uint32_t> sequence = rig.draw_sequence(i);
      CHECK(std::vector<std::uint32_t>(sequence.data, sequence.data + sequence.size) == expected[i]);
    }
    // Sweep the path's line: each frame draws in its first drawing's pose's
    // order, and the arm comes to the front once 'up' dominates.
    const std::size_t count = 41;
    std::vector<double> points;
    for (std::size_t k = 0; k < count; ++k) points.insert(points.end(), {2.0 * double(k) / double(count - 1), 0.0});
    const CharacterBuffers buffers = CharacterBuffers::For(rig, count);
    std::vector<double> block((buffers.bytes + sizeof(double) - 1) / sizeof(double));
    DrawListJob job;
    REQUIRE(buffers.Bind(rig, block.data(), block.size() * sizeof(double), &job));
    job.points = {points.data(), points.size()};
    REQUIRE(job.Run());
    int switches = 0;
    for (std::size_t k = 0; k < count; ++k) {
      const DrawList& list = job.output[k];
      const Span<const std::uint32_t> want = rig.draw_sequence(list.drawings[0].pose);
      REQUIRE(list.parts.size == 2);
      CHECK(list.parts.data == want.data);
      if (k > 0 && list.parts[1] != job.output[k - 1].parts[1]) ++switches;
    }
    CHECK(job.output[0].parts[1] == 0);          // rest: the body in front
    CHECK(job.output[count - 1].parts[1] == 1);  // up: the arm in front
    CHECK(switches == 1);
  }
  // One order per pose, all equal: a fixed order, no PORD.
  description["parts"][1]["order"] = json::array({2, 2, 2});
  const Rig fixed = Bake(description);
  CHECK_FALSE(fixed.draw_order_changes());
  CHECK(fixed.part(1).draw_order == 2);
  CHECK(fixed.draw_sequence(2).data == fixed.draw_sequence(0).data);
  // Bad orders.
  description["parts"][1]["order"] = json::array({1, 2});
  CHECK(LayeredBakeError(description) ==
        "arm.json: parts[1].order: part 'arm' has 2 draw orders, the rig 3 poses: give one order, or one per pose");
  description["parts"][1]["order"] = json::array({1, 2, 0.5});
  CHECK(LayeredBakeError(description) ==
        "arm.json: parts[1].order[2]: expected an integer in -1000000..1000000 (lower "
        "draws first)");
}

TEST_CASE("layered: the loader refuses per-pose draw orders that disagree with the part table or lack their flag") {
  json description = ArmRig();
  description["parts"][1]["order"] = json::array({-1, -1, 1});
  description["bake"]["precision"] = "exact";
  std::vector<unsigned char> bytes = bake::BakeRig(bake::ParseRigDescription(description.dump(), "arm.json", "."));
  RigSection sections[format::kMaxSections];
  std::uint32_t count = 0;
  REQUIRE(ReadRigSections(bytes.data(), bytes.size(), sections, format::kMaxSections, &count));
  std::uint64_t pord_at = 0, meta_at = 0;
  for (std::uint32_t k = 0; k < count; ++k) {
    if (sections[k].tag == format::kPartPoseOrders) pord_at = sections[k].offset;
    if (sections[k].tag == format::kMeta) meta_at = sections[k].offset;
  }
  REQUIRE(pord_at != 0);
  LoadOptions no_checksum;
  no_checksum.verify_checksum = false;
  const auto refused = [&](const std::vector<unsigned char>& b) {
    Rig rig;
    Error err;
    CHECK_FALSE(LoadRig(b.data(), b.size(), &rig, &err, no_checksum));
    return std::string(err.message);
  };
  const auto put = [](std::vector<unsigned char>& b, std::uint64_t at, std::uint32_t v) { std::memcpy(&b[at], &v, 4); };
  std::vector<unsigned char> disagree = bytes;
  put(disagree, pord_at + 4, 7);  // pose 0, part 1: 7, where PART says -1
  CHECK(refused(disagree) == "part 1: PART's draw order -1 is not pose 0's in PORD (7)");
  std::uint32_t flags = 0;
  std::memcpy(&flags, &bytes[meta_at + 28], 4);
  std::vector<unsigned char> unflagged = bytes;
  put(unflagged, meta_at + 28, flags & ~format::kMetaFlagPartPoseOrders);
  CHECK(refused(unflagged) == "PORD section present but META says the draw order is fixed");
  std::vector<unsigned char> no_parts = bytes;
  put(no_parts, meta_at + 28, flags & ~format::kMetaFlagParts);
  CHECK(refused(no_parts) == "PART section present but META says the rig has no parts");  // checked first
  // Pose 1's entries may be anything: the sequences are sorted at load, ties in part order.
  std::vector<unsigned char> tie = bytes;
  put(tie, pord_at + 8, std::uint32_t(-1)), put(tie, pord_at + 12, std::uint32_t(-1));
  Rig rig;
  Error err;
  REQUIRE_MESSAGE(LoadRig(tie.data(), tie.size(), &rig, &err, no_checksum), err.message);
  CHECK(rig.draw_sequence(1)[0] == 0);
  CHECK(rig.draw_sequence(1)[1] == 1);
}

TEST_CASE("layered: bad parts and glue are refused with the part, the pose and the problem") {
  const json good = ArmRig();
  {
    json d = good;
    d["parts"][1]["poses"].erase(2);
    CHECK(LayeredBakeError(d) ==
          "arm.json: parts[1].poses: part 'arm' has 2 poses, the rig 3: every part is drawn in every "
          "pose (one that should vanish is drawn tiny, or hidden behind another by its order)");
  }
  {
    json d = good;
    d["glue"][0]["to"] = "torso";
    CHECK(LayeredBakeError(d) == "arm.json: glue[0].to: no part is named 'torso'");
  }
  {
    json d = good;
    d["glue"][0]["at"] = json::array({12.5, 3});
    CHECK(LayeredBakeError(d).find(
              "arm.json: part 'body': glue[0] ('arm' to 'body'): no vertex of part 'body' lies at the "
              "joint (12.5, 3) in pose 'rest' (index 0) (the nearest is ") == 0);
  }
  {
    json d = good;
    d["glue"].push_back(d["glue"][0]);
    CHECK(LayeredBakeError(d) ==
          "arm.json: glue[1]: gluing 'arm' to 'body' closes a cycle: they are glued together already "
          "(directly or through other parts), and a cycle of glue over-constrains the joints; remove one");
  }
  {
    json d = good;
    d.erase("glue");
    CHECK(LayeredBakeError(d) == "arm.json: missing \"glue\": the parts must be glued together at joints");
  }
  {
    json d = good;
    json hat = d["parts"][1];
    hat["name"] = "hat";
    d["parts"].push_back(hat);
    CHECK(LayeredBakeError(d) ==
          "arm.json: glue: part 'hat' is not glued to part 'body' (directly or through other parts): "
          "a character's parts are one piece");
  }
  {
    json d = good;
    for (int k = 0; k < 64; ++k) {
      json extra = d["parts"][1];
      extra["name"] = "extra" + std::to_string(k);
      d["parts"].push_back(extra);
    }
    CHECK(LayeredBakeError(d) == "arm.json: parts: 66 parts, more than the rig format's limit of 64");
  }
  {
    // The arm's end moved off the body's corner in pose 'mid', the joint given in pose 0 only.
    json d = good;
    d["glue"][0]["at"] = d["glue"][0]["at"][0];
    const double x = d["parts"][1]["poses"][1]["vertices"][5][0];
    d["parts"][1]["poses"][1]["vertices"][5][0] = x + 1;
    const std::string e = LayeredBakeError(d);
    CHECK(e.find("arm.json: glue[0] ('arm' to 'body'): in pose 'mid' (index 1) the joint is at (") == 0);
    CHECK(e.find("on part 'arm' but at (") != std::string::npos);
    CHECK(e.find("on part 'body': a joint is one point in every pose") != std::string::npos);
  }
  {
    json d = good;
    d["parts"][1]["poses"][0]["vertices"][3] = json::array({1e300, 0});
    CHECK(LayeredBakeError(d) ==
          "arm.json: part 'arm', pose 'rest': parts[1].poses[0].vertices[3]: "
          "coordinate beyond +-1e9 ([1e+300,0])");
  }
  {
    json d = good;
    d["poses"][0]["vertices"] = d["parts"][0]["poses"][0]["vertices"];
    CHECK(LayeredBakeError(d) ==
          "arm.json: poses[0].vertices: with \"parts\", a rig's pose gives its name and point only; "
          "what it looks like goes in each part's \"poses\"");
  }
}

TEST_CASE("layered: drawn parts are mapped on their own and share a vertex exactly at the joint in every pose") {
  // Outlines (rig coordinates): a body rectangle and an arm bar turning
  // 120 degrees about the shoulder at (30, -10), inside both.
  auto rotated = [](double x, double y, double degrees) {
    const double t = degrees * M_PI / 180;
    return json::array({30 + std::cos(t) * x - std::sin(t) * y, -10 + std::sin(t) * x + std::cos(t) * y});
  };
  const json body =
      json::array({json::array({-40, -120}), json::array({40, -120}), json::array({40, 0}), json::array({-40, 0})});
  json d = {{"posemorph", 1}, {"bake", {{"grid_resolution", 16}, {"precision", "exact"}}}};
  json body_poses = json::array(), arm_poses = json::array(), at = json::array();
  const double angles[3] = {-90, -30, 30};
  for (int i = 0; i < 3; ++i) {
    d["poses"].push_back({{"name", "p" + std::to_string(i)}, {"point", json::array({i, 0})}});
    body_poses.push_back({{"outline", body}, {"landmarks", json::array({body[0]})}});
    json arm = json::array({rotated(-10, -10, angles[i]), rotated(80, -10, angles[i]), rotated(80, 10, angles[i]),
                            rotated(-10, 10, angles[i])});
    arm_poses.push_back({{"outline", arm}, {"landmarks", json::array({arm[0]})}});
    at.push_back(json::array({30, -10}));
  }
  d["parts"] =
      json::array({{{"name", "body"}, {"poses", body_poses}}, {{"name", "arm"}, {"order", 1}, {"poses", arm_poses}}});
  d["glue"] = json::array({{{"part", "arm"}, {"to", "body"}, {"at", at}}});
  const bake::RigDescription description = bake::ParseRigDescription(d.dump(), "drawn.json", ".");
  bake::BakeReport report;
  const std::vector<unsigned char> bytes = bake::BakeRig(description, &report);
  Rig rig;
  REQUIRE(LoadRig(bytes.data(), bytes.size(), &rig, nullptr));
  REQUIRE(rig.part_count() == 2);
  REQUIRE(report.joints.size() == 1);
  const std::uint32_t joint = report.joints[0];
  for (std::uint32_t i = 0; i < 3; ++i) {
    CHECK(rig.pose_positions(i)[2 * joint] == 30);
    CHECK(rig.pose_positions(i)[2 * joint + 1] == -10);
  }
  CHECK(report.max_reproduction_error <= 1e-9);
  // Exactly one vertex is in both parts' triangles.
  std::vector<int> in(rig.vertex_count(), 0);
  for (std::uint32_t p = 0; p < 2; ++p)
    for (std::uint32_t t = rig.part(p).first_triangle; t < rig.part(p).first_triangle + rig.part(p).triangle_count; ++t)
      for (int k = 0; k < 3; ++k) in[rig.triangles()[3 * t + k]] |= 1 << p;
  CHECK(std::count(in.begin(), in.end(), 3) == 1);
  CHECK(in[joint] == 3);
  // A joint off the body in one pose is refused, naming the part and the pose.
  d["glue"][0]["at"][1] = json::array({200, 50});
  CHECK(LayeredBakeError(d, "drawn.json")
            .find("drawn.json: part 'body': pose 'p1' (index 1): feature 0 lies outside the outline") !=
        std::string::npos);
}

TEST_CASE("layered: the command line bakes parts, info lists them, deform and outline say what they need") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("posemorph-layered-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string input = std::string(POSEMORPH_SOURCE_DIR) + "/tests/runtime/rigs/arm.json";
  const std::string rig = (dir / "arm.pmrig").string();
  auto run = [](const std::vector<std::string>& args, std::string* text) {
    std::ostringstream out, err;
    const int status = bake::RunBakeCommand(args, out, err);
    *text = out.str() + err.str();
    return status;
  };
  std::string text;
  REQUIRE(run({input, "-o", rig}, &text) == 0);
  CHECK(text.find("parts (back to front): body (32 triangles), arm (16 triangles); 1 joint, each one vertex shared "
                  "by its two parts\n") != std::string::npos);
  CHECK(text.find("ghosting: not measured: the rig is drawn as parts") != std::string::npos);
  REQUIRE(run({"info", rig}, &text) == 0);
  CHECK(text.find("  part 0 'body': triangles 0..31, draw order 0\n  part 1 'arm': triangles 32..47, draw order 1\n") !=
        std::string::npos);
  CHECK(text.find("PART        32  u32 parts: first triangle, triangle count, draw order") != std::string::npos);
  CHECK(run({"deform", input, "--pose", "rest", "-o", (dir / "x.json").string()}, &text) == 1);
  CHECK(text.find(input + ": has parts: deform makes poses of one shape") != std::string::npos);
  CHECK(run({"outline", input, "-o", dir.string()}, &text) == 1);
  CHECK(text.find(input + ": has parts: trace one with --part NAME ('body', 'arm')") != std::string::npos);
  CHECK(run({"outline", input, "-o", dir.string(), "--part", "leg"}, &text) == 1);
  CHECK(text.find(input + ": has no part 'leg' ('body', 'arm')") != std::string::npos);
  CHECK(!fs::exists(dir / "x.json"));
  fs::remove_all(dir);
}

TEST_CASE("layered: parts drawn as layers of one SVG per pose, by Inkscape label or group id") {
  // Each pose is one drawing: a background layer that is no part, the body
  // as an Inkscape layer, and the arm as a plain group inside a layer of
  // arms, turning 120 degrees about the shoulder at (130, 130), inside both.
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("posemorph-svg-layers-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const double sx = 130, sy = 130;
  auto rotated = [&](double x, double y, double degrees) {
    const double t = degrees * M_PI / 180;
    return std::array<double, 2>{sx + std::cos(t) * x - std::sin(t) * y, sy + std::sin(t) * x + std::cos(t) * y};
  };
  const double angles[3] = {-90, -30, 30};
  json d = {{"posemorph", 1}, {"bake", {{"grid_resolution", 16}, {"precision", "exact"}}}};
  json body_poses = json::array(), arm_poses = json::array();
  for (int i = 0; i < 3; ++i) {
    const std::string name = "p" + std::to_string(i) + ".svg";
    std::ostringstream arm;
    const double corners[4][2] = {{-10, -10}, {80, -10}, {80, 10}, {-10, 10}};
    for (int k = 0; k < 4; ++k) {
      const auto c = rotated(corners[k][0], corners[k][1], angles[i]);
      arm << (k ? " L " : "M ") << c[0] << ' ' << c[1];
    }
    std::ofstream(dir / name)
        << "<svg xmlns=\"http://www.w3.org/2000/svg\" "
           "xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\" viewBox=\"0 0 300 300\">\n"
           "<g inkscape:groupmode=\"layer\" inkscape:label=\"background\" id=\"layer1\">"
           "<path d=\"M 0 0 H 300 V 300 H 0 Z\"/></g>\n"
           "<g inkscape:groupmode=\"layer\" inkscape:label=\"body\" id=\"layer2\">"
           "<polygon points=\"60,120 140,120 140,240 60,240\"/></g>\n"
           "<g inkscape:groupmode=\"layer\" inkscape:label=\"arms\" id=\"layer3\">"
           "<g id=\"empty\"/><g id=\"arm-front\"><path d=\""
        << arm.str() << " Z\"/></g></g>\n</svg>\n";
    d["poses"].push_back({{"name", "p" + std::to_string(i)}, {"point", json::array({i, 0})}});
    body_poses.push_back({{"drawing", name}, {"landmarks", json::array({json::array({60, 120})})}});
    const auto start = rotated(-10, -10, angles[i]);
    arm_poses.push_back(
        {{"drawing", name}, {"layer", "arm-front"}, {"landmarks", json::array({json::array({start[0], start[1]})})}});
  }
  d["parts"] =
      json::array({{{"name", "body"}, {"poses", body_poses}}, {{"name", "arm"}, {"order", 1}, {"poses", arm_poses}}});
  const json at = json::array({sx, sy});
  d["glue"] = json::array({{{"part", "arm"}, {"to", "body"}, {"at", json::array({at, at, at})}}});
  const auto in_dir = [&](const char* file) { return (dir / file).string(); };
  const auto bake_error = [&](const json& description) {
    try {
      bake::BakeRig(bake::ParseRigDescription(description.dump(), "layers.json", dir.string()));
    } catch (const bake::BakeError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };

  bake::BakeReport report;
  const std::vector<unsigned char> bytes =
      bake::BakeRig(bake::ParseRigDescription(d.dump(), "layers.json", dir.string()), &report);
  Rig rig;
  REQUIRE(LoadRig(bytes.data(), bytes.size(), &rig, nullptr));
  REQUIRE(rig.part_count() == 2);
  REQUIRE(report.joints.size() == 1);
  CHECK(report.max_reproduction_error <= 1e-9);
  const std::uint32_t joint = report.joints[0];
  for (std::uint32_t i = 0; i < 3; ++i) {
    // Each part's vertices span its own layer's shape (to the outline's
    // simplification), not the background's 300 x 300.
    const double* x = rig.pose_positions(i).data;
    double body_lo[2] = {1e9, 1e9}, body_hi[2] = {-1e9, -1e9}, arm_reach = 0;
    for (std::uint32_t p = 0; p < 2; ++p)
      for (std::uint32_t t = rig.part(p).first_triangle; t < rig.part(p).first_triangle + rig.part(p).triangle_count;
           ++t)
        for (int k = 0; k < 3; ++k) {
          const std::uint32_t v = rig.triangles()[3 * t + k];
          if (p == 0) {
            for (int c = 0; c < 2; ++c)
              body_lo[c] = std::min(body_lo[c], x[2 * v + c]), body_hi[c] = std::max(body_hi[c], x[2 * v + c]);
          } else {
            arm_reach = std::max(arm_reach, std::hypot(x[2 * v] - x[2 * joint], x[2 * v + 1] - x[2 * joint + 1]));
          }
        }
    CHECK(body_hi[0] - body_lo[0] == doctest::Approx(80).epsilon(1e-4));
    CHECK(body_hi[1] - body_lo[1] == doctest::Approx(120).epsilon(1e-4));
    CHECK(arm_reach == doctest::Approx(std::hypot(80, 10)).epsilon(1e-4));
    CHECK(x[2 * joint] == rig.pose_positions(0)[2 * joint]);
    CHECK(x[2 * joint + 1] == rig.pose_positions(0)[2 * joint + 1]);
  }

  // The part's own name is its layer by default; a drawing of several
  // layers, none of them the part's, is refused rather than read whole.
  {
    json e = d;
    for (json& pose : e["parts"][1]["poses"]) pose.erase("layer");
    CHECK(bake_error(e) ==
          "layers.json: part 'arm': pose 'p0' (index 0): " + in_dir("p0.svg") +
              ": no layer or group is named 'arm' "
              "(its named groups: 'background', 'layer1', 'body', 'layer2', 'arms', 'layer3', 'empty', 'arm-front'); "
              "name the part like its layer, or give the pose a \"layer\"");
  }
  {
    json e = d;
    e["parts"][1]["poses"][2]["layer"] = "arm-back";
    CHECK(bake_error(e).find("layers.json: part 'arm': pose 'p2' (index 2): " + in_dir("p2.svg") +
                             ": no layer or group is named 'arm-back' (its named groups: 'background', ") == 0);
  }
  {
    json e = d;
    e["parts"][1]["poses"][1]["layer"] = "empty";
    CHECK(bake_error(e) == "layers.json: part 'arm': pose 'p1' (index 1): " + in_dir("p1.svg") +
                               ": layer 'empty' has no <path> or <polygon> to take the outline from");
  }
  {
    // Two groups answer to one name.
    std::ifstream in(dir / "p0.svg");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text.replace(text.find("id=\"layer1\""), 11, "id=\"body\"");
    std::ofstream(dir / "twice.svg") << text;
    json e = d;
    e["parts"][0]["poses"][0]["drawing"] = "twice.svg";
    CHECK(bake_error(e) == "layers.json: part 'body': pose 'p0' (index 0): " + in_dir("twice.svg") +
                               ": 2 groups are named 'body' (inkscape:label or id): a layer's name must pick one");
  }
  {
    json e = d;
    e["parts"][1]["poses"][0]["drawing"] = "p0.png";
    CHECK(bake_error(e) ==
          "layers.json: part 'arm', pose 'p0': parts[1].poses[0].layer: only an SVG drawing has "
          "layers (a PNG part is its own file)");
    e["parts"][1]["poses"][0]["drawing"] = "p0.svg";
    e["parts"][1]["poses"][0]["layer"] = "";
    CHECK(bake_error(e) ==
          "layers.json: part 'arm', pose 'p0': parts[1].poses[0].layer: must not be empty (leave "
          "it out for the whole drawing)");
  }
  fs::remove_all(dir);
}

TEST_CASE("layered: Pell, the drawn layered sample, bakes its seven parts with their joints exact in every pose") {
  const std::string dir = std::string(POSEMORPH_DRAWN_SAMPLES) + "/pell";
  const bake::RigDescription description = bake::ReadRigDescription(dir + "/pell.json");
  REQUIRE(description.parts.size() == 7);
  for (bool exact : {true, false}) {
    CAPTURE(exact);
    bake::RigDescription d = description;
    d.parameters.compact = !exact;
    bake::BakeReport report;
    const std::vector<unsigned char> bytes = bake::BakeRig(d, &report);
    Rig rig;
    Error err;
    REQUIRE_MESSAGE(LoadRig(bytes.data(), bytes.size(), &rig, &err), err.message);
    REQUIRE(rig.part_count() == 7);
    CHECK(rig.draw_order_changes());
    CHECK(report.max_reproduction_error <= (exact ? 1e-9 : 1e-4));
    REQUIRE(report.joints.size() == 6);
    // Each joint is one vertex of both its parts, at the point the
    // description gives in every pose (drawing pixels, y down; rig y up).
    for (std::size_t g = 0; g < 6; ++g) {
      const bake::GlueDescription& glue = description.glue[g];
      const std::uint32_t v = report.joints[g];
      for (std::uint32_t i = 0; i < rig.pose_count(); ++i) {
        const double* x = rig.pose_positions(i).data;
        CHECK(std::hypot(x[2 * v] - glue.at[i].x(), x[2 * v + 1] + glue.at[i].y()) < (exact ? 1e-3 : 0.02));
      }
      int parts_using = 0;
      for (std::size_t p : {glue.part_index, glue.to_index}) {
        const PartView part = rig.part(std::uint32_t(p));
        bool uses = false;
        for (std::uint32_t t = part.first_triangle; t < part.first_triangle + part.triangle_count; ++t)
          for (int k = 0; k < 3; ++k) uses |= rig.triangles()[3 * t + k] == v;
        parts_using += uses;
      }
      CHECK(parts_using == 2);
    }
  }
}
