// SPDX-License-Identifier: MIT
// Frames drawn by the viewer on lavapipe, compared with goldens in
// tests/goldens/: exact bytes first; on a mismatch a tolerant comparison
// decides (a driver or CPU with other rounding), and the actual frame and a
// diff image are written for a person to look at. POSEMORPH_BLESS=1 rewrites
// the goldens. The Vulkan validation layer is on; any message fails.
#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>

#include "posemorph/bake/bake.h"
#include "posemorph/rig.h"
#include "scene.h"

using namespace posemorph;
using namespace posemorph::viewer;
namespace fs = std::filesystem;

namespace {

constexpr std::uint32_t kSize = 256;
const float kBackground[4] = {0.93f, 0.94f, 0.95f, 1.0f};

struct Fixture {
  Gpu gpu;
  Rig rig;
  std::vector<unsigned char> bytes;
  Drawings drawings;
  std::string images = std::string(POSEMORPH_DRAWN_SAMPLES) + "/pip";
  Fixture() {
    bake::RigDescription d = bake::ReadRigDescription(images + "/pip.json");
    bytes = bake::BakeRig(d);
    Error err;
    REQUIRE_MESSAGE(LoadRig(bytes.data(), bytes.size(), &rig, &err), err.message);
    std::string problem;
    REQUIRE_MESSAGE(LoadDrawings(rig, images, &drawings, &problem), problem);
    GpuOptions options;
    options.validation = true;
    REQUIRE_MESSAGE(gpu.Init(options, &problem), problem);
  }
};

Fixture& Shared() {
  static std::unique_ptr<Fixture> f;
  if (!f) f = std::make_unique<Fixture>();
  return *f;
}

std::vector<unsigned char> Render(const Scene& scene, const View* override_view = nullptr) {
  Fixture& f = Shared();
  RigRenderer renderer;
  std::string problem;
  REQUIRE_MESSAGE(renderer.Init(f.gpu, f.rig, f.drawings, OffscreenTarget::kFormat, scene.crowd, &problem), problem);
  View view;
  std::uint32_t count = 0;
  SceneScratch scratch;
  REQUIRE_MESSAGE(PrepareScene(f.rig, scene, renderer, scratch, &view, &count, &problem), problem);
  if (override_view) view = *override_view;
  OffscreenTarget target;
  target.Init(f.gpu, kSize, kSize);
  target.Render([&](VkCommandBuffer cmd) { renderer.Record(cmd, count, view, kSize, kSize, scene.wireframe); },
                kBackground);
  CHECK(f.gpu.validation_messages() == 0);
  return std::vector<unsigned char>(target.pixels(), target.pixels() + 4 * kSize * kSize);
}

void CompareWithGolden(const std::string& name, const std::vector<unsigned char>& actual) {
  const std::string golden = std::string(POSEMORPH_SOURCE_DIR) + "/tests/goldens/" + name + ".png";
  std::string problem;
  if (std::getenv("POSEMORPH_BLESS")) {
    REQUIRE_MESSAGE(WritePng(golden, actual.data(), kSize, kSize, &problem), problem);
    MESSAGE("blessed " << golden);
    return;
  }
  std::vector<unsigned char> expected;
  std::uint32_t w = 0, h = 0;
  const bool read = ReadPng(golden, &expected, &w, &h, &problem);
  REQUIRE_MESSAGE(read, problem << " (run with POSEMORPH_BLESS=1 to create it)");
  REQUIRE(w == kSize);
  REQUIRE(h == kSize);
  if (expected == actual) return;  // the exact hash matches

  // Tolerant: a pixel differs when a channel is off by more than 3; allow 0.5% of them.
  std::size_t differing = 0;
  int worst = 0;
  std::vector<unsigned char> diff(actual.size(), 255);
  for (std::size_t p = 0; p < actual.size(); p += 4) {
    int d = 0;
    for (int c = 0; c < 4; ++c) d = std::max(d, std::abs(int(actual[p + c]) - int(expected[p + c])));
    worst = std::max(worst, d);
    if (d > 3) ++differing;
    const unsigned char v = (unsigned char)std::min(255, d * 8);
    diff[p] = 255, diff[p + 1] = (unsigned char)(255 - v), diff[p + 2] = (unsigned char)(255 - v);
  }
  const fs::path out = fs::path(POSEMORPH_FRAME_OUTPUT);
  fs::create_directories(out);
  WritePng((out / (name + "-actual.png")).string(), actual.data(), kSize, kSize, &problem);
  WritePng((out / (name + "-diff.png")).string(), diff.data(), kSize, kSize, &problem);
  const double share = double(differing) / (kSize * kSize);
  MESSAGE(name << ": not bit-identical to its golden; " << differing << " pixels (" << share * 100
               << "%) differ by more than 3, worst " << worst << "; actual and diff in " << out.string());
  CHECK(share <= 0.005);
}

}  // namespace

