// SPDX-License-Identifier: MIT
// Bad input to posemorph-bake: one clear message naming the file and the
// problem, a non-zero exit, and no output file (an existing one untouched).

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <unistd.h>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli.h"
#include "posemorph/posemorph.h"
#include "posemorph/bake/import/layered_image.h"
#include "posemorph/bake/validate_rig.h"
#include "posemorph/bake/stage.h"
#include "posemorph/rig_format.h"
#include "bad_input_support.h"
#include "test_support.h"

using namespace posemorph;
using namespace posemorph::test;
using nlohmann::json;
namespace fs = std::filesystem;

TEST_CASE("a valid description bakes and writes its output") {
  TempDir dir;
  const fs::path input = dir.path / "rig.json", output = dir.path / "rig.pmrig";
  Write(input, ValidDescription().dump());
  const Result r = Run({input.string()});
  CHECK(r.status == 0);
  CHECK(fs::exists(output));  // default name: the description's, with .pmrig
  CHECK(Run({"info", output.string()}).status == 0);
  CHECK(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()) == 2);
}

TEST_CASE("wrong vertex count") {
  json d = ValidDescription();
  d["poses"][1]["vertices"].erase(3);
  ExpectFailure(d.dump(), "pose 'b' (index 1) has 3 vertices, pose 0 has 4");
}

TEST_CASE("a rig beyond the bake's work bound is refused at once, from its counts") {
  // Issue 38, point 2: 500,001 vertices in 2 poses pass kMaxBakeVertexPoses
  // (1,000,000): refused with the counts, before the mesh is checked or
  // factored (one triangle, the rest unused vertices, would fail later).
  const std::size_t V = bake::kMaxBakeVertexPoses / 2 + 1;
  std::string vertices;
  vertices.reserve(V * 6);
  for (std::size_t v = 0; v < V; ++v) vertices += v ? ",[0,0]" : "[0,0]";
  const std::string text = R"({"posemorph": 1, "triangles": [[0, 1, 2]], "poses": [)"
                           R"({"name": "a", "point": [0, 0], "vertices": [)" +
                           vertices + R"(]}, {"name": "b", "point": [1, 0], "vertices": [)" + vertices + "]}]}";
  ExpectFailure(text, "500001 vertices in 2 poses (1000002 vertex-poses), above the bake's bound of 1000000");
}

TEST_CASE("out-of-range index") {
  json d = ValidDescription();
  d["triangles"][1][2] = 9;
  ExpectFailure(d.dump(), "triangle 1 uses vertex 9");
  d["triangles"][1][2] = -1;
  ExpectFailure(d.dump(), "triangles[1]: vertex index -1 is out of range");
}

TEST_CASE("repeated index") {
  json d = ValidDescription();
  d["triangles"][0] = {0, 2, 2};
  ExpectFailure(d.dump(), "triangle 0 repeats a vertex");
  d = ValidDescription();
  d["triangles"][1] = {2, 0, 1};
  ExpectFailure(d.dump(), "triangle 1 appears twice");
}

TEST_CASE("a non-manifold mesh: three triangles on one edge") {
  json d = ValidDescription();
  // A fifth vertex and a third triangle on the diagonal (0, 2), overlapping the others.
  for (auto& pose : d["poses"]) pose["vertices"].push_back({0.6, 0.4});
  d["triangles"].push_back({0, 4, 2});
  ExpectFailure(d.dump(),
                "the mesh is not manifold: edge (0, 2) borders triangles 0, 1 and 2 (an edge borders at most two)");
}

TEST_CASE("pose-space points the grid cannot represent") {
  json d = ValidDescription();
  d["poses"][1]["point"] = {1e308, 0};
  ExpectFailure(d.dump(), "pose 'b' (index 1): pose-space point (1e+308, 0) lies beyond +-1e12");
  d["poses"][1]["point"] = {-1e13, 0};
  ExpectFailure(d.dump(), "pose 'b' (index 1): pose-space point (-1e+13, 0) lies beyond +-1e12");
  d["poses"][1]["point"] = {4.9406564584124654e-324, 0};
  ExpectFailure(d.dump(), "the pose-space points span only 4.94066e-324; they must span at least 1e-6");
}

