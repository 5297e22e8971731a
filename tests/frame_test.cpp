// SPDX-License-Identifier: MIT
// Frames drawn by the viewer on lavapipe, compared with goldens in
// tests/goldens/: exact bytes first; on a mismatch a tolerant comparison
// decides (a driver or CPU with other rounding), and the actual frame and a
// diff image are written for a person to look at. POSEMORPH_BLESS=1 rewrites
// the goldens. The Vulkan validation layer is on; any message fails.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "posemorph/bake/bake.h"
#include "posemorph/bake/rig_description.h"
#include "posemorph/rig.h"
#include "machine_driver.h"
#include "scene.h"

using namespace posemorph;
using namespace posemorph::viewer;
namespace fs = std::filesystem;

namespace {

constexpr std::uint32_t kSize = 256;
const float kBackground[4] = {0.93f, 0.94f, 0.95f, 1.0f};

// A drawn sample of the build (assets/NAME/NAME.json), baked exact (the
// goldens are frames of the exact rig), with its drawings.
struct DrawnSample {
  Rig rig;
  std::vector<unsigned char> bytes;
  Drawings drawings;
  std::string images;
  // assets/FOLDER/NAME.json (FOLDER: NAME by default), baked exact.
  explicit DrawnSample(const std::string& name, const std::string& folder = "")
      : images(std::string(POSEMORPH_DRAWN_SAMPLES) + "/" + (folder.empty() ? name : folder)) {
    bake::RigDescription d = bake::ReadRigDescription(images + "/" + name + ".json");
    d.parameters.compact = false;
    bytes = bake::BakeRig(d);
    Error err;
    REQUIRE_MESSAGE(LoadRig(bytes.data(), bytes.size(), &rig, &err), err.message);
    std::string problem;
    REQUIRE_MESSAGE(LoadDrawings(rig, images, &drawings, &problem), problem);
  }
};

struct Fixture : DrawnSample {
  Gpu gpu;
  Fixture() : DrawnSample("pip") {
    std::string problem;
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

// Renders a scene of `rig`; the camera fits it unless one is given.
std::vector<unsigned char> RenderRig(const Rig& rig, const Drawings& drawings, const Scene& scene,
                                     const Camera* camera = nullptr, Blend blend = Blend::kExact) {
  Fixture& f = Shared();
  RigRenderer renderer;
  std::string problem;
  REQUIRE_MESSAGE(renderer.Init(f.gpu, rig, drawings, OffscreenTarget::kFormat, SceneCharacters(rig, scene),
                                SceneFilter(rig, scene), &problem),
                  problem);
  SceneBounds bounds;
  std::uint32_t count = 0;
  SceneScratch scratch;
  REQUIRE_MESSAGE(PrepareScene(rig, scene, renderer, scratch, &bounds, &count, &problem), problem);
  const Camera cam = camera ? *camera : FitCamera(bounds.all, kSize, kSize);
  OffscreenTarget target;
  target.Init(f.gpu, kSize, kSize);
  target.Render(
      [&](VkCommandBuffer cmd) { renderer.Record(cmd, count, cam, kSize, kSize, scene.wireframe, 0, 0, blend); },
      kBackground);
  CHECK(f.gpu.validation_messages() == 0);
  return std::vector<unsigned char>(target.pixels(), target.pixels() + 4 * kSize * kSize);
}

// Renders a scene of Pip.
std::vector<unsigned char> Render(const Scene& scene, const Camera* camera = nullptr, Blend blend = Blend::kExact) {
  return RenderRig(Shared().rig, Shared().drawings, scene, camera, blend);
}

using Difference = FrameDifference;
Difference Compare(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b,
                   std::vector<unsigned char>* diff = nullptr) {
  return CompareFrames(a, b, diff);
}

std::vector<unsigned char> MirrorRows(const std::vector<unsigned char>& frame) {
  std::vector<unsigned char> out(frame.size());
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x)
      for (int c = 0; c < 4; ++c)
        out[(std::size_t(y) * kSize + x) * 4 + c] = frame[(std::size_t(y) * kSize + (kSize - 1 - x)) * 4 + c];
  return out;
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
  std::vector<unsigned char> diff;
  const Difference d = Compare(actual, expected, &diff);
  const std::size_t differing = d.differing;
  const int worst = d.worst;
  const fs::path out = fs::path(POSEMORPH_FRAME_OUTPUT);
  fs::create_directories(out);
  WritePng((out / (name + "-actual.png")).string(), actual.data(), kSize, kSize, &problem);
  WritePng((out / (name + "-diff.png")).string(), diff.data(), kSize, kSize, &problem);
  const double share = d.share();
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
  // Off the diagonal: at (0.5, 0.5) no texture weight reaches 0.4, and
  // sigma 0.8 (a step from 0.4 to 0.6) renormalises back to the same blend.
  Scene s;
  s.x = 0.3, s.y = 0.6;
  s.sigma = 0;
  const auto soft = Render(s);
  CompareWithGolden("pip-sigma0", soft);
  s.sigma = 0.8;
  const auto sharp = Render(s);
  CompareWithGolden("pip-sigma0.8", sharp);
  CHECK(soft != sharp);
}

TEST_CASE("frames: a mixed crowd of 12 on a ground line, back to front, one instanced draw") {
  Scene s;
  s.path = "hello";
  s.crowd = 12;
  s.seed = 7;
  const auto crowd = Render(s);
  CompareWithGolden("pip-crowd-mixed", crowd);
  s.seed = 8;
  CHECK(Compare(Render(s), crowd).share() > 0.05);  // the seed moves them
}

TEST_CASE("frames: the crowd layout is seeded, sorted back to front, and mixes sizes and facings") {
  Fixture& f = Shared();
  constexpr std::uint32_t K = 40;
  std::vector<Transform2D> t(K), again(K);
  std::vector<double> phase(K), phase_again(K);
  CrowdLayout(f.rig, K, 3, t.data(), phase.data());
  CrowdLayout(f.rig, K, 3, again.data(), phase_again.data());
  CHECK(std::memcmp(t.data(), again.data(), K * sizeof(Transform2D)) == 0);
  std::uint32_t mirrored = 0;
  double smallest = 1e9, largest = 0;
  std::vector<bool> phase_seen(K, false);
  for (std::uint32_t k = 0; k < K; ++k) {
    const double scale = std::sqrt(std::fabs(double(t[k].a) * t[k].d - double(t[k].b) * t[k].c));
    smallest = std::min(smallest, scale), largest = std::max(largest, scale);
    mirrored += t[k].mirrors();
    // Back to front: farther characters (smaller, standing higher) come first.
    if (k > 0)
      CHECK(scale >= std::sqrt(std::fabs(double(t[k - 1].a) * t[k - 1].d - double(t[k - 1].b) * t[k - 1].c)) - 1e-6);
    if (k > 0) CHECK(t[k].ty <= t[k - 1].ty + 1e-3f);
    const auto index = std::uint32_t(std::lround(phase[k] * K));
    REQUIRE(index < K);
    phase_seen[index] = true;
  }
  CHECK(mirrored > K / 4);
  CHECK(mirrored < 3 * K / 4);
  CHECK(largest / smallest > 1.5);
  CHECK(std::count(phase_seen.begin(), phase_seen.end(), true) == K);  // every phase once
}

TEST_CASE("frames: a mirrored character is the unmirrored frame flipped") {
  Scene s;
  s.x = 0.5, s.y = 0.5;
  const auto plain = Render(s);
  s.transform = Transform2D::Make(0, 0, 0, 1, 1, true);
  const auto mirrored = Render(s);
  CompareWithGolden("pip-mirrored", mirrored);
  const Difference d = Compare(mirrored, MirrorRows(plain));
  MESSAGE("mirrored vs flipped: " << d.differing << " pixels differ by more than 3 (worst " << d.worst << ")");
  CHECK(d.share() <= 0.005);
  CHECK(Compare(mirrored, plain).share() > 0.05);  // and it is not the same frame
}

TEST_CASE("frames: a rotated, non-uniformly scaled character, and a zoomed camera") {
  Scene s;
  s.x = 0.5, s.y = 0.5;
  s.transform = Transform2D::Make(40, -10, 30 * 3.14159265358979323846 / 180, 1.5, 0.8);
  CompareWithGolden("pip-rotated-scaled", Render(s));

  Scene plain;
  Fixture& f = Shared();
  const View one = CharacterBounds(f.rig);
  Camera zoomed = FitCamera(one, kSize, kSize);
  zoomed.zoom *= 2.5;
  zoomed.centre.y += 0.02 * (one.y1 - one.y0);  // the face
  CompareWithGolden("pip-zoomed", Render(plain, &zoomed));
}

TEST_CASE("frames: sequential over equals the exact blend where one drawing shows, and differs mid-way") {
  Fixture& f = Shared();
  Scene base;
  base.x = f.rig.pose_points().data[2], base.y = f.rig.pose_points().data[3];
  base.sigma = 1;
  CHECK(Render(base) == Render(base, nullptr, Blend::kSequentialOver));
  Scene mid;
  mid.x = 0.5, mid.y = 0.5;
  const auto exact = Render(mid);
  const Difference over = Compare(Render(mid, nullptr, Blend::kSequentialOver), exact);
  mid.max_drawings = 1;
  const Difference dominant = Compare(Render(mid), exact);
  MESSAGE("at (0.5, 0.5) against the exact blend: sequential over " << over.differing << " pixels (worst " << over.worst
                                                                    << "), dominant drawing only " << dominant.differing
                                                                    << " pixels (worst " << dominant.worst << ")");
  CHECK(over.differing > 0);
  CHECK(dominant.differing > 0);
}

TEST_CASE("frames: the rendered base pose is its own drawing where the mesh covers it") {
  // Rig coordinates of a drawn pose are its pixels with y negated, so this view
  // maps output pixel (x, y) onto drawing pixel (x, y).
  Fixture& f = Shared();
  REQUIRE(f.drawings.width == kSize);
  Camera pixels;
  pixels.centre = {kSize / 2.0, -(kSize / 2.0)};
  pixels.zoom = 1;
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

TEST_CASE(
    "frames: sampled nearest (pixel art), a drawing pixel is one flat block at zoom 4, and is the drawing's colour") {
  // Zoom 4 about a whole drawing point: each drawing pixel covers a 4 x 4
  // block of output pixels. Nearest sampling makes every block inside the
  // drawing flat and of its pixel's colour; linear sampling blends across
  // pixel edges.
  Fixture& f = Shared();
  Camera zoomed;
  zoomed.centre = {128, -120};
  zoomed.zoom = 4;
  Scene s;
  s.x = f.rig.pose_points().data[0], s.y = f.rig.pose_points().data[1];
  s.sigma = 1;
  auto blocks = [&](const std::vector<unsigned char>& frame, std::size_t* flat, std::size_t* true_colour) {
    std::size_t inside = 0;
    *flat = *true_colour = 0;
    for (std::uint32_t by = 0; by < kSize / 4; ++by)
      for (std::uint32_t bx = 0; bx < kSize / 4; ++bx) {
        // Output block (bx, by) shows drawing pixel (96 + bx, 88 + by).
        const std::size_t d = (std::size_t(88 + by) * kSize + 96 + bx) * 4;
        if (f.drawings.rgba[0][d + 3] < 255) continue;
        ++inside;
        const std::size_t first = (std::size_t(4 * by) * kSize + 4 * bx) * 4;
        bool same = true;
        for (std::uint32_t y = 0; y < 4; ++y)
          for (std::uint32_t x = 0; x < 4; ++x)
            same =
                same && std::memcmp(&frame[first], &frame[(std::size_t(4 * by + y) * kSize + 4 * bx + x) * 4], 4) == 0;
        *flat += same;
        int off = 0;
        for (int c = 0; c < 3; ++c)
          off = std::max(off, std::abs(int(frame[first + c]) - int(f.drawings.rgba[0][d + c])));
        *true_colour += off <= 2;
      }
    return inside;
  };
  s.filter = 1;
  std::size_t flat = 0, true_colour = 0;
  const std::size_t inside = blocks(Render(s, &zoomed), &flat, &true_colour);
  s.filter = 0;
  std::size_t linear_flat = 0, linear_true = 0;
  blocks(Render(s, &zoomed), &linear_flat, &linear_true);
  MESSAGE("zoom 4, " << inside << " opaque drawing pixels: flat blocks " << flat << " nearest, " << linear_flat
                     << " linear; of the drawing's colour " << true_colour << " nearest, " << linear_true << " linear");
  REQUIRE(inside > 2000);
  CHECK(double(flat) >= 0.999 * double(inside));
  CHECK(double(true_colour) >= 0.999 * double(inside));
  CHECK(double(linear_flat) < 0.9 * double(inside));
  // The rig's hint decides when --filter is not given: Pip's description has none.
  CHECK(f.rig.texture_filter() == TextureFilter::kLinear);
  CHECK(SceneFilter(f.rig, Scene{}) == TextureFilter::kLinear);
}

namespace {

// A layered character with drawings: tests/runtime/rigs/arm.json's body and
// arm, each part drawn in each pose on a 256 x 256 canvas (rig point (x, y)
// at pixel ((x + 35) * 2.2, (45 - y) * 2.2)) in its own flat colour, shaded
// by the pose. `arm_order` is the arm's "order": one, or one per pose.
constexpr double kArmScale = 2.2, kArmLeft = -35, kArmTop = 45;
const unsigned char kBodyColour[3] = {220, 110, 40}, kArmColour[3] = {40, 90, 200};

struct LayeredArm {
  Rig rig;
  std::vector<unsigned char> bytes;
  Drawings drawings;
};

bool InTriangle(double px, double py, const double* a, const double* b, const double* c) {
  const auto edge = [&](const double* p, const double* q) {
    return (q[0] - p[0]) * (py - p[1]) - (q[1] - p[1]) * (px - p[0]);
  };
  const double e0 = edge(a, b), e1 = edge(b, c), e2 = edge(c, a);
  return (e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0);
}

std::unique_ptr<LayeredArm> MakeLayeredArm(const nlohmann::json& arm_order) {
  std::ifstream in(std::string(POSEMORPH_SOURCE_DIR) + "/tests/runtime/rigs/arm.json");
  REQUIRE(in.good());
  nlohmann::json d = nlohmann::json::parse(in);
  d["parts"][1]["order"] = arm_order;
  d["bake"]["precision"] = "exact";
  // A folder of this process's own: ctest runs the test cases that make
  // the arm in parallel processes, which must not read each other's
  // half-written drawings.
  const std::string dir = std::string(POSEMORPH_FRAME_OUTPUT) + "/layered-arm-" + std::to_string(getpid());
  fs::create_directories(dir);
  std::string problem;
  for (std::size_t p = 0; p < 2; ++p) {
    nlohmann::json& part = d["parts"][p];
    const unsigned char* colour = p == 0 ? kBodyColour : kArmColour;
    for (std::size_t i = 0; i < part["poses"].size(); ++i) {
      nlohmann::json& pose = part["poses"][i];
      // Drawing pixels of the vertices, and their uvs.
      std::vector<double> px;
      nlohmann::json uvs = nlohmann::json::array();
      for (const auto& v : pose["vertices"]) {
        const double x = (v[0].get<double>() - kArmLeft) * kArmScale, y = (kArmTop - v[1].get<double>()) * kArmScale;
        px.insert(px.end(), {x, y});
        uvs.push_back({x / kSize, y / kSize});
      }
      std::vector<unsigned char> rgba(4 * kSize * kSize, 0);
      for (std::uint32_t y = 0; y < kSize; ++y)
        for (std::uint32_t x = 0; x < kSize; ++x)
          for (const auto& t : part["triangles"])
            if (InTriangle(x + 0.5, y + 0.5, &px[2 * t[0].get<std::size_t>()], &px[2 * t[1].get<std::size_t>()],
                           &px[2 * t[2].get<std::size_t>()])) {
              unsigned char* out = &rgba[4 * (std::size_t(y) * kSize + x)];
              out[0] = colour[0], out[1] = (unsigned char)(colour[1] + 30 * i), out[2] = colour[2], out[3] = 255;
              break;
            }
      const std::string name = (p == 0 ? "body-" : "arm-") + std::to_string(i) + ".png";
      REQUIRE_MESSAGE(WritePng(dir + "/" + name, rgba.data(), kSize, kSize, &problem), problem);
      pose["image"] = name;
      pose["uvs"] = uvs;
    }
  }
  auto out = std::make_unique<LayeredArm>();
  out->bytes = bake::BakeRig(bake::ParseRigDescription(d.dump(), "arm.json", dir));
  Error err;
  REQUIRE_MESSAGE(LoadRig(out->bytes.data(), out->bytes.size(), &out->rig, &err), err.message);
  REQUIRE_MESSAGE(LoadDrawings(out->rig, dir, &out->drawings, &problem), problem);
  return out;
}

// Output pixel (x, y) is drawing pixel (x, y).
Camera ArmPixels() {
  Camera c;
  c.centre = {kSize / 2.0 / kArmScale + kArmLeft, kArmTop - kSize / 2.0 / kArmScale};
  c.zoom = kArmScale;
  return c;
}

// Pixels of a frame in a part's colour (any pose's shade).
std::size_t CountColour(const std::vector<unsigned char>& frame, const unsigned char* colour) {
  std::size_t n = 0;
  for (std::size_t p = 0; p < frame.size(); p += 4)
    n += std::abs(int(frame[p]) - colour[0]) <= 3 && std::abs(int(frame[p + 2]) - colour[2]) <= 3 &&
         frame[p + 1] >= colour[1] - 3 && frame[p + 1] <= colour[1] + 63;
  return n;
}

}  // namespace

TEST_CASE("frames: a layered character's parts each show their own drawings, in the pose's draw order") {
  const auto arm = MakeLayeredArm(1);
  const Rig& rig = arm->rig;
  REQUIRE(rig.part_count() == 2);
  REQUIRE(arm->drawings.rgba.size() == 2 * rig.pose_count());
  REQUIRE(arm->drawings.pages == 2 * rig.pose_count());  // no atlas: a page per part and pose
  const Camera pixels = ArmPixels();
  for (std::uint32_t pose = 0; pose < rig.pose_count(); ++pose) {
    CAPTURE(pose);
    Scene s;
    s.x = rig.pose_points().data[2 * pose], s.y = rig.pose_points().data[2 * pose + 1];
    s.sigma = 1;
    const auto frame = RenderRig(rig, arm->drawings, s, &pixels);
    // The expected frame: the arm's drawing over the body's, where both are
    // opaque around the pixel (away from the outlines' edges).
    const std::vector<unsigned char>& body = arm->drawings.rgba[pose];
    const std::vector<unsigned char>& limb = arm->drawings.rgba[rig.pose_count() + pose];
    // 1: the drawing is opaque around the pixel, 0: clear around it, -1: its edge.
    const auto inside = [&](const std::vector<unsigned char>& d, std::uint32_t x, std::uint32_t y) {
      int opaque = 0;
      for (std::uint32_t v = y - 1; v <= y + 1; ++v)
        for (std::uint32_t u = x - 1; u <= x + 1; ++u) opaque += d[4 * (std::size_t(v) * kSize + u) + 3] == 255;
      return opaque == 9 ? 1 : opaque == 0 ? 0 : -1;
    };
    std::size_t compared = 0, off = 0, overlap = 0;
    for (std::uint32_t y = 1; y + 1 < kSize; ++y)
      for (std::uint32_t x = 1; x + 1 < kSize; ++x) {
        const int b = inside(body, x, y), a = inside(limb, x, y);
        const bool in_arm = a == 1, in_body = b == 1;
        if (!(in_arm || (a == 0 && in_body))) continue;  // the arm's edge, or no part
        overlap += in_body && in_arm;
        const std::size_t at = 4 * (std::size_t(y) * kSize + x);
        const unsigned char* want = in_arm ? &limb[at] : &body[at];
        ++compared;
        int worst = 0;
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(frame[at + c]) - int(want[c])));
        off += worst > 2;
      }
    CHECK(compared > 3000);
    if (pose == 0) CHECK(overlap > 500);  // the arm down the body's side, where its drawing must win
    if (double(off) / double(compared) >= 0.002) {
      std::string problem;
      WritePng(std::string(POSEMORPH_FRAME_OUTPUT) + "/layered-arm-pose" + std::to_string(pose) + ".png", frame.data(),
               kSize, kSize, &problem);
    }
    CHECK(double(off) / double(compared) < 0.002);
  }
  // Along the path: a golden of the blend between 'rest' and 'mid'.
  Scene mid;
  mid.path = "raise";
  mid.time = 0.5;
  CompareWithGolden("layered-arm-raise", RenderRig(rig, arm->drawings, mid, &pixels));
}

TEST_CASE("frames: a layered character's arm passes behind the body with its per-pose order, and parts hide") {
  const auto front = MakeLayeredArm(1), behind = MakeLayeredArm(nlohmann::json::array({-1, -1, 1}));
  const Camera pixels = ArmPixels();
  Scene rest;
  rest.sigma = 1;
  const auto in_front = RenderRig(front->rig, front->drawings, rest, &pixels);
  const auto in_back = RenderRig(behind->rig, behind->drawings, rest, &pixels);
  // Behind the body at rest: the shoulder's overlap shows the body instead.
  const std::size_t arm_front = CountColour(in_front, kArmColour), arm_back = CountColour(in_back, kArmColour);
  const std::size_t body_front = CountColour(in_front, kBodyColour), body_back = CountColour(in_back, kBodyColour);
  CHECK(arm_front > 1500);  // 40 x 10 units at 2.2 px each: 1,936 pixels
  CHECK(arm_front - arm_back > 100);
  CHECK(body_back - body_front == arm_front - arm_back);
  // In 'up' both orders put the arm in front: the same frame, bit for bit.
  Scene up;
  up.x = 2, up.sigma = 1;
  CHECK(RenderRig(front->rig, front->drawings, up, &pixels) == RenderRig(behind->rig, behind->drawings, up, &pixels));
  // Hidden parts are not drawn; the other part is drawn whole.
  Scene no_body = rest, no_arm = rest;
  no_body.hidden_parts = 1, no_arm.hidden_parts = 2;
  const auto arm_only = RenderRig(front->rig, front->drawings, no_body, &pixels);
  const auto body_only = RenderRig(front->rig, front->drawings, no_arm, &pixels);
  CHECK(CountColour(arm_only, kBodyColour) == 0);
  CHECK(CountColour(arm_only, kArmColour) == arm_front);
  CHECK(CountColour(body_only, kArmColour) == 0);
  CHECK(CountColour(body_only, kBodyColour) == body_back);
  // A crowd of layered characters on the path: each drawn whole, parts in
  // order (the validation layer watches the per-character draws).
  Scene crowd;
  crowd.path = "raise", crowd.crowd = 6, crowd.seed = 3;
  const auto many = RenderRig(behind->rig, behind->drawings, crowd);
  CHECK(CountColour(many, kArmColour) > 0);
  CHECK(CountColour(many, kBodyColour) > CountColour(many, kArmColour));
}

TEST_CASE("frames: a character's tint and opacity and a part's opacity multiply what it draws") {
  const auto arm = MakeLayeredArm(1);
  const Camera pixels = ArmPixels();
  Scene rest;
  rest.sigma = 1;
  const auto plain = RenderRig(arm->rig, arm->drawings, rest, &pixels);
  Scene no_arm = rest;
  no_arm.hidden_parts = 2;
  const auto body_only = RenderRig(arm->rig, arm->drawings, no_arm, &pixels);
  // Opacity 1 everywhere is the plain frame, bit for bit; a part at
  // opacity 0 is that part hidden, bit for bit.
  Scene same = rest, arm_clear = rest;
  same.colour = {1, 1, 1, 1}, same.part_opacities = {1, 1};
  arm_clear.part_opacities = {1, 0};
  CHECK(RenderRig(arm->rig, arm->drawings, same, &pixels) == plain);
  CHECK(RenderRig(arm->rig, arm->drawings, arm_clear, &pixels) == body_only);
  // A tint multiplies each covered pixel's colour and leaves the background.
  Scene tinted = rest;
  tinted.colour = {0.5f, 1, 0.25f, 1};
  const auto tint = RenderRig(arm->rig, arm->drawings, tinted, &pixels);
  const float factor[3] = {0.5f, 1, 0.25f};
  std::size_t covered = 0, off = 0, background = 0;
  for (std::size_t p = 0; p < plain.size(); p += 4) {
    const bool is_background = std::abs(plain[p] - 0.93f * 255) < 1.5f && std::abs(plain[p + 2] - 0.95f * 255) < 1.5f;
    const bool opaque_part = CountColour({plain.begin() + long(p), plain.begin() + long(p) + 4}, kArmColour) +
                                 CountColour({plain.begin() + long(p), plain.begin() + long(p) + 4}, kBodyColour) >
                             0;
    if (is_background) background += std::equal(&plain[p], &plain[p] + 4, &tint[p]);
    if (!opaque_part) continue;
    ++covered;
    for (int c = 0; c < 3; ++c) off += std::abs(tint[p + c] - plain[p + c] * factor[c]) > 1.01f;
  }
  CHECK(covered > 3000);
  CHECK(off == 0);
  CHECK(background > 30000);
  // Half opacity: where only the body covers, half body and half background.
  Scene half = no_arm;
  half.colour.a = 0.5f;
  const auto faded = RenderRig(arm->rig, arm->drawings, half, &pixels);
  std::size_t body = 0, wrong = 0;
  for (std::size_t p = 0; p < body_only.size(); p += 4) {
    if (CountColour({body_only.begin() + long(p), body_only.begin() + long(p) + 4}, kBodyColour) == 0) continue;
    ++body;
    for (int c = 0; c < 3; ++c)
      wrong += std::abs(faded[p + c] - (0.5f * body_only[p + c] + 0.5f * kBackground[c] * 255)) > 1.01f;
  }
  CHECK(body > 1500);
  CHECK(wrong == 0);
}

namespace {

// Pell (assets/pell/, the layered sample): seven parts drawn on one canvas
// per pose, rasterised part by part by the build.
using Pell = DrawnSample;

Pell& SharedPell() {
  static std::unique_ptr<Pell> p;
  if (!p) p = std::make_unique<Pell>("pell");
  return *p;
}

}  // namespace

TEST_CASE("frames: Pell, the layered sample, shows at each base pose its parts' drawings in that pose's order") {
  Pell& pell = SharedPell();
  const Rig& rig = pell.rig;
  REQUIRE(rig.part_count() == 7);
  REQUIRE(rig.draw_order_changes());  // the right arm crosses in front of the body in 'cross'
  const std::uint32_t N = rig.pose_count();
  Camera pixels;  // output pixel (x, y) is drawing pixel (x, y): rig coordinates are pixels, y up
  pixels.centre = {kSize / 2.0, -(kSize / 2.0)};
  pixels.zoom = 1;
  for (std::uint32_t pose = 0; pose < N; ++pose) {
    CAPTURE(pose);
    Scene s;
    s.x = rig.pose_points().data[2 * pose], s.y = rig.pose_points().data[2 * pose + 1];
    s.sigma = 1;
    const auto frame = RenderRig(rig, pell.drawings, s, &pixels);
    // The expected colour: the front-most part whose drawing is opaque at
    // the pixel, where no part's drawing has an edge within a pixel.
    const Span<const std::uint32_t> sequence = rig.draw_sequence(pose);
    std::size_t compared = 0, off = 0;
    for (std::uint32_t y = 1; y + 1 < kSize; ++y)
      for (std::uint32_t x = 1; x + 1 < kSize; ++x) {
        const unsigned char* want = nullptr;
        bool edge = false;
        for (std::size_t k = 0; k < sequence.size && !edge; ++k) {
          const std::vector<unsigned char>& d = pell.drawings.rgba[std::size_t(sequence[k]) * N + pose];
          int opaque = 0;
          for (std::uint32_t v = y - 1; v <= y + 1; ++v)
            for (std::uint32_t u = x - 1; u <= x + 1; ++u) opaque += d[4 * (std::size_t(v) * kSize + u) + 3] == 255;
          edge = opaque != 0 && opaque != 9;
          if (opaque == 9) want = &d[4 * (std::size_t(y) * kSize + x)];
        }
        if (edge || !want) continue;
        ++compared;
        const std::size_t at = 4 * (std::size_t(y) * kSize + x);
        int worst = 0;
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(frame[at + c]) - int(want[c])));
        off += worst > 2;
      }
    CHECK(compared > 10000);
    CHECK(double(off) / double(compared) < 0.002);
  }
}