TEST_CASE("frames: a base pose exactly") {
  Scene s;
  CompareWithGolden("pip-rest", Render(s));
}

TEST_CASE("frames: a midpoint between four poses") {
  Scene s;
  s.x = 0.5, s.y = 0.5;
  CompareWithGolden("pip-midpoint", Render(s));
}

TEST_CASE("frames: extrapolated beyond a pose") {
  Scene s;
  s.x = 1.4;
  CompareWithGolden("pip-extrapolated", Render(s));
}

TEST_CASE("frames: texture sharpening sigma 0 and 0.8") {
  Scene s;
  s.x = 0.5, s.y = 0.5;
  s.sigma = 0;
  const auto soft = Render(s);
  CompareWithGolden("pip-sigma0", soft);
  s.sigma = 0.8;
  const auto sharp = Render(s);
  CompareWithGolden("pip-sigma0.8", sharp);
  CHECK(soft != sharp);
}

TEST_CASE("frames: a crowd of 9 on a path, one instanced draw") {
  Scene s;
  s.path = "hello";
  s.crowd = 9;
  CompareWithGolden("pip-crowd9", Render(s));
}

TEST_CASE("frames: the rendered base pose is its own drawing where the mesh covers it") {
  // Rig coordinates of a drawn pose are its pixels with y negated, so this view
  // maps output pixel (x, y) onto drawing pixel (x, y).
  Fixture& f = Shared();
  REQUIRE(f.drawings.width == kSize);
  const View pixels{0, -double(kSize), double(kSize), 0};
  for (std::uint32_t pose = 0; pose < f.rig.pose_count(); ++pose) {
    CAPTURE(pose);
    Scene s;
    s.x = f.rig.pose_points().data[2 * pose], s.y = f.rig.pose_points().data[2 * pose + 1];
    s.sigma = 1;
    const auto frame = Render(s, &pixels);
    const std::vector<unsigned char>& drawing = f.drawings.rgba[pose];
    std::size_t compared = 0, off = 0;
    for (std::size_t p = 0; p < frame.size(); p += 4) {
      if (drawing[p + 3] < 255) continue;  // opaque drawing pixels: frame = drawing (premultiplied = straight)
      ++compared;
      int d = 0;
      for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(int(frame[p + c]) - int(drawing[p + c])));
      off += d > 2;
    }
    CHECK(compared > 10000);
    CHECK(double(off) / double(compared) < 0.002);
  }
}

TEST_CASE("frames: a character shows all its drawings up to 8, else the 8 most weighted") {
  const double five[5] = {0.1, 0.4, 0.0, 0.3, 0.2};
  InstanceData inst;
  PickDrawings(five, 5, &inst);
  double sum = 0;
  for (std::uint32_t k = 0; k < kDrawingsPerCharacter; ++k) sum += inst.weights[k];
  CHECK(sum == doctest::Approx(1.0));
  CHECK(inst.layers[0] == 1);
  CHECK(inst.weights[0] == doctest::Approx(0.4));
  CHECK(inst.layers[3] == 0);
  CHECK(inst.weights[3] == doctest::Approx(0.1));

  double ten[10];
  for (int i = 0; i < 10; ++i) ten[i] = (i + 1) / 55.0;  // 1..10, sum 1
  PickDrawings(ten, 10, &inst);
  CHECK(inst.layers[0] == 9);
  CHECK(inst.layers[7] == 2);
  CHECK(inst.weights[0] == doctest::Approx(10.0 / 52.0));  // poses 0 and 1 (weights 1, 2) dropped
}