TEST_CASE("degenerate triangle in a pose") {
  json d = ValidDescription();
  d["poses"][1]["vertices"][2] = {0.5, 0.1};  // (0,0), (1,0.2), (0.5,0.1): collinear
  ExpectFailure(d.dump(), "pose 'b' (index 1): triangle 0 is degenerate");
}

TEST_CASE("flipped triangle in a pose") {
  json d = ValidDescription();
  d["poses"][1]["vertices"][3] = {0.5, -0.8};  // folds triangle 1 over
  ExpectFailure(d.dump(), "pose 'b' (index 1): triangle 1 is flipped");
}

TEST_CASE("fewer than 2 poses") {
  json d = ValidDescription();
  d["poses"].erase(1);
  ExpectFailure(d.dump(), "a rig needs at least 2 poses, this one has 1");
}

TEST_CASE("coincident pose points") {
  json d = ValidDescription();
  d["poses"][1]["point"] = {0, 0};
  ExpectFailure(d.dump(), "share the pose-space point");
}

TEST_CASE("pose points too close for the weight grid") {
  json d = ValidDescription();
  d["poses"].push_back(d["poses"][1]);
  d["poses"][2]["name"] = "c";
  d["poses"][2]["point"] = {1e-4, 0};
  ExpectFailure(d.dump(),
                "pose points 'a' and 'c' fall in one pose-space grid cell; raise bake.grid_resolution (now 8)");
}

TEST_CASE("non-finite numbers") {
  std::string text = ValidDescription().dump();
  text.replace(text.find("[1,0.2]"), 7, "[1e999,0.2]");
  ExpectFailure(text, "invalid JSON: number overflow parsing '1e999'");
  // Descriptions built in code (not from JSON) can hold NaN: validation names it.
  bake::RigDescription rig = bake::ParseRigDescription(ValidDescription().dump(), "in-memory", ".");
  rig.poses[1].vertices[2].x() = std::nan("");
  CHECK_THROWS_WITH(bake::BakeRig(rig), "in-memory: pose 'b' (index 1): vertex 2 is not finite");
  json d = ValidDescription();
  d["poses"][0]["point"] = {"x", 0};
  ExpectFailure(d.dump(), "poses[0].point[0]: expected a number");
}

TEST_CASE("unreadable and malformed files") {
  ExpectFailure("{\"posemorph\": 1, \"poses\": [", "invalid JSON");
  ExpectFailure("[1, 2]", "expected a JSON object");
  json d = ValidDescription();
  d["poses"][1].erase("vertices");
  d["poses"][1]["mesh"] = "missing-mesh.json";
  ExpectFailure(d.dump(), "cannot open file", "missing-mesh.json");
  d["poses"][1]["mesh"] = "bad-mesh.json";
  ExpectFailure(d.dump(), "invalid JSON", "bad-mesh.json",
                [](const fs::path& dir) { Write(dir / "bad-mesh.json", "{\"vertices\": [[0, 0],"); });

  TempDir dir;
  const Result r = Run({(dir.path / "nope.json").string(), "-o", (dir.path / "x.pmrig").string()});
  CHECK(r.status == 1);
  CHECK(r.err.find("nope.json: cannot open file") != std::string::npos);
  CHECK_FALSE(fs::exists(dir.path / "x.pmrig"));
}

TEST_CASE("a mesh file gives the vertices") {
  TempDir dir;
  json d = ValidDescription();
  d["poses"][1].erase("vertices");
  d["poses"][1]["mesh"] = "b.json";
  Write(dir.path / "b.json",
        R"({"vertices": [[0, 0], [1, 0.2], [0.9, 1.1], [-0.1, 0.9]], "triangles": [[0, 1, 2], [0, 2, 3]]})");
  Write(dir.path / "rig.json", d.dump());
  CHECK(Run({(dir.path / "rig.json").string()}).status == 0);
  // A mesh file with other triangles is refused.
  Write(dir.path / "b.json",
        R"({"vertices": [[0, 0], [1, 0.2], [0.9, 1.1], [-0.1, 0.9]], "triangles": [[0, 1, 3], [1, 2, 3]]})");
  const Result r = Run({(dir.path / "rig.json").string()});
  CHECK(r.status == 1);
  CHECK(r.err.find("b.json: triangles: differ from the rig's triangle list") != std::string::npos);
}

