// SPDX-License-Identifier: MIT
// posemorph-bake sheet --textured: frames rasterised with the drawings.
#include <doctest/doctest.h>

#include <png.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <unistd.h>

#include "cli.h"
#include "posemorph/bake/bake.h"
#include "posemorph/bake/mapping/outline_image.h"
#include "posemorph/bake/texture_atlas.h"
#include "posemorph/rig.h"
#include "textured_sheet.h"

using namespace posemorph;
namespace fs = std::filesystem;

namespace {

// A sample as the build baked it (build/<preset>/rigs/NAME.compact.pmrig:
// `posemorph-bake DRAWINGS/NAME.json`, the default compact encoding), read
// rather than baked again by every test case.
std::string RigPath(const std::string& name) {
  return std::string(POSEMORPH_TEST_RIGS) + "/" + name + ".compact.pmrig";
}

std::vector<unsigned char> BakedRigBytes(const std::string& name) {
  const std::string path = RigPath(name);
  std::ifstream in(path, std::ios::binary);
  REQUIRE_MESSAGE(in, "cannot read " << path << " (the build bakes it: target posemorph-test-rigs)");
  return std::vector<unsigned char>(std::istreambuf_iterator<char>(in), {});
}

// Of the 3 x 3 pixels around (dx, dy) of drawing d (outside: empty), how
// many are opaque and how many empty.
void CountAround(const bake::RgbaImage& d, long dx, long dy, int* opaque, int* empty) {
  for (long ny = dy - 1; ny <= dy + 1; ++ny)
    for (long nx = dx - 1; nx <= dx + 1; ++nx) {
      const bool inside = nx >= 0 && ny >= 0 && nx < long(d.width) && ny < long(d.height);
      const unsigned a = inside ? d.rgba[(std::size_t(ny) * d.width + std::size_t(nx)) * 4 + 3] : 0;
      *opaque += a == 255, *empty += a == 0;
    }
}

struct Pip {
  std::string images = std::string(POSEMORPH_DRAWN_SAMPLES) + "/pip";
  std::vector<unsigned char> bytes = BakedRigBytes("pip");
  Rig rig;
  Pip() { REQUIRE(LoadRig(bytes.data(), bytes.size(), &rig, nullptr)); }
};

}  // namespace

TEST_CASE("sheet --textured: the drawings cut back out of the atlas are the drawings where the rig samples them") {
  Pip pip;
  REQUIRE(pip.rig.has_atlas());
  const std::vector<bake::RgbaImage> cut = bake::ReadPoseDrawings(pip.rig, RigPath("pip"), pip.images);
  REQUIRE(cut.size() == pip.rig.pose_count());
  std::size_t compared = 0;
  for (std::uint32_t i = 0; i < pip.rig.pose_count(); ++i) {
    CAPTURE(i);
    int w = 0, h = 0;
    const std::string drawing = pip.images + "/" + std::string(pip.rig.pose_image(i).data, pip.rig.pose_image(i).size);
    const std::vector<unsigned char> original = bake::mapping::ReadPngRgba(drawing, &w, &h, drawing);
    REQUIRE((std::uint32_t(w) == cut[i].width && std::uint32_t(h) == cut[i].height));
    // Every pixel the part samples: alpha exact, colour within the rounding
    // of premultiplied 8-bit storage (where alpha is at least 32).
    for (std::size_t p = 0; p < original.size(); p += 4) {
      const unsigned a = original[p + 3];
      if (cut[i].rgba[p + 3] != a) {
        CHECK(cut[i].rgba[p + 3] == 0);  // outside the crop: transparent
        continue;
      }
      if (a < 32) continue;
      ++compared;
      for (int c = 0; c < 3; ++c) REQUIRE(std::abs(int(cut[i].rgba[p + c]) - int(original[p + c])) <= 4);
    }
  }
  CHECK(compared > 50000);  // Pip's five drawings: 86,254 pixels of alpha >= 32
}

TEST_CASE("atlas: a part that samples more than a page holds is refused before any drawing is read") {
  Pip pip;
  bake::AtlasSettings settings;
  settings.max_page_size = 64;  // Pip's rest pose samples about 200 x 200 of its drawing
  // The drawings are not where the rig says: reading one would fail with
  // another message, so the page size is what refused it.
  const bake::PackedAtlas atlas = bake::PackAtlas(pip.bytes, "pip.pmrig", "/nonexistent-folder", settings, "pip.json");
  CHECK(atlas.pages.empty());
  CHECK(atlas.rig.empty());
  CHECK(atlas.skipped.find("/nonexistent-folder/rest.png: the part of it the rig samples, at least ") == 0);
  CHECK(atlas.skipped.find(" pixels, does not fit a page of 64 (atlas.max_page_size)") != std::string::npos);
}