TEST_CASE("frames: Pell along its path, the arm crossing in front of the body") {
  Pell& pell = SharedPell();
  Scene s;
  s.path = "greet";
  s.time = 2.2;
  CompareWithGolden("pell-greet-cross", RenderRig(pell.rig, pell.drawings, s));
  s.time = 0.6;
  CompareWithGolden("pell-greet-wave", RenderRig(pell.rig, pell.drawings, s));
}

// Pell with a face channel (assets/pell/pell-face.json): the eyes and the
// mouth are attachments driven by "face".
DrawnSample& SharedPellFace() {
  static std::unique_ptr<DrawnSample> p;
  if (!p) p = std::make_unique<DrawnSample>("pell-face", "pell");
  return *p;
}

TEST_CASE("frames: Pell's face channel shows each expression's drawings over the rest body's, in draw order") {
  DrawnSample& pell = SharedPellFace();
  const Rig& rig = pell.rig;
  REQUIRE(rig.channel_count() == 2);
  REQUIRE(rig.attachment_count() == 3);
  REQUIRE(pell.drawings.attachments.size() == 3);
  const Rig& face = *rig.channel_rig(1);
  const std::uint32_t N = rig.pose_count();
  Camera pixels;
  pixels.centre = {kSize / 2.0, -(kSize / 2.0)};
  pixels.zoom = 1;
  for (std::uint32_t expression = 0; expression < face.pose_count(); ++expression) {
    CAPTURE(expression);
    Scene s;
    s.sigma = 1;
    s.channels = {ChannelInput{face.pose_points()[2 * expression], face.pose_points()[2 * expression + 1], ""}};
    const auto frame = RenderRig(rig, pell.drawings, s, &pixels);
    // Back to front: the body's parts in the rest pose's order, then the
    // face's (draw order 3, above the head's 2), each its expression's drawing.
    std::vector<const std::vector<unsigned char>*> layers;
    const Span<const std::uint32_t> sequence = rig.draw_sequence(0);
    for (std::size_t k = 0; k < sequence.size; ++k) layers.push_back(&pell.drawings.rgba[std::size_t(sequence[k]) * N]);
    for (const Drawings& a : pell.drawings.attachments) layers.push_back(&a.rgba[expression]);
    std::size_t compared = 0, off = 0, on_face = 0;
    for (std::uint32_t y = 1; y + 1 < kSize; ++y)
      for (std::uint32_t x = 1; x + 1 < kSize; ++x) {
        const unsigned char* want = nullptr;
        bool edge = false, face_pixel = false;
        for (std::size_t k = 0; k < layers.size() && !edge; ++k) {
          int opaque = 0;
          for (std::uint32_t v = y - 1; v <= y + 1; ++v)
            for (std::uint32_t u = x - 1; u <= x + 1; ++u)
              opaque += (*layers[k])[4 * (std::size_t(v) * kSize + u) + 3] == 255;
          edge = opaque != 0 && opaque != 9;
          if (opaque == 9) want = &(*layers[k])[4 * (std::size_t(y) * kSize + x)], face_pixel = k >= sequence.size;
        }
        if (edge || !want) continue;
        ++compared;
        on_face += face_pixel;
        const std::size_t at = 4 * (std::size_t(y) * kSize + x);
        int worst = 0;
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(frame[at + c]) - int(want[c])));
        off += worst > 2;
      }
    MESSAGE(compared << " interior pixels, " << on_face << " of them the face's; " << off << " off");
    CHECK(compared > 10000);
    CHECK(on_face > 50);  // the sleepy eyes are thin
    CHECK(double(off) / double(compared) < 0.002);
  }
}