TEST_CASE("rig files that are not rigs") {
  TempDir dir;
  Write(dir.path / "fake.pmrig", "this is not a rig");
  for (const char* cmd : {"info", "sheet"}) {
    const Result r = Run({cmd, (dir.path / "fake.pmrig").string(), "-o", (dir.path / "s.svg").string()});
    CHECK(r.status != 0);
  }
  const Result r = Run({"info", (dir.path / "fake.pmrig").string()});
  CHECK(r.err.find("fake.pmrig: not a valid rig (truncated)") != std::string::npos);
  CHECK_FALSE(fs::exists(dir.path / "s.svg"));
}

TEST_CASE("descriptions beyond the rig format's limits are refused by name, not baked into a rig that does not load") {
  json j = ValidDescription();
  j["poses"][0]["name"] = std::string(600000, 'a');
  j["poses"][1]["name"] = std::string(500000, 'b');
  ExpectFailure(j.dump(),
                "pose names, image references and path names take 1100016 bytes, more than the rig format's "
                "limit of 1048576 (the longest, pose '");
  j = ValidDescription();
  j["paths"] = json::array();
  for (int k = 0; k < 1025; ++k) j["paths"].push_back({{"name", "p" + std::to_string(k)}, {"keys", {{0, 0, 0}}}});
  ExpectFailure(j.dump(), "paths: 1025 paths, more than the rig format's limit of 1024");
  j = ValidDescription();
  json keys = json::array();
  for (int k = 0; k < (1 << 20) + 1; ++k) keys.push_back({k, 0, 0});
  j["paths"] = {{{"name", "long"}, {"keys", keys}}};
  ExpectFailure(j.dump(), "paths: 1048577 keys in all, more than the rig format's limit of 1048576");
}

TEST_CASE("path events outside their path, unnamed or malformed are refused by path and event") {
  json j = ValidDescription();
  j["paths"] =
      json::parse(R"([{"name": "walk", "keys": [[0, 0, 0], [1, 1, 0]], "events": [[0.5, "step"], [1.5, "late"]]}])");
  ExpectFailure(j.dump(), "paths[0].events[1]: time 1.5 is outside path \"walk\"'s keys [0, 1]");
  j["paths"][0]["events"] = json::parse(R"([[0.5, ""]])");
  ExpectFailure(j.dump(), "paths[0].events[0]: an event needs a name");
  j["paths"][0]["events"] = json::parse(R"([["step", 0.5]])");
  ExpectFailure(j.dump(), "paths[0].events[0]: expected a number");
  j["paths"][0]["events"] = json::parse("[[0.5]]");
  ExpectFailure(j.dump(), "paths[0].events[0]: expected [time, \"name\"]");
  j["paths"][0]["events"] = "step";
  ExpectFailure(j.dump(), "paths[0].events: expected an array");
  j = ValidDescription();
  json events = json::array();
  for (int k = 0; k < 65537; ++k) events.push_back(json::array({0.5, "e"}));
  j["paths"] = json::parse(R"([{"name": "walk", "keys": [[0, 0, 0], [1, 1, 0]]}])");
  j["paths"][0]["events"] = events;
  ExpectFailure(j.dump(), "paths: 65537 events in all, more than the rig format's limit of 65536");
}

TEST_CASE("a failure without context of its own names the bake stage it happened in") {
  try {
    bake::BakeStage outer("mapping the drawings");
    {
      bake::BakeStage inner("tracing a.png");
      CHECK(std::string(bake::CurrentBakeStage()) == "tracing a.png");
    }
    CHECK(std::string(bake::CurrentBakeStage()) == "mapping the drawings");
    bake::BakeStage failing("solving the pose-space weights");
    throw std::bad_alloc();
  } catch (const std::bad_alloc&) {
    // Left by the exception: the stage it happened in is still named.
    CHECK(std::string(bake::CurrentBakeStage()) == "solving the pose-space weights");
  }
}

TEST_CASE("an unknown key in the description bakes with a warning naming it") {
  TempDir dir;
  json j = ValidDescription();
  j["bake"]["grid_resolutoin"] = 32;
  j["poses"][1]["landmark"] = json::array();
  Write(dir.path / "rig.json", j.dump());
  const Result r = Run({(dir.path / "rig.json").string(), "-o", (dir.path / "rig.pmrig").string()});
  CHECK(r.status == 0);
  CHECK(r.err.find("rig.json: bake: unknown key \"grid_resolutoin\" ignored") != std::string::npos);
  CHECK(r.err.find("rig.json: poses[1]: unknown key \"landmark\" ignored") != std::string::npos);
  // Only known keys: no warning.
  j = ValidDescription();
  Write(dir.path / "rig.json", j.dump());
  CHECK(Run({(dir.path / "rig.json").string(), "-o", (dir.path / "rig.pmrig").string()}).err.find("unknown key") ==
        std::string::npos);
}