TEST_CASE("sheet --textured: each base pose is drawn as its own drawing, the in-betweens cross-fade") {
  Pip pip;
  const std::vector<bake::RgbaImage> drawings = bake::ReadPoseDrawings(pip.rig, RigPath("pip"), pip.images);
  REQUIRE(drawings.size() == pip.rig.pose_count());
  bake::TexturedSheetLayout layout;
  const bake::RgbaImage sheet =
      bake::TexturedSheet(pip.rig, drawings, 3, 2, bake::EvalOptions{}, TextureFilter::kNearest, 160, &layout);
  CHECK(layout.columns == 5);  // wide enough for the 5 base poses
  CHECK(layout.rows == 2);
  CHECK(sheet.width == 5 * 160);
  CHECK(sheet.height == 3 * 160);
  // Base pose i in cell (i, 0): where the drawing is opaque all around, the
  // sheet shows the drawing's own pixel (the rig point under each sheet pixel,
  // mapped to the drawing through the pose's canvas).
  for (std::uint32_t i = 0; i < pip.rig.pose_count(); ++i) {
    CAPTURE(i);
    const bake::RgbaImage& d = drawings[i];
    const DrawingCanvas canvas = pip.rig.pose_canvas(i);
    std::size_t compared = 0, same = 0;
    for (std::uint32_t py = 0; py < 160; ++py)
      for (std::uint32_t px = i * 160; px < (i + 1) * 160; ++px) {
        const double x = (px + 0.5 - (i + 0.5) * 160) / layout.scale + layout.centre_x;
        const double y = -(py + 0.5 - 0.5 * 160) / layout.scale + layout.centre_y;
        const long dx = long(std::floor(x + canvas.pivot_x)), dy = long(std::floor(-y + canvas.pivot_y));
        bool interior = true;
        for (long ny = dy - 1; ny <= dy + 1; ++ny)
          for (long nx = dx - 1; nx <= dx + 1; ++nx)
            interior = interior && nx >= 0 && ny >= 0 && nx < long(d.width) && ny < long(d.height) &&
                       d.rgba[(std::size_t(ny) * d.width + std::size_t(nx)) * 4 + 3] == 255;
        if (!interior) continue;
        ++compared;
        const unsigned char* want = &d.rgba[(std::size_t(dy) * d.width + std::size_t(dx)) * 4];
        const unsigned char* got = &sheet.rgba[(std::size_t(py) * sheet.width + px) * 4];
        int off = 0;
        for (int c = 0; c < 3; ++c) off = std::max(off, std::abs(int(got[c]) - int(want[c])));
        same += off <= 2;
      }
    MESSAGE("pose " << i << ": " << same << " of " << compared << " interior pixels are the drawing's");
    CHECK(compared > 3000);
    CHECK(double(same) >= 0.99 * double(compared));
  }
  // The background shows where no triangle is: the sheet's corner.
  CHECK(sheet.rgba[0] == 237);
  // Linear sampling gives another, smoother sheet of the same size.
  const bake::RgbaImage linear =
      bake::TexturedSheet(pip.rig, drawings, 3, 2, bake::EvalOptions{}, TextureFilter::kLinear, 160);
  CHECK(linear.width == sheet.width);
  CHECK(linear.rgba != sheet.rgba);
}