TEST_CASE("frames: Pell with a face, both channels on their paths, alone and in a crowd") {
  DrawnSample& pell = SharedPellFace();
  Scene s;
  s.path = "greet";
  s.time = 0.6;
  s.channels = {ChannelInput{0, 0, "chatter"}};
  CompareWithGolden("pell-face-greet-chatter", RenderRig(pell.rig, pell.drawings, s));
  s.crowd = 6;
  s.time = 1.3;
  CompareWithGolden("pell-face-crowd", RenderRig(pell.rig, pell.drawings, s));
  // The face hidden: the head shows where the face was.
  Scene hidden;
  hidden.hidden_parts = std::uint64_t(7) << pell.rig.part_count();
  Scene shown;
  const auto with = RenderRig(pell.rig, pell.drawings, shown), without = RenderRig(pell.rig, pell.drawings, hidden);
  std::size_t changed = 0;
  for (std::size_t k = 0; k < with.size(); k += 4) changed += with[k] != without[k];
  MESSAGE(changed << " pixels change when the face's three parts hide");
  CHECK(changed > 200);
}

TEST_CASE("frames: Pell with a face driven by its state machine: the start is the rest frame, colours by state") {
  DrawnSample& pell = SharedPellFace();
  const Rig& rig = pell.rig;
  auto driven = [&](const std::string& timeline, int frames) {
    std::vector<InputCommand> commands;
    std::string problem;
    REQUIRE_MESSAGE(ParseInputTimeline(rig, timeline, &commands, &problem), problem);
    MachineDriver driver;
    REQUIRE_MESSAGE(driver.Init(rig, 1, &problem), problem);
    for (int f = 0; f < frames; ++f) REQUIRE(driver.Advance(f == 0 ? 0 : 1.0 / 30, commands));
    Scene s;
    s.machine = &driver;
    return RenderRig(rig, pell.drawings, s);
  };
  // The first step enters idle and calm: the frame at the channels' first
  // poses, as a point-driven scene draws it.
  Scene rest;
  rest.x = rig.pose_points()[0], rest.y = rig.pose_points()[1];
  const auto plain = RenderRig(rig, pell.drawings, rest), start = driven("", 1);
  const Difference d = Compare(start, plain);
  CAPTURE(d.differing);
  CHECK(d.differing == 0);
  // Vanished (opacity 0 after its 1 s mix): nothing but the background.
  const auto gone = driven("0:vanish", 40);
  std::size_t drawn = 0;
  for (std::size_t k = 0; k < gone.size(); k += 4) drawn += !std::equal(&gone[k], &gone[k] + 4, &plain[0]);
  CHECK(drawn == 0);
  // The ghost: the same motion (breath and spring run in both), its colour
  // and the translucent body change what covers the character, nothing else.
  const auto idle = driven("0:talking", 40), ghost = driven("0:talking;0:ghost", 40);
  std::size_t changed = 0, background_changed = 0;
  for (std::size_t k = 0; k < idle.size(); k += 4) {
    const bool same = std::equal(&idle[k], &idle[k] + 4, &ghost[k]);
    changed += !same;
    background_changed += !same && std::equal(&idle[k], &idle[k] + 4, &plain[0]);
  }
  MESSAGE(changed << " pixels change when Pell turns into a ghost");
  CHECK(changed > 2000);
  CHECK(background_changed == 0);
}