TEST_CASE("usage errors exit with status 2") {
  CHECK(Run({}).status == 2);
  CHECK(Run({"eval", "x.pmrig"}).status == 2);
  CHECK(Run({"eval", "x.pmrig", "-o", "a.png", "--at", "0,0"}).status == 2);
  CHECK(Run({"eval", "x.pmrig", "-o", "a.svg", "--at", "zero,0"}).status == 2);
  CHECK(Run({"rig.json", "--frobnicate"}).status == 2);
}

// --- Drawn poses (N-way mapping) ---------------------------------------------

namespace {

void WritePngAlpha(const fs::path& p, int w, int h, const std::function<int(int, int)>& alpha) {
  std::vector<unsigned char> rgba(std::size_t(w) * h * 4, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) rgba[(std::size_t(y) * w + x) * 4 + 3] = (unsigned char)alpha(x, y);
  const std::vector<unsigned char> png = posemorph::bake::import::EncodeRgbaPng(rgba, w, h, p.string());
  std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
  REQUIRE(fs::file_size(p) == png.size());
}

json Outline(const std::vector<std::array<double, 2>>& points) {
  json a = json::array();
  for (const auto& p : points) a.push_back({p[0], p[1]});
  return a;
}

json DrawnDescription() {
  // Two squares, the second sheared; landmarks at two corners.
  return json::parse(R"({
    "posemorph": 1,
    "poses": [
      {"name": "a", "point": [0, 0], "outline": [[0, 0], [40, 0], [40, 40], [0, 40]], "landmarks": [[0, 0], [40, 40]]},
      {"name": "b", "point": [1, 0], "outline": [[0, 0], [40, 0], [50, 40], [10, 40]], "landmarks": [[0, 0], [50, 40]]}
    ],
    "bake": {"grid_resolution": 8}
  })");
}

json Spiral(double turns, double width) {
  std::vector<std::array<double, 2>> right, left;
  for (int k = 0; k <= 160; ++k) {
    const double t = k / 160.0, a = t * turns * 2 * M_PI, r = 20 + 60 * t;
    const double dx = 60 * std::cos(a) - r * turns * 2 * M_PI * std::sin(a);
    const double dy = 60 * std::sin(a) + r * turns * 2 * M_PI * std::cos(a);
    const double n = std::hypot(dx, dy);
    right.push_back({r * std::cos(a) + width * dy / n, r * std::sin(a) - width * dx / n});
    left.push_back({r * std::cos(a) - width * dy / n, r * std::sin(a) + width * dx / n});
  }
  right.insert(right.end(), left.rbegin(), left.rend());
  return Outline(right);
}

}  // namespace

TEST_CASE("a drawn rig bakes") {
  TempDir dir;
  Write(dir.path / "rig.json", DrawnDescription().dump());
  const Result r = Run({(dir.path / "rig.json").string(), "-o", (dir.path / "out.pmrig").string()});
  CAPTURE(r.err);
  CHECK(r.status == 0);
  CHECK(r.out.find("mapped drawings") != std::string::npos);
}

TEST_CASE("drawn poses: a small shape's landmarks may lie 3 units off the outline, not only 5% of its size") {
  // 20 x 20 squares (the second sheared, 32.02 across): 5% of its diagonal is
  // 1.6 units, the floor 3 units.
  json d = json::parse(R"({
    "posemorph": 1,
    "poses": [
      {"name": "a", "point": [0, 0], "outline": [[0, 0], [20, 0], [20, 20], [0, 20]], "landmarks": [[0, 0], [20, 20]]},
      {"name": "b", "point": [1, 0], "outline": [[0, 0], [20, 0], [25, 20], [5, 20]], "landmarks": [[0, 0], [25, 20]]}
    ],
    "bake": {"grid_resolution": 8}
  })");
  d["poses"][1]["landmarks"][1] = {25, 22.5};  // 2.5 above the corner
  {
    TempDir dir;
    Write(dir.path / "rig.json", d.dump());
    const Result r = Run({(dir.path / "rig.json").string(), "-o", (dir.path / "out.pmrig").string()});
    CAPTURE(r.err);
    CHECK(r.status == 0);
  }
  d["poses"][1]["landmarks"][1] = {25, 23.5};  // 3.5 above it
  ExpectFailure(d.dump(),
                "pose 'b' (index 1): landmark 1 is 3.5 from the outline (more than 5% of the outline's size, 32.02, "
                "and more than 3, the least allowed)");
}