TEST_CASE("sheet --textured: a layered character's parts are drawn back to front, each with its own drawings") {
  // Pell: seven parts, each drawn on its own per pose; the right arm passes in
  // front of the body in pose 'cross' only (its draw order changes).
  const std::string images = std::string(POSEMORPH_DRAWN_SAMPLES) + "/pell";
  const std::vector<unsigned char> bytes = BakedRigBytes("pell");
  Rig rig;
  REQUIRE(LoadRig(bytes.data(), bytes.size(), &rig, nullptr));
  const std::uint32_t N = rig.pose_count(), M = rig.part_count();
  REQUIRE(M == 7);
  REQUIRE(rig.draw_order_changes());
  const std::vector<bake::RgbaImage> drawings = bake::ReadPoseDrawings(rig, RigPath("pell"), images);
  REQUIRE(drawings.size() == std::size_t(M) * N);
  const std::uint32_t cell = 200;
  bake::TexturedSheetLayout layout;
  const bake::RgbaImage sheet =
      bake::TexturedSheet(rig, drawings, 3, 1, bake::EvalOptions{}, TextureFilter::kNearest, cell, &layout);
  // Base pose i in cell (i, 0) is its parts' drawings laid over each other in
  // that pose's order. Compared where every part's drawing is either opaque
  // or empty all around (no part's anti-aliased edge), and some part opaque:
  // there the sheet shows the front-most opaque part's own pixel. Pixels
  // where two parts overlap prove the order: the other order shows the other part.
  for (std::uint32_t i = 0; i < N; ++i) {
    CAPTURE(i);
    const DrawingCanvas canvas = rig.pose_canvas(i);
    const Span<const std::uint32_t> order = rig.draw_sequence(i);
    std::size_t compared = 0, same = 0, overlapping = 0, overlapping_same = 0;
    for (std::uint32_t py = 0; py < cell; ++py)
      for (std::uint32_t px = i * cell; px < (i + 1) * cell; ++px) {
        const double x = (px + 0.5 - (i + 0.5) * cell) / layout.scale + layout.centre_x;
        const double y = -(py + 0.5 - 0.5 * cell) / layout.scale + layout.centre_y;
        const long dx = long(std::floor(x + canvas.pivot_x)), dy = long(std::floor(-y + canvas.pivot_y));
        const unsigned char* front = nullptr;
        int opaque_parts = 0;
        bool clean = true;
        for (std::uint32_t s = 0; s < order.size && clean; ++s) {
          const bake::RgbaImage& d = drawings[std::size_t(order[s]) * N + i];
          int opaque = 0, empty = 0;
          CountAround(d, dx, dy, &opaque, &empty);
          clean = opaque == 9 || empty == 9;
          if (opaque == 9) front = &d.rgba[(std::size_t(dy) * d.width + std::size_t(dx)) * 4], ++opaque_parts;
        }
        if (!clean || !front) continue;
        const unsigned char* got = &sheet.rgba[(std::size_t(py) * sheet.width + px) * 4];
        int off = 0;
        for (int c = 0; c < 3; ++c) off = std::max(off, std::abs(int(got[c]) - int(front[c])));
        ++compared, same += off <= 2;
        if (opaque_parts > 1) ++overlapping, overlapping_same += off <= 2;
      }
    MESSAGE("pose " << i << ": " << same << " of " << compared << " interior pixels are the front part's, "
                    << overlapping_same << " of " << overlapping << " where parts overlap");
    CHECK(compared > 3000);
    CHECK(double(same) >= 0.99 * double(compared));
    CHECK(overlapping > 100);
    CHECK(double(overlapping_same) >= 0.99 * double(overlapping));
  }
}

TEST_CASE("sheet --textured --channel: Pell's face channel, each expression laid over the rest body's parts") {
  const std::string images = std::string(POSEMORPH_DRAWN_SAMPLES) + "/pell";
  const std::vector<unsigned char> bytes = BakedRigBytes("pell-face");
  Rig rig;
  REQUIRE(LoadRig(bytes.data(), bytes.size(), &rig, nullptr));
  REQUIRE(rig.attachment_count() == 3);
  const std::uint32_t N = rig.pose_count();
  const Rig& face = *rig.channel_rig(1);
  const std::vector<bake::RgbaImage> drawings = bake::ReadPoseDrawings(rig, RigPath("pell-face"), images);
  const auto attached = bake::ReadAttachmentDrawings(rig, RigPath("pell-face"), images);
  REQUIRE(attached.size() == 3);
  const std::uint32_t cell = 200;
  bake::TexturedSheetLayout layout;
  const bake::RgbaImage sheet = bake::TexturedSheet(rig, drawings, 4, 1, bake::EvalOptions{}, TextureFilter::kNearest,
                                                    cell, &layout, 1, attached);
  REQUIRE(layout.columns == face.pose_count());
  // Cell i: the body at rest (its parts in the rest pose's order), then the
  // face's three parts (draw order 3, above the head) in expression i.
  for (std::uint32_t i = 0; i < face.pose_count(); ++i) {
    CAPTURE(i);
    const DrawingCanvas canvas = rig.pose_canvas(0);
    std::vector<const bake::RgbaImage*> layers;
    for (std::uint32_t p : rig.draw_sequence(0)) layers.push_back(&drawings[std::size_t(p) * N]);
    for (const auto& a : attached) layers.push_back(&a[i]);
    std::size_t compared = 0, same = 0, on_face = 0;
    for (std::uint32_t py = 0; py < cell; ++py)
      for (std::uint32_t px = i * cell; px < (i + 1) * cell; ++px) {
        const double x = (px + 0.5 - (i + 0.5) * cell) / layout.scale + layout.centre_x;
        const double y = -(py + 0.5 - 0.5 * cell) / layout.scale + layout.centre_y;
        const long dx = long(std::floor(x + canvas.pivot_x)), dy = long(std::floor(-y + canvas.pivot_y));
        const unsigned char* front = nullptr;
        bool clean = true, face_pixel = false;
        for (std::size_t s = 0; s < layers.size() && clean; ++s) {
          const bake::RgbaImage& d = *layers[s];
          int opaque = 0, empty = 0;
          CountAround(d, dx, dy, &opaque, &empty);
          clean = opaque == 9 || empty == 9;
          if (opaque == 9)
            front = &d.rgba[(std::size_t(dy) * d.width + std::size_t(dx)) * 4], face_pixel = s >= rig.part_count();
        }
        if (!clean || !front) continue;
        const unsigned char* got = &sheet.rgba[(std::size_t(py) * sheet.width + px) * 4];
        int off = 0;
        for (int c = 0; c < 3; ++c) off = std::max(off, std::abs(int(got[c]) - int(front[c])));
        ++compared, same += off <= 2;
        on_face += face_pixel && off <= 2;
      }
    MESSAGE("expression " << i << ": " << same << " of " << compared << " interior pixels are the front layer's, "
                          << on_face << " of them the face's");
    CHECK(compared > 3000);
    CHECK(double(same) >= 0.99 * double(compared));
    CHECK(on_face > 20);
  }
}

