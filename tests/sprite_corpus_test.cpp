// SPDX-License-Identifier: MIT
// The sprite corpus (assets/sprites/: small characters drawn for these tests,
// 24 to 80 pixels, 3 to 4 poses, anti-aliased and pixel-art, one on canvases
// that differ): default settings bake them fold-free, with meshes in
// proportion to the sprite that enclose the anti-aliased fringe; and
// `posemorph-bake outline` draws what the bake traces.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <unistd.h>

#include "cli.h"
#include "posemorph/bake/bake.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/mapping/outline_image.h"
#include "posemorph/bake/rig_description.h"
#include "textured_sheet.h"
#include "drawing_coverage.h"

namespace pb = posemorph::bake;
using Point = Eigen::Vector2d;

namespace {

std::string SpriteDir(const std::string& name) { return std::string(POSEMORPH_DRAWN_SAMPLES) + "/sprites/" + name; }

}  // namespace

TEST_CASE("sprites: the corpus bakes fold-free with default settings, meshes in proportion, the fringe enclosed") {
  for (const std::string name : {"slime", "chick", "ghost", "cat"}) {
    CAPTURE(name);
    const std::string dir = SpriteDir(name);
    REQUIRE_MESSAGE(std::filesystem::exists(dir + "/" + name + ".json"), "the build rasterises the sprites");
    const pb::RigDescription rig = pb::ReadRigDescription(dir + "/" + name + ".json");
    // No mapping settings: the defaults are what is tested.
    CHECK(rig.mapping.simplify_tolerance == 0);
    CHECK(rig.mapping.max_edge_length == 0);
    CHECK(rig.mapping.spacing == 0);
    pb::BakeReport report;
    REQUIRE_NOTHROW(pb::BakeRig(rig, &report));  // a fold in the hull would throw
    CHECK(report.mapping.fold_retries == 0);     // and the first mapping is fold-free
    CHECK(report.inbetweens.FoldsInHull() == 0);
    CHECK(report.inbetweens.min_area_ratio > 0.5);
    CHECK(report.mapping.min_angle_degrees > 9);
    CHECK(report.mapping.warnings.empty());  // no dropped part, no start landmark that seems misplaced

    const pb::MappedDrawings mapped = pb::MapDrawings(rig);
    std::size_t opaque = 0;
    std::vector<Point> canvases;
    for (std::size_t k = 0; k < mapped.meshes.size(); ++k) {
      const pb::PoseMesh& pose = mapped.meshes[k];
      CAPTURE(pose.name);
      const posemorph::test::DrawingCoverage c =
          posemorph::test::CoverageOf(pose.uvs, mapped.triangles, dir + "/" + pose.image, rig.mapping.alpha_threshold);
      MESSAGE(name << " " << pose.name << ": " << c.opaque << " opaque pixels, alpha outside the mesh "
                   << 100 * c.alpha_outside_share << "%");
      CHECK(c.shape_uncovered == 0);         // every pixel of the traced shape is meshed
      CHECK(c.alpha_outside_share < 0.001);  // the fringe below the threshold is nearly nothing
      opaque = std::max(opaque, c.opaque);
      canvases.push_back(pose.canvas_size);
      // The origin (the cat's: between its feet, on the outline) is the rig's (0, 0) in every pose.
      if (name == "cat") {
        double nearest = 1e9;
        for (const Point& v : pose.vertices) nearest = std::min(nearest, v.norm());
        CHECK(nearest < 1.5);
      }
    }
    MESSAGE(name << ": " << report.vertices << " vertices, " << report.triangles << " triangles for up to " << opaque
                 << " opaque pixels; min angle " << report.mapping.min_angle_degrees
                 << ", smallest in-between area ratio " << report.inbetweens.min_area_ratio << ", bake "
                 << report.seconds * 1e3 << " ms");
    // In proportion: at most one vertex per 3 opaque pixels (a 32-pixel
    // sprite had 617 vertices for 460 opaque pixels with 256-pixel defaults).
    CHECK(report.vertices * 3 <= opaque);
    if (name == "cat") CHECK(std::count(canvases.begin(), canvases.end(), canvases[0]) < long(canvases.size()));
  }
}