TEST_CASE("drawn poses: bad drawings and correspondences") {
  json d = DrawnDescription();
  d["poses"][1]["outline"] = Outline({{0, 0}, {40, 40}, {40, 0}, {0, 40}});
  ExpectFailure(d.dump(), "pose 'b' (index 1): the outline crosses or touches itself");

  d = DrawnDescription();
  d["poses"][1]["landmarks"] = json::parse("[[0, 0]]");
  ExpectFailure(d.dump(), "pose 'b' (index 1): gives 1 landmark(s) but pose 'a' (index 0) gives 2");

  d = DrawnDescription();
  d["poses"][1]["landmarks"][1] = {25, 20};  // the middle of the shape
  ExpectFailure(d.dump(),
                "pose 'b' (index 1): landmark 1 is 19.4 from the outline (more than 5% of the outline's size");

  d = DrawnDescription();
  d["poses"][0].erase("landmarks");
  ExpectFailure(d.dump(), "poses[0]: missing \"landmarks\"");

  d = DrawnDescription();
  d["poses"][1]["landmarks"] = json::parse("[[50, 40], [0, 0]]");
  d["poses"][1]["landmarks"][0] = {0, 0};
  d["poses"][1]["landmarks"][1] = {0, 0};
  ExpectFailure(d.dump(),
                "pose 'b' (index 1): landmark 1 is out of order or coincides with another: landmarks go "
                "counter-clockwise around the shape as seen in the drawing, in the same order in every pose");

  // Three landmarks given clockwise: the message says so.
  d = DrawnDescription();
  d["poses"][0]["landmarks"] = json::parse("[[0, 0], [40, 0], [40, 40]]");
  d["poses"][1]["landmarks"] = json::parse("[[0, 0], [40, 40], [40, 0]]");
  ExpectFailure(d.dump(),
                "pose 'b' (index 1): landmarks are out of order: they go clockwise around the shape as seen in "
                "the drawing; give them counter-clockwise, from landmark 0, in the same order in every pose");

  // Spirals of 0.6 and 2 turns need more Steiner points than the rig allows.
  d = DrawnDescription();
  d["poses"][0]["outline"] = Spiral(0.6, 9);
  d["poses"][1]["outline"] = Spiral(2.0, 6);
  d["poses"][0]["landmarks"] = json::array({d["poses"][0]["outline"][0]});
  d["poses"][1]["landmarks"] = json::array({d["poses"][1]["outline"][0]});
  d["mapping"] = {{"max_steiner_points", 2}};
  ExpectFailure(d.dump(), "cannot be triangulated compatibly with at most 2 Steiner points");

  d = DrawnDescription();
  d["poses"][0].erase("outline");
  d["poses"][0]["drawing"] = "a.gif";
  ExpectFailure(
      d.dump(),
      "pose 'a' (index 0): drawing \"a.gif\" is neither .png, .svg nor a layered file (.ora, .psd, with #Group/Layer)");
  d["poses"][0]["drawing"] = "missing.png";
  ExpectFailure(d.dump(), "missing.png: cannot open file");

  // A transparent drawing, and an SVG whose outline crosses itself.
  d["poses"][0]["drawing"] = "clear.png";
  ExpectFailure(d.dump(), "pose 'a' (index 0): ", "clear.png: image is empty or fully transparent",
                [](const fs::path& p) { WritePngAlpha(p / "clear.png", 32, 32, [](int, int) { return 0; }); });
  d["poses"][0]["drawing"] = "bow.svg";
  ExpectFailure(d.dump(), "pose 'a' (index 0): the outline crosses or touches itself", "rig.json",
                [](const fs::path& p) {
                  Write(p / "bow.svg", R"(<svg xmlns="http://www.w3.org/2000/svg" width="64" height="64">)"
                                       R"(<path d="M 0 0 L 40 40 L 40 0 L 0 40 Z"/></svg>)");
                });
}