TEST_CASE("camera: fit, zoom about the cursor, pan, pixel-exact") {
  const View rect{-10, 20, 30, 60};  // 40 x 40
  Camera c = FitCamera(rect, 200, 100);
  CHECK(c.zoom == 2.5);  // the smaller of 200/40 and 100/40
  CHECK(c.centre.x == 10);
  CHECK(c.centre.y == 40);
  const glm::dvec2 corner = ToScreen(c, {rect.x0, rect.y1}, 200, 100);  // top-left of the rectangle
  CHECK(corner.x == doctest::Approx(50));
  CHECK(corner.y == doctest::Approx(0));
  // The world point under the cursor stays under it.
  const glm::dvec2 cursor(37, 81);
  const glm::dvec2 before = ToWorld(c, cursor, 200, 100);
  const Camera z = ZoomAbout(c, cursor, 1.7, 200, 100);
  CHECK(z.zoom == doctest::Approx(4.25));
  const glm::dvec2 after = ToWorld(z, cursor, 200, 100);
  CHECK(after.x == doctest::Approx(before.x));
  CHECK(after.y == doctest::Approx(before.y));
  CHECK(ZoomAbout(c, cursor, 1e9, 200, 100).zoom == Camera::kMaxZoom);
  // A drag moves the world with the cursor.
  const Camera p = Pan(c, {10, -4});
  const glm::dvec2 moved = ToScreen(p, before, 200, 100);
  CHECK(moved.x == doctest::Approx(cursor.x + 10));
  CHECK(moved.y == doctest::Approx(cursor.y - 4));
  // Pixel-exact: whole zoom, and whole world coordinates land on whole screen pixels.
  for (std::uint32_t w : {200u, 201u}) {
    Camera e = c;
    e.centre = {10.37, 40.81};
    e.zoom = 2.6;
    e = PixelExact(e, w, 101);
    CHECK(e.zoom == 3);
    const glm::dvec2 q = ToScreen(e, {7, -5}, w, 101);
    CHECK(q.x == doctest::Approx(std::round(q.x)).epsilon(1e-12));
    CHECK(q.y == doctest::Approx(std::round(q.y)).epsilon(1e-12));
    CHECK(std::fabs(e.centre.x - 10.37) <= 0.5 / 3 + 1e-12);  // moved by at most half a pixel
  }
}