TEST_CASE("mapping: a start landmark on another part of the outline than in pose 0 is named, with where it fits") {
  // The slime with only its start landmarks: in 'squash' it is put on the
  // top of the dome instead of between the feet.
  pb::RigDescription rig = pb::ReadRigDescription(SpriteDir("slime") + "/slime.json");
  for (pb::PoseDescription& pose : rig.poses) pose.landmarks.resize(1);
  const pb::MappedDrawings aligned = pb::MapDrawings(rig);
  CHECK(aligned.report.warnings.empty());
  rig.poses[1].landmarks[0] = Point(16, 16);
  const pb::MappedDrawings moved = pb::MapDrawings(rig);
  REQUIRE(moved.report.warnings.size() == 1);
  const std::string& w = moved.report.warnings[0];
  CAPTURE(w);
  CHECK(w.find("pose 'squash' (index 1): its start landmark (landmark 0) may sit on another part of the outline "
               "than in pose 'rest' (index 0)") != std::string::npos);
  CHECK(w.find("if the in-betweens spin, move landmark 0 there") != std::string::npos);
  // It suggests the bottom of the squashed slime, where the start belongs (16, 29).
  const std::size_t near = w.find(") in its drawing");
  REQUIRE(near != std::string::npos);
  const std::size_t open = w.rfind("near (", near);
  double x = 0, y = 0;
  REQUIRE(std::sscanf(w.c_str() + open, "near (%lf, %lf)", &x, &y) == 2);
  CHECK(std::abs(y - 29) < 2);
  CHECK(std::abs(x - 16) < 4);

  // When the mapping then fails (here: a vertex budget too small for any
  // mesh), the error names the start landmark too, as a likely cause.
  rig.mapping.max_vertices = 10;
  try {
    pb::MapDrawings(rig);
    FAIL("the mapping should fail");
  } catch (const pb::BakeError& e) {
    const std::string what = e.what();
    CAPTURE(what);
    CHECK(what.find("needs more than mapping.max_vertices 10") != std::string::npos);
    CHECK(what.find("; pose 'squash' (index 1): its start landmark (landmark 0) may sit on another part of the "
                    "outline than in pose 'rest' (index 0) (a start that switches feet between poses, say)") !=
          std::string::npos);
    CHECK(what.find("move landmark 0 there") != std::string::npos);
  }
  // Without the misplaced start the same failure says nothing of it.
  rig.poses[1].landmarks = pb::ReadRigDescription(SpriteDir("slime") + "/slime.json").poses[1].landmarks;
  rig.poses[1].landmarks.resize(1);
  try {
    pb::MapDrawings(rig);
    FAIL("the mapping should fail");
  } catch (const pb::BakeError& e) {
    CHECK(std::string(e.what()).find("start landmark") == std::string::npos);
  }
}