TEST_CASE(
    "drawn poses: a PNG drawing with separate parts bakes with a warning naming the pose, the parts' sizes and "
    "shares, and where the largest lies") {
  TempDir dir;
  json d = DrawnDescription();
  d["poses"][0].erase("outline");
  d["poses"][0]["drawing"] = "a.png";
  d["poses"][0]["landmarks"] = json::parse("[[8, 48], [48, 8]]");  // image rows go down
  WritePngAlpha(dir.path / "a.png", 64, 64, [](int x, int y) {
    if (x >= 8 && x < 48 && y >= 8 && y < 48) return 255;
    return (x == 60 && y == 60) ? 255 : 0;
  });
  Write(dir.path / "rig.json", d.dump());
  const Result r = Run({(dir.path / "rig.json").string(), "-o", (dir.path / "out.pmrig").string()});
  CAPTURE(r.err);
  CHECK(r.status == 0);
  CHECK(r.err.find("rig.json: pose 'a' (index 0): " + (dir.path / "a.png").string() +
                   ": dropped a separate part of 1 pixels (0.06246% of the drawing, from (60, 60) to (60, 60) in the "
                   "drawing): only the largest part is meshed; join the parts in the drawing to keep them\n") !=
        std::string::npos);  // 1 of 1601 pixels

  // Two eyes apart from the head: 3 x 3 and 2 x 2 pixels.
  WritePngAlpha(dir.path / "a.png", 64, 64, [](int x, int y) {
    if (x >= 8 && x < 48 && y >= 8 && y < 48) return 255;
    if (x >= 52 && x < 55 && y >= 10 && y < 13) return 255;
    return (x >= 58 && x < 60 && y >= 10 && y < 12) ? 255 : 0;
  });
  const Result two = Run({(dir.path / "rig.json").string(), "-o", (dir.path / "out.pmrig").string()});
  CAPTURE(two.err);
  CHECK(two.status == 0);
  CHECK(two.err.find("a.png: dropped 2 separate parts of 13 pixels (0.806% of the drawing; the largest 9 pixels, "
                     "0.558%, from (52, 10) to (54, 12) in the drawing): only the largest part is meshed") !=
        std::string::npos);  // of 1613 pixels

  // Traced at a working level (600 px: halved twice), the box is still in
  // the drawing's pixels: a 4 x 4 speck at (520, 40).
  d["poses"][0]["landmarks"] = json::parse("[[80, 480], [480, 80]]");
  d["poses"][1]["outline"] = json::parse("[[0, 0], [400, 0], [500, 400], [100, 400]]");
  d["poses"][1]["landmarks"] = json::parse("[[0, 0], [500, 400]]");
  WritePngAlpha(dir.path / "a.png", 600, 600, [](int x, int y) {
    if (x >= 80 && x < 480 && y >= 80 && y < 480) return 255;
    return (x >= 520 && x < 524 && y >= 40 && y < 44) ? 255 : 0;
  });
  Write(dir.path / "rig.json", d.dump());
  const Result large = Run({(dir.path / "rig.json").string(), "-o", (dir.path / "out.pmrig").string()});
  CAPTURE(large.err);
  CHECK(large.status == 0);
  CHECK(large.err.find("a.png: dropped a separate part of 16 pixels (") != std::string::npos);
  CHECK(large.err.find(" of the drawing, from (520, 40) to (523, 43) in the drawing)") != std::string::npos);
}