TEST_CASE("posemorph-bake sheet --textured writes a PNG, and refuses what it cannot draw") {
  Pip pip;
  const fs::path dir = fs::temp_directory_path() / ("posemorph-sheet-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  // The rig one folder down: the drawing folder it records (../assets/pip,
  // from build/<preset>/rigs/) is then dir/assets/pip, which does not exist.
  fs::create_directories(dir / "rigs");
  const fs::path rig = dir / "rigs" / "pip.pmrig", out = dir / "sheet.png";
  std::ofstream(rig, std::ios::binary)
      .write(reinterpret_cast<const char*>(pip.bytes.data()), std::streamsize(pip.bytes.size()));
  // Its atlas page beside it (named as the bake named it, after the rig it wrote).
  const std::string page(pip.rig.page(0).name.data, pip.rig.page(0).name.size);
  fs::copy_file(fs::path(RigPath("pip")).parent_path() / page, dir / "rigs" / page);
  auto run = [](const std::vector<std::string>& args, std::string* text) {
    std::ostringstream o, e;
    const int status = bake::RunBakeCommand(args, o, e);
    *text = o.str() + e.str();
    return status;
  };
  std::string text;
  CHECK(run({"sheet", rig.string(), "--textured", "--images", pip.images, "--columns", "2", "--rows", "1", "-o",
             out.string()},
            &text) == 0);
  CHECK(text.find("wrote " + out.string() + " (800 x 320: 5 poses, then 2x1 samples, drawings sampled linear)") == 0);
  // The PNG reads back at that size.
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  REQUIRE(png_image_begin_read_from_file(&image, out.string().c_str()));
  CHECK(image.width == 800);
  CHECK(image.height == 320);
  png_image_free(&image);

  CHECK(run({"sheet", rig.string(), "--textured", "-o", (dir / "s.svg").string()}, &text) == 2);
  CHECK(text.find("sheet --textured needs -o OUT.png") != std::string::npos);
  // The atlas page is not beside the rig: it is named.
  fs::remove(dir / "rigs" / page);
  CHECK(run({"sheet", rig.string(), "--textured", "-o", (dir / "t.png").string()}, &text) == 1);
  CHECK(text.find("posemorph-bake: error: " + (dir / "rigs" / page).string() + ": ") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "t.png"));
  fs::remove_all(dir);
}