TEST_CASE("posemorph-bake outline: one picture per drawn pose, drawn from what the bake traces") {
  namespace fs = std::filesystem;
  const fs::path out_dir = fs::temp_directory_path() / ("posemorph-outline-" + std::to_string(::getpid()));
  fs::remove_all(out_dir);
  fs::create_directories(out_dir);
  auto run = [](const std::vector<std::string>& args, std::string* out, std::string* err) {
    std::ostringstream o, e;
    const int status = pb::RunBakeCommand(args, o, e);
    *out = o.str();
    *err = e.str();
    return status;
  };
  const std::string chick = SpriteDir("chick") + "/chick.json";
  std::string out, err;
  REQUIRE(run({"outline", chick, "-o", out_dir.string()}, &out, &err) == 0);
  CAPTURE(out);
  CHECK(err.empty());
  const pb::RigDescription rig = pb::ReadRigDescription(chick);
  for (std::size_t i = 0; i < rig.poses.size(); ++i) {
    const std::string path = (out_dir / (std::to_string(i) + "-" + rig.poses[i].name + ".png")).string();
    CAPTURE(path);
    REQUIRE(fs::exists(path));
    const pb::RgbaImage picture = pb::ReadRgbaPng(path);
    CHECK(picture.width == 24 * 16);  // a 24-pixel canvas at 16 pixels per drawing pixel
    CHECK(picture.height == 24 * 16);
    // The start landmark is a green disc (0, 170, 60) at its point.
    const Point at = rig.poses[i].landmarks[0] * 16;
    const unsigned char* p = &picture.rgba[(std::size_t(at.y()) * picture.width + std::size_t(at.x())) * 4];
    CHECK(int(p[0]) == 0);
    CHECK(int(p[1]) == 170);
    CHECK(int(p[2]) == 60);
  }
  CHECK(out.find("boundary vertices, 3 landmarks)") != std::string::npos);

  // A landmark far off the outline: the mapping fails, the pictures (what
  // was traced, the landmark and its ring) are still written, and the
  // error is one line.
  const fs::path bad_dir = out_dir / "bad";
  fs::create_directories(bad_dir);
  for (const char* f : {"rest.png", "flap.png", "hop.png"}) fs::copy(SpriteDir("chick") + "/" + f, bad_dir / f);
  {
    std::ifstream in(chick);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text.replace(text.find("[12, 21]]"), 9, "[12, 12]]");  // rest's third landmark inside the body
    std::ofstream(bad_dir / "chick.json") << text;
  }
  CHECK(run({"outline", (bad_dir / "chick.json").string(), "-o", bad_dir.string()}, &out, &err) == 1);
  CAPTURE(err);
  CHECK(err.find("landmark 2 is ") != std::string::npos);
  CHECK(err.find("(the pictures show the outlines and landmarks as traced)\n") != std::string::npos);
  CHECK(std::count(err.begin(), err.end(), '\n') == 1);
  CHECK(fs::exists(bad_dir / "0-rest.png"));
  // Features (Pip's eyes) are amber crosses at their points: 256-pixel
  // drawings at 2 pixels per drawing pixel.
  const fs::path pip_dir = out_dir / "pip";
  fs::create_directories(pip_dir);
  const std::string pip = std::string(POSEMORPH_DRAWN_SAMPLES) + "/pip/pip.json";
  REQUIRE(run({"outline", pip, "-o", pip_dir.string()}, &out, &err) == 0);
  CHECK(out.find("4 landmarks, 2 features)") != std::string::npos);
  const pb::RigDescription pip_rig = pb::ReadRigDescription(pip);
  for (std::size_t i = 0; i < pip_rig.poses.size(); ++i) {
    const pb::RgbaImage picture =
        pb::ReadRgbaPng((pip_dir / (std::to_string(i) + "-" + pip_rig.poses[i].name + ".png")).string());
    REQUIRE(picture.width == 512);
    for (const Point& feature : pip_rig.poses[i].features) {
      const Point at = feature * 2;
      const unsigned char* p = &picture.rgba[(std::size_t(at.y()) * picture.width + std::size_t(at.x())) * 4];
      CHECK(int(p[0]) == 255);
      CHECK(int(p[1]) == 190);
      CHECK(int(p[2]) == 0);
    }
  }
  // Usage: a folder is needed.
  CHECK(run({"outline", chick}, &out, &err) == 2);
  CHECK(run({"outline", chick, "-o", (out_dir / "missing").string()}, &out, &err) == 1);
  CHECK(err.find("is not a folder") != std::string::npos);
  fs::remove_all(out_dir);
}