TEST_CASE("drawn poses: an origin per pose lines up drawings on canvases of different sizes") {
  // The same 40-pixel square drawn on a 64 x 64 canvas and, 20 px right and
  // 10 px lower, on a 96 x 80 one. Each pose's origin is the middle of the
  // square's bottom edge ("between the feet").
  TempDir dir;
  WritePngAlpha(dir.path / "a.png", 64, 64,
                [](int x, int y) { return x >= 8 && x < 48 && y >= 8 && y < 48 ? 255 : 0; });
  WritePngAlpha(dir.path / "b.png", 96, 80,
                [](int x, int y) { return x >= 28 && x < 68 && y >= 18 && y < 58 ? 255 : 0; });
  json d = json::parse(R"({"posemorph": 1, "poses": [
      {"name": "a", "point": [0, 0], "drawing": "a.png", "origin": [28, 48], "landmarks": [[8, 48], [48, 8]]},
      {"name": "b", "point": [1, 0], "drawing": "b.png", "origin": [48, 58], "landmarks": [[28, 58], [68, 18]]}],
    "mapping": {"align_interiors": false},
    "bake": {"grid_resolution": 8, "precision": "exact"}})");
  // (Alignment off: the two canvases' pyramids are cut at different places,
  // which moves interior vertices by 0.009 px; this case is about origins.)
  auto bake = [&](const json& description) {
    bake::RigDescription rig = bake::ParseRigDescription(description.dump(), "rig.json", dir.path.string());
    const std::vector<unsigned char> bytes = bake::BakeRig(rig);
    Rig loaded;
    REQUIRE(LoadRig(bytes.data(), bytes.size(), &loaded, nullptr));
    return loaded;
  };
  auto farthest = [](const Rig& rig) {
    double worst = 0;
    for (std::uint32_t v = 0; v < rig.vertex_count(); ++v)
      worst = std::max(worst, std::hypot(rig.pose_positions(0)[2 * v] - rig.pose_positions(1)[2 * v],
                                         rig.pose_positions(0)[2 * v + 1] - rig.pose_positions(1)[2 * v + 1]));
    return worst;
  };
  const Rig with = bake(d);
  CHECK(farthest(with) <= 1e-9);  // the two poses coincide: an in-between does not slide
  // The origin is the rig's (0, 0) on each canvas, and every vertex's uv
  // still lands on its own place in its own drawing.
  CHECK(with.pose_canvas(0).pivot_x == 28);
  CHECK(with.pose_canvas(0).pivot_y == 48);
  CHECK(with.pose_canvas(1).width == 96);
  CHECK(with.pose_canvas(1).pivot_x == 48);
  CHECK(with.pose_canvas(1).pivot_y == 58);
  for (std::uint32_t v = 0; v < with.vertex_count(); ++v) {
    CHECK(with.uvs(1)[2 * v] * 96 == doctest::Approx(with.pose_positions(1)[2 * v] + 48).epsilon(1e-6));
    CHECK(with.uvs(1)[2 * v + 1] * 80 == doctest::Approx(58 - with.pose_positions(1)[2 * v + 1]).epsilon(1e-6));
  }
  // Without origins the second pose sits 20 px right and 10 px lower.
  json plain = d;
  plain["poses"][0].erase("origin");
  plain["poses"][1].erase("origin");
  CHECK(farthest(bake(plain)) == doctest::Approx(std::hypot(20.0, 10.0)).epsilon(1e-9));

  json bad = d;
  bad["poses"][0]["origin"] = json::parse("[1, 2, 3]");
  CHECK_THROWS_WITH(bake::ParseRigDescription(bad.dump(), "rig.json", dir.path.string()),
                    doctest::Contains("poses[0].origin"));
  bad = DrawnDescription();
  bad["poses"][0]["origin"] = json::parse("[1, 2]");
  CHECK_THROWS_WITH(bake::ParseRigDescription(bad.dump(), "rig.json", dir.path.string()),
                    "rig.json: poses[0].origin: only a drawing has an origin (an outline is in rig coordinates)");
}