TEST_CASE("eval --no-weight-limit blends the stretches with raw weights, and --no-shear-limit is its old name") {
  Pip pip;
  const fs::path dir = fs::temp_directory_path() / ("posemorph-limit-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path rig = dir / "pip.pmrig";
  std::ofstream(rig, std::ios::binary)
      .write(reinterpret_cast<const char*>(pip.bytes.data()), std::streamsize(pip.bytes.size()));
  auto eval = [&](const std::string& flag, const std::string& name) {
    std::vector<std::string> args = {"eval", rig.string(), "--at", "2.5,-2", "-o", (dir / name).string()};
    if (!flag.empty()) args.push_back(flag);
    std::ostringstream o, e;
    REQUIRE(bake::RunBakeCommand(args, o, e) == 0);
    std::ifstream in(dir / name, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string limited = eval("", "limited.json"), raw = eval("--no-weight-limit", "raw.json");
  CHECK(!limited.empty());
  CHECK(limited != raw);  // far outside the poses the raw weights extrapolate
  CHECK(eval("--no-shear-limit", "old-name.json") == raw);
  fs::remove_all(dir);
}

TEST_CASE("sheet --textured: the tint multiplies every frame, opacity fades it over the background, parts fade alone") {
  Pip pip;
  const std::vector<bake::RgbaImage> drawings = bake::ReadPoseDrawings(pip.rig, RigPath("pip"), pip.images);
  const auto sheet_of = [&](const bake::SheetColour& colour) {
    return bake::TexturedSheet(pip.rig, drawings, 3, 1, bake::EvalOptions{}, TextureFilter::kNearest, 80, nullptr, 0,
                               {}, colour);
  };
  const bake::RgbaImage plain = sheet_of({});
  bake::SheetColour tint, fade, clear;
  tint.colour = {0.5f, 1, 0.25f, 1};
  fade.colour.a = 0.5f;
  clear.colour.a = 0;
  const bake::RgbaImage tinted = sheet_of(tint), faded = sheet_of(fade), cleared = sheet_of(clear);
  // Opacity 0: the background alone, every pixel.
  std::size_t not_background = 0;
  for (std::size_t p = 0; p < cleared.rgba.size(); p += 4)
    not_background += cleared.rgba[p] != 237 || cleared.rgba[p + 1] != 240 || cleared.rgba[p + 2] != 242;
  CHECK(not_background == 0);
  // Where the plain sheet is exactly the character (its pixel is far from the
  // background and its neighbours' too), the tint multiplies it and half
  // opacity halves its distance from the background.
  const double background[3] = {0.93 * 255, 0.94 * 255, 0.95 * 255}, factor[3] = {0.5, 1, 0.25};
  std::size_t compared = 0, tint_off = 0, fade_off = 0;
  for (std::size_t p = 0; p < plain.rgba.size(); p += 4) {
    if (std::abs(plain.rgba[p] - background[0]) + std::abs(plain.rgba[p + 2] - background[2]) < 60) continue;
    ++compared;
    for (int c = 0; c < 3; ++c) {
      const double v = plain.rgba[p + std::size_t(c)];
      // Only on opaque pixels is the tinted value v x factor exactly; allow the edges' partial alpha 1.5 units.
      tint_off += tinted.rgba[p + std::size_t(c)] > v + 1.01 || tinted.rgba[p + std::size_t(c)] < v * factor[c] - 1.01;
      fade_off += std::abs(faded.rgba[p + std::size_t(c)] - (0.5 * v + 0.5 * background[c])) > 1.01;
    }
  }
  MESSAGE(compared << " character pixels compared");
  CHECK(compared > 5000);
  CHECK(tint_off == 0);
  CHECK(fade_off <= compared / 50);  // anti-aliased edges: the covered share is not 1
  // A part at opacity 0 in a layered character draws as if absent: Pell's
  // sheet without its head equals the sheet where the head is fully clear.
  const std::string images = std::string(POSEMORPH_DRAWN_SAMPLES) + "/pell";
  const std::vector<unsigned char> bytes = BakedRigBytes("pell");
  Rig pell;
  REQUIRE(LoadRig(bytes.data(), bytes.size(), &pell, nullptr));
  const std::vector<bake::RgbaImage> parts = bake::ReadPoseDrawings(pell, RigPath("pell"), images);
  bake::SheetColour all_opaque, one_clear;
  all_opaque.part_opacities.assign(pell.part_count(), 1.0f);
  one_clear.part_opacities.assign(pell.part_count(), 1.0f);
  one_clear.part_opacities[0] = 0;
  const auto pell_sheet = [&](const bake::SheetColour& colour) {
    return bake::TexturedSheet(pell, parts, 3, 1, bake::EvalOptions{}, TextureFilter::kNearest, 80, nullptr, 0, {},
                               colour)
        .rgba;
  };
  const auto opaque = pell_sheet(all_opaque);
  CHECK(opaque == pell_sheet({}));
  const auto without = pell_sheet(one_clear);
  std::size_t changed = 0;
  for (std::size_t p = 0; p < opaque.size(); ++p) changed += opaque[p] != without[p];
  CHECK(changed > 100);  // part 0 shows somewhere, and is gone
}