TEST_CASE("sprites: a drop shadow is left out of the mesh with a warning in drawing pixels, the fringe still covered") {
  // slime-shadow: the slime over a dark ellipse of 40% alpha, larger than
  // the slime and offset to the right, touching its base.
  const std::string dir = SpriteDir("slime-shadow");
  REQUIRE_MESSAGE(std::filesystem::exists(dir + "/slime-shadow.json"), "the build rasterises the sprites");
  const pb::RigDescription rig = pb::ReadRigDescription(dir + "/slime-shadow.json");
  CHECK(rig.mapping.drop_shadows);  // the default
  {
    const std::string base = R"({"posemorph": 1, "poses": [
        {"name": "a", "point": [0, 0], "outline": [[0, 0], [1, 0], [0, 1]], "landmarks": [[0, 0]]},
        {"name": "b", "point": [1, 0], "outline": [[0, 0], [2, 0], [0, 1]], "landmarks": [[0, 0]]}], "mapping": )";
    CHECK(!pb::ParseRigDescription(base + R"({"drop_shadows": false}})", "r.json", ".").mapping.drop_shadows);
    CHECK_THROWS_WITH_AS(pb::ParseRigDescription(base + R"({"drop_shadows": "yes"}})", "r.json", "."),
                         "r.json: mapping.drop_shadows: expected true or false", pb::BakeError);
  }
  pb::BakeReport report;
  REQUIRE_NOTHROW(pb::BakeRig(rig, &report));
  std::size_t said = 0;
  for (const std::string& w : report.mapping.warnings)
    said += w.find("is taken as its drop shadow and left out of the mesh") != std::string::npos;
  CHECK(said == 4);  // one line per drawing
  REQUIRE(!report.mapping.warnings.empty());
  CHECK(report.mapping.warnings[0].find("rest.png: a dark, semi-transparent region of ") != std::string::npos);
  CHECK(report.mapping.warnings[0].find(") in the drawing (mean alpha 0.3") != std::string::npos);
  CHECK(report.inbetweens.FoldsInHull() == 0);

  for (const std::string pose : {"rest", "squash", "stretch", "lean"}) {
    CAPTURE(pose);
    const std::string png = dir + "/" + pose + ".png";
    const pb::ErrorSource source(png);
    const pb::mapping::ImageOutline without = pb::mapping::OutlineFromPng(png, 0.05, source, false, true);
    const pb::mapping::ImageOutline with = pb::mapping::OutlineFromPng(png, 0.05, source, false, false);
    double bottom_without = 0, bottom_with = 0, right_without = 0, right_with = 0;
    for (const Point& p : without.outline)
      bottom_without = std::max(bottom_without, p.y()), right_without = std::max(right_without, p.x());
    for (const Point& p : with.outline)
      bottom_with = std::max(bottom_with, p.y()), right_with = std::max(right_with, p.x());
    // The slime's base is at y = 31 (its stroke to 31.5); the shadow reaches 35.5 and x 39.
    CHECK(bottom_without < 32.5);
    CHECK(bottom_with > 34.5);
    CHECK(right_without < right_with - 3);
    CHECK(without.shadow_pixels > 80);
    CHECK(with.shadow_pixels == 0);
    // Every pixel of alpha >= 0.05 that is not the shadow's has its centre
    // inside the traced outline (or on it): the fringe is still meshed.
    int W = 0, H = 0;
    const std::vector<unsigned char> rgba = pb::mapping::ReadPngRgba(png, &W, &H, source);
    std::vector<unsigned char> shadow;
    pb::mapping::ImageOutline found;
    pb::mapping::FindDropShadow(rgba.data(), W, H, 0.05, shadow, found);
    CHECK(found.shadow_pixels == without.shadow_pixels);
    const std::vector<Point>& o = without.outline;
    auto inside = [&](const Point& q) {
      bool in = false;
      for (std::size_t i = 0, j = o.size() - 1; i < o.size(); j = i++) {
        const Point &a = o[j], &b = o[i];
        const Point d = b - a;
        const double t = std::clamp((q - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
        if ((a + t * d - q).norm() < 0.01) return true;  // on the outline
        if ((a.y() > q.y()) != (b.y() > q.y()) && q.x() < a.x() + (q.y() - a.y()) * d.x() / d.y()) in = !in;
      }
      return in;
    };
    std::size_t uncovered = 0, shape = 0;
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        const std::size_t i = std::size_t(y) * W + x;
        if (rgba[4 * i + 3] < 13 || shadow[i]) continue;
        ++shape;
        uncovered += !inside(Point(x + 0.5, y + 0.5));
      }
    MESSAGE(pose << ": " << without.shadow_pixels << " shadow pixels left out, " << shape << " pixels of the slime, "
                 << uncovered << " of them outside the outline");
    CHECK(uncovered == 0);
  }
}

TEST_CASE("sprites: a band pixel two drop shadows reach is counted once") {
  // The fuzzer's finding (tests/fuzz/corpus/png_outline/): random RGBA of
  // 64 x 64 in which two shadow regions grow into one band pixel; it was
  // counted in both, so the count disagreed with the pixels marked.
  std::ifstream f(std::string(POSEMORPH_SOURCE_DIR) + "/tests/fuzz/corpus/png_outline/shadow-band-pixel-of-two-regions",
                  std::ios::binary);
  const std::vector<unsigned char> data((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  REQUIRE(data.size() > 3);
  const int w = data[1] % 64 + 1, h = data[2] % 64 + 1;  // as the harness reads it
  std::vector<unsigned char> rgba(std::size_t(w) * h * 4, 0), shadow;
  for (std::size_t i = 0; i < rgba.size() && 3 + i < data.size(); ++i) rgba[i] = data[3 + i];
  pb::mapping::ImageOutline found;
  const std::size_t marked = pb::mapping::FindDropShadow(rgba.data(), w, h, 0.05, shadow, found);
  CHECK(marked > 0);
  CHECK(std::size_t(std::count(shadow.begin(), shadow.end(), 1)) == marked);
  CHECK(found.shadow_pixels == marked);
}