TEST_CASE("a rig baked to a file records its drawings' folder relative to it (format 1.5)") {
  json d = ValidDescription();
  d["poses"][0]["image"] = "a.png";
  auto folder = [&](const std::string& description, const std::string& rig_file, const char* precision) {
    d["bake"]["precision"] = precision;
    bake::RigDescription desc = bake::ParseRigDescription(d.dump(), description, ".");
    desc.rig_file = rig_file;
    const std::vector<unsigned char> bytes = bake::BakeRig(desc);
    Rig rig;
    Error err;
    REQUIRE_MESSAGE(LoadRig(bytes.data(), bytes.size(), &rig, &err), err.message);
    CHECK(rig.format_minor() == format::kVersionMinor);
    const std::string recorded(rig.drawing_folder().data, rig.drawing_folder().size);
    pm_rig* handle = nullptr;
    REQUIRE(pm_rig_load(bytes.data(), bytes.size(), &handle, nullptr) == PM_OK);
    char text[128];
    std::size_t length = 99;
    CHECK(pm_rig_drawing_folder(handle, text, sizeof text, &length) == PM_OK);
    CHECK(std::string(text) == recorded);
    CHECK(length == recorded.size());
    pm_rig_free(handle);
    return recorded;
  };
  for (const char* precision : {"exact", "compact"}) {
    CAPTURE(precision);
    CHECK(folder("/studio/assets/chick/chick.json", "/studio/build/rigs/chick.pmrig", precision) ==
          "../../assets/chick");
    CHECK(folder("/studio/chick.json", "/studio/chick.pmrig", precision) == ".");
    CHECK(folder("/studio/chick.json", "/studio/out/chick.pmrig", precision) == "..");
    CHECK(folder("art/chick.json", "art/rigs/chick.pmrig", precision) == "..");
    // Baked in memory: nowhere to be relative to.
    CHECK(folder("/studio/chick.json", "", precision).empty());
  }
  // No drawing referenced: nothing to find.
  d["poses"][0].erase("image");
  CHECK(folder("/studio/chick.json", "/studio/out/chick.pmrig", "exact").empty());
}

TEST_CASE("a description's \"filter\" reaches the rig, exact and compact, and the C API") {
  for (const char* precision : {"exact", "compact"}) {
    CAPTURE(precision);
    json d = ValidDescription();
    d["filter"] = "nearest";
    d["bake"]["precision"] = precision;
    bake::RigDescription desc = bake::ParseRigDescription(d.dump(), "rig.json", ".");
    const std::vector<unsigned char> bytes = bake::BakeRig(desc);
    Rig rig;
    REQUIRE(LoadRig(bytes.data(), bytes.size(), &rig, nullptr));
    CHECK(rig.texture_filter() == TextureFilter::kNearest);
    CHECK(rig.format_minor() == format::kVersionMinor);
    pm_rig* handle = nullptr;
    REQUIRE(pm_rig_load(bytes.data(), bytes.size(), &handle, nullptr) == PM_OK);
    CHECK(pm_rig_texture_filter(handle) == PM_FILTER_NEAREST);
    pm_rig_free(handle);
    d["filter"] = "linear";
    desc = bake::ParseRigDescription(d.dump(), "rig.json", ".");
    const std::vector<unsigned char> linear = bake::BakeRig(desc);
    REQUIRE(LoadRig(linear.data(), linear.size(), &rig, nullptr));
    CHECK(rig.texture_filter() == TextureFilter::kLinear);
  }
  json d = ValidDescription();
  d["filter"] = "cubic";
  ExpectFailure(d.dump(), "filter: expected \"linear\" or \"nearest\" (pixel art)");
}

TEST_CASE("messages escape control characters and elide the middle of huge ones") {
  json d = ValidDescription();
  d["poses"][0]["name"] = "a\x1b[31mRED\x07";
  d["poses"][1]["name"] = "a\x1b[31mRED\x07";
  ExpectFailure(d.dump(), "pose 'a\\x1b[31mRED\\x07' (index 1): the name is used by pose 0 too");
  {
    TempDir dir;
    Write(dir.path / "rig.json", d.dump());
    const Result r = Run({(dir.path / "rig.json").string(), "-o", (dir.path / "out.pmrig").string()});
    for (char c : r.err) CHECK((static_cast<unsigned char>(c) >= 0x20 || c == '\n'));
  }
  const std::string huge(900000, 'N');
  d["poses"][0]["name"] = huge;
  d["poses"][1]["name"] = huge;
  TempDir dir;
  Write(dir.path / "rig.json", d.dump());
  const Result r = Run({(dir.path / "rig.json").string(), "-o", (dir.path / "out.pmrig").string()});
  CHECK(r.status == 1);
  CHECK(r.err.size() < 1100);
  CHECK(r.err.find("rig.json: pose 'NNN") != std::string::npos);
  CHECK(r.err.find(" characters ...] ") != std::string::npos);
  CHECK(r.err.find("(index 1): the name is used by pose 0 too\n") != std::string::npos);
}

TEST_CASE("a pose-space grid finer than bakes within 1 GB is refused") {
  json d = ValidDescription();
  d["bake"]["grid_resolution"] = 1024;
  ExpectFailure(d.dump(), "bake.grid_resolution: must be in 2..256 (finer grids need more than 1 GB to bake)");
}