// Rig files are hostile input to the viewer too: image references must stay
// inside the images folder, and drawings may not make the texture huge.
TEST_CASE("drawings: image references stay inside the images folder, and sizes are bounded") {
  for (const char* bad : {"../../etc/passwd", "/etc/passwd", "a/../../b.png", "..", "a\\..\\b.png", "a\x1b[31m.png", "",
                          "c:/x.png", "x/..", "https://example.com/a.png"})
    CHECK_FALSE(ImageReferenceStaysInside(bad));
  for (const char* good : {"rest.png", "poses/rest.png", "a..b.png", "..a.png", "./rest.png"})
    CHECK(ImageReferenceStaysInside(good));

  auto rig_with_images = [](const std::string& first, const std::string& second) {
    bake::RigDescription d = bake::ParseRigDescription(R"({"posemorph": 1, "triangles": [[0, 1, 2]], "poses": [
      {"name": "a", "point": [0, 0], "vertices": [[0, 0], [1, 0], [0, 1]], "uvs": [[0, 1], [1, 1], [0, 0]], "image": ")" +
                                                           first + R"("},
      {"name": "b", "point": [1, 0], "vertices": [[0, 0], [1, 0], [0, 1.5]], "uvs": [[0, 1], [1, 1], [0, 0]], "image": ")" +
                                                           second + R"("}]})",
                                                       "in-memory", ".");
    d.parameters.compact = false;
    const std::vector<unsigned char> bytes = bake::BakeRig(d);
    Rig rig;
    REQUIRE(LoadRig(bytes.data(), bytes.size(), &rig, nullptr));
    return rig;
  };
  const std::string dir = std::string(POSEMORPH_FRAME_OUTPUT) + "/drawing-limits";
  std::filesystem::create_directories(dir);
  Drawings drawings;
  std::string problem;
  CHECK_FALSE(LoadDrawings(rig_with_images("../../etc/passwd", "b.png"), dir, &drawings, &problem));
  CHECK(problem ==
        "pose 0: image reference '../../etc/passwd' leaves the images folder (absolute, '..', or a control character); "
        "refusing to open it");
  // 8192 x 1 and 1 x 8192: two small PNGs that would share an 8192 x 8192 texture.
  std::vector<unsigned char> line(8192 * 4, 255);
  REQUIRE(WritePng(dir + "/wide.png", line.data(), 8192, 1, &problem));
  REQUIRE(WritePng(dir + "/tall.png", line.data(), 1, 8192, &problem));
  CHECK_FALSE(LoadDrawings(rig_with_images("wide.png", "tall.png"), dir, &drawings, &problem));
  CHECK(problem ==
        "the drawings (8192 wide, 8192 high at most) would share a texture of more than 16777216 pixels; draw the "
        "poses on canvases of one size");
  CHECK_FALSE(LoadDrawings(rig_with_images("missing.png", "tall.png"), dir, &drawings, &problem));
  CHECK(problem == dir + "/missing.png: cannot open file");
  CHECK_FALSE(LoadDrawings(rig_with_images("..", "tall.png"), dir, &drawings, &problem));
}

TEST_CASE("a failed Vulkan call becomes a message naming the call and the cause") {
  CHECK_NOTHROW(VkCheck(VK_SUCCESS, "vkCreateBuffer"));
  CHECK_THROWS_WITH_AS(VkCheck(VK_ERROR_OUT_OF_DEVICE_MEMORY, "vkAllocateMemory"),
                       "Vulkan vkAllocateMemory: out of GPU memory (VkResult -2)", GpuError);
  CHECK_THROWS_WITH_AS(VkCheck(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateBuffer"),
                       "Vulkan vkCreateBuffer: out of host memory (VkResult -1)", GpuError);
}
