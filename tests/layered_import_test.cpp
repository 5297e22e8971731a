// SPDX-License-Identifier: MIT
// Layered files in (bake/src/import/): OpenRaster and Photoshop files
// written by GIMP and Krita (tests/data/import/, scripts/make-import-
// fixtures.sh) read as their writers drew them: names, offsets, opacity,
// visibility, groups, the notes for what is not supported, the composited
// pixels; the two conventions of a character's files; and hostile bytes:
// every refusal one message naming the file, no crash on any truncation or
// byte changed (the sanitizer builds run these too).
#include <doctest/doctest.h>

#include <zip.h>

#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include "posemorph/bake/error.h"
#include "posemorph/bake/import/layered_character.h"
#include "posemorph/bake/import/layered_image.h"

using namespace posemorph::bake;
using namespace posemorph::bake::import;

namespace {

const std::string kData = std::string(POSEMORPH_SOURCE_DIR) + "/tests/data/import/";

std::vector<unsigned char> Bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in.good());
  return std::vector<unsigned char>(std::istreambuf_iterator<char>(in), {});
}

const Layer* Find(const std::vector<Layer>& layers, const std::string& name) {
  for (const Layer& l : layers)
    if (l.name == name) return &l;
  return nullptr;
}

std::array<int, 4> Pixel(const std::vector<unsigned char>& rgba, int width, int x, int y) {
  const std::size_t i = (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4;
  return {rgba[i], rgba[i + 1], rgba[i + 2], rgba[i + 3]};
}

bool Contains(const std::vector<std::string>& notes, const std::string& text) {
  for (const std::string& n : notes)
    if (n.find(text) != std::string::npos) return true;
  return false;
}

std::string Message(const std::function<void()>& f) {
  try {
    f();
  } catch (const BakeError& e) {
    return e.what();
  }
  return "";
}

// features.psd / features.ora (make-import-fixtures.sh): 64 x 48, top first:
// half (white 8x8 at 50,30, opacity 25%), mul (green 6x6 at 2,40, multiply),
// hidden (black, the whole canvas), g (a group at 50% in GIMP's file) of a
// (red 20x10 at 5,6) over b (blue 10x20 at 15,2), base (grey 4x4 at -2,-2).
void CheckFeatures(const LayeredImage& image, double group_opacity) {
  CHECK(image.width == 64);
  CHECK(image.height == 48);
  REQUIRE(image.layers.size() == 5);
  const char* names[] = {"half", "mul", "hidden", "g", "base"};
  for (int i = 0; i < 5; ++i) CHECK(image.layers[std::size_t(i)].name == names[i]);
  const Layer& half = image.layers[0];
  CHECK(half.opacity == doctest::Approx(64 / 255.0).epsilon(1e-3));
  CHECK((half.x == 50 && half.y == 30 && half.width == 8 && half.height == 8));
  CHECK_FALSE(image.layers[2].visible);
  const Layer& g = image.layers[3];
  CHECK(g.group);
  CHECK(g.opacity == doctest::Approx(group_opacity).epsilon(1e-2));
  REQUIRE(g.children.size() == 2);
  const Layer* a = Find(g.children, "a");
  const Layer* b = Find(g.children, "b");
  REQUIRE(a);
  REQUIRE(b);
  CHECK(&g.children[0] == a);  // a over b
  CHECK((a->x == 5 && a->y == 6 && a->width == 20 && a->height == 10));
  CHECK((b->x == 15 && b->y == 2 && b->width == 10 && b->height == 20));
  const Layer& base = image.layers[4];
  CHECK((base.x == -2 && base.y == -2 && base.width == 4 && base.height == 4));
  CHECK(Contains(image.notes, "layer 'mul'"));
  CHECK(Contains(image.notes, "multiply"));

  const std::vector<unsigned char> c = Composite(image.layers, 64, 48);
  const int group_alpha = int(std::lround(255 * group_opacity));
  CHECK(Pixel(c, 64, 7, 8) == std::array<int, 4>{255, 0, 0, group_alpha});    // a alone
  CHECK(Pixel(c, 64, 20, 10) == std::array<int, 4>{255, 0, 0, group_alpha});  // a over b: a
  CHECK(Pixel(c, 64, 20, 18) == std::array<int, 4>{0, 0, 255, group_alpha});  // b alone
  CHECK(Pixel(c, 64, 0, 0) == std::array<int, 4>{128, 128, 128, 255});        // base, its corner off the canvas
  CHECK(Pixel(c, 64, 2, 2) == std::array<int, 4>{0, 0, 0, 0});                // past base's box
  CHECK(Pixel(c, 64, 3, 41) == std::array<int, 4>{0, 255, 0, 255});           // mul, drawn as normal
  CHECK(Pixel(c, 64, 53, 33) == std::array<int, 4>{255, 255, 255, 64});       // half at 25%
  CHECK(Pixel(c, 64, 40, 2) == std::array<int, 4>{0, 0, 0, 0});               // hidden is not drawn
}

// An OpenRaster file made here with libzip from `stack` and `entries`.
std::vector<unsigned char> MakeOra(const std::string& stack,
                                   const std::vector<std::pair<std::string, std::vector<unsigned char>>>& entries,
                                   const std::string& mimetype = "image/openraster") {
  zip_error_t error;
  zip_error_init(&error);
  zip_source_t* out = zip_source_buffer_create(nullptr, 0, 0, &error);
  REQUIRE(out);
  zip_source_keep(out);
  zip_t* z = zip_open_from_source(out, ZIP_TRUNCATE, &error);
  REQUIRE(z);
  std::vector<std::string> keep{mimetype, stack};
  auto add = [&](const std::string& name, const void* data, std::size_t size) {
    zip_source_t* s = zip_source_buffer(z, data, size, 0);
    REQUIRE(s);
    REQUIRE(zip_file_add(z, name.c_str(), s, ZIP_FL_OVERWRITE) >= 0);
  };
  add("mimetype", keep[0].data(), keep[0].size());
  add("stack.xml", keep[1].data(), keep[1].size());
  for (const auto& e : entries) add(e.first, e.second.data(), e.second.size());
  REQUIRE(zip_close(z) == 0);
  REQUIRE(zip_source_open(out) == 0);
  zip_stat_t st;
  REQUIRE(zip_source_stat(out, &st) == 0);
  std::vector<unsigned char> bytes(st.size);
  REQUIRE(zip_source_read(out, bytes.data(), bytes.size()) == zip_int64_t(st.size));
  zip_source_close(out);
  zip_source_free(out);
  zip_error_fini(&error);
  return bytes;
}

// A layer's PNG: features.ora's first layer.
std::vector<unsigned char> SomePng() {
  const std::vector<unsigned char> ora = Bytes(kData + "features.ora");
  zip_error_t error;
  zip_error_init(&error);
  zip_source_t* s = zip_source_buffer_create(ora.data(), ora.size(), 0, &error);
  zip_t* z = zip_open_from_source(s, ZIP_RDONLY, &error);
  REQUIRE(z);
  zip_stat_t st;
  REQUIRE(zip_stat(z, "data/layer0.png", 0, &st) == 0);
  std::vector<unsigned char> png(st.size);
  zip_file_t* f = zip_fopen(z, "data/layer0.png", 0);
  REQUIRE(zip_fread(f, png.data(), png.size()) == zip_int64_t(st.size));
  zip_fclose(f);
  zip_discard(z);
  zip_error_fini(&error);
  return png;
}

}  // namespace

TEST_CASE("import: GIMP's PSD keeps names, offsets, opacity, visibility and groups") {
  CheckFeatures(ReadPhotoshop(kData + "features.psd"), 0.5);
}

TEST_CASE("import: Krita's OpenRaster keeps names, offsets, opacity, visibility and groups") {
  // Krita 5.1 writes the group's 50% from GIMP's PSD as opacity 1: the file says so.
  CheckFeatures(ReadOpenRaster(kData + "features.ora"), 1.0);
}

TEST_CASE("import: a character from one file per pose (GIMP) and from one file of poses (Krita)") {
  const std::vector<std::string> expected_parts{"mouth",     "eye-right", "eye-left", "head",
                                                "arm-right", "arm-left",  "body"};
  const LayeredCharacter psd = ImportLayeredCharacter(
      {kData + "pell/rest.psd", kData + "pell/wave.psd", kData + "pell/cross.psd", kData + "pell/lean.psd"}, false);
  const LayeredCharacter ora = ImportLayeredCharacter({kData + "pell/pell.ora"}, false);
  for (const LayeredCharacter* c : {&psd, &ora}) {
    CHECK(c->poses == std::vector<std::string>{"rest", "wave", "cross", "lean"});
    CHECK(c->parts == expected_parts);  // GIMP's "mouth #1" is the part "mouth"
    CHECK((c->width == 256 && c->height == 256));
    CHECK(c->drawings.size() == 28);
    CHECK(c->FileName(1, 5) == "wave-arm-left.png");
  }
  CHECK(Contains(psd.notes, "rest.psd: layer 'sketch' is hidden: not imported"));
  CHECK(ora.sources[1 * 7 + 3] == kData + "pell/pell.ora: group 'wave': layer 'head #1'");
  // GIMP wrote the same pixels to both files: the drawings are equal.
  for (std::size_t k = 0; k < 28; ++k) CHECK(psd.drawings[k] == ora.drawings[k]);
  // Flattened: one drawing per pose, every part composited.
  const LayeredCharacter flat = ImportLayeredCharacter({kData + "pell/pell.ora"}, true);
  CHECK(flat.parts.empty());
  CHECK(flat.drawings.size() == 4);
  CHECK(flat.FileName(2, 0) == "cross.png");
}

TEST_CASE("import: files that break a convention are refused naming file and layer") {
  CHECK(Message([] {
          ImportLayeredCharacter({kData + "pell/rest.psd", kData + "features.psd"}, false);
        }) == kData + "features.psd: a canvas of 64 x 48, but " + kData +
                  "pell/rest.psd's is 256 x 256: a character's poses share one canvas");
  // GIMP's and Krita's features files draw the same parts (half, mul, g, base).
  const std::string other = kData + "features.ora";
  CHECK(Message([&] { ImportLayeredCharacter({kData + "features.psd", other}, false); }) == "");
  const std::string m = Message([] {
    ImportLayeredCharacter({kData + "pell/rest.psd", kData + "pell/wave.psd", kData + "pell/pell.ora"}, false);
  });
  CHECK(m.find("pell.ora: a canvas") == std::string::npos);
  CHECK(m.find(kData + "pell/pell.ora: group 'rest' is not a part of pose 'rest'") != std::string::npos);
}

TEST_CASE("import: unsupported Photoshop files get one message naming the file and what to do") {
  const std::vector<unsigned char> psd = Bytes(kData + "features.psd");
  auto patched = [&](std::size_t at, std::vector<unsigned char> value) {
    std::vector<unsigned char> b = psd;
    std::copy(value.begin(), value.end(), b.begin() + std::ptrdiff_t(at));
    return Message([&] { ReadPhotoshopBytes(b, "f.psd"); });
  };
  CHECK(patched(0, {'G', 'I', 'F', '8'}) == "f.psd: not a Photoshop file (it does not begin with 8BPS)");
  CHECK(patched(4, {0, 2}) == "f.psd: a large document (PSB) is not read: save it as PSD");
  CHECK(patched(22, {0, 16}) == "f.psd: 16-bit channels are not supported: save the file with 8 bits per channel");
  CHECK(patched(24, {0, 4}) == "f.psd: colour mode CMYK is not supported: convert the image to RGB (or greyscale)");
  CHECK(patched(14, {0, 0x10, 0, 0}) ==
        "f.psd: a canvas of 64 x 1048576 pixels (1 to 16777216 pixels, 4096 x 4096, are read)");
}

TEST_CASE("import: any truncation or changed byte of a PSD is refused or read, never a crash") {
  const std::vector<unsigned char> psd = Bytes(kData + "features.psd");
  std::size_t refused = 0;
  for (std::size_t n = 0; n < psd.size(); ++n) {
    const std::vector<unsigned char> cut(psd.begin(), psd.begin() + std::ptrdiff_t(n));
    const std::string m = Message([&] { ReadPhotoshopBytes(cut, "cut.psd"); });
    refused += m.rfind("cut.psd: ", 0) == 0;
  }
  // Past the layer and mask section only the merged image is cut, which the
  // import does not read: everything before it is refused.
  CHECK(refused >= psd.size() / 2);
  for (std::size_t at = 0; at < psd.size(); ++at)
    for (unsigned char v : {0x00, 0x7F, 0x80, 0xFF}) {
      std::vector<unsigned char> b = psd;
      b[at] = v;
      try {
        const LayeredImage image = ReadPhotoshopBytes(b, "x.psd");
        Composite(image.layers, image.width, image.height);
      } catch (const BakeError& e) {
        CHECK(std::string(e.what()).rfind("x.psd: ", 0) == 0);
      }
    }
}

TEST_CASE("import: any truncation or changed byte of an OpenRaster file is refused or read, never a crash") {
  const std::vector<unsigned char> ora = Bytes(kData + "features.ora");
  for (std::size_t n = 0; n < ora.size(); n += 7) {
    const std::vector<unsigned char> cut(ora.begin(), ora.begin() + std::ptrdiff_t(n));
    CHECK(Message([&] { ReadOpenRasterBytes(cut, "cut.ora"); }).rfind("cut.ora: ", 0) == 0);
  }
  for (std::size_t at = 0; at < ora.size(); at += 3) {
    std::vector<unsigned char> b = ora;
    b[at] ^= 0x5A;
    try {
      const LayeredImage image = ReadOpenRasterBytes(b, "x.ora");
      Composite(image.layers, image.width, image.height);
    } catch (const BakeError& e) {
      CHECK(std::string(e.what()).rfind("x.ora: ", 0) == 0);
    }
  }
}

TEST_CASE("import: OpenRaster files that break the format or the bounds are refused") {
  const std::vector<unsigned char> png = SomePng();
  const std::string layer = "<layer name=\"l\" src=\"data/l.png\" x=\"1\" y=\"2\"/>";
  auto ora = [&](const std::string& stack, const std::string& mimetype = "image/openraster") {
    return Message([&] { ReadOpenRasterBytes(MakeOra(stack, {{"data/l.png", png}}, mimetype), "t.ora"); });
  };
  CHECK(ora("<image w=\"8\" h=\"8\"><stack>" + layer + "</stack></image>") == "");
  CHECK(ora("<image w=\"8\" h=\"8\"><stack>" + layer + "</stack></image>", "image/png") ==
        "t.ora: not an OpenRaster file (its mimetype entry is not image/openraster)");
  CHECK(ora("<image w=\"5000\" h=\"5000\"><stack/></image>") ==
        "t.ora: stack.xml: a canvas of 5000 x 5000 pixels (1 to 16777216 pixels, 4096 x 4096, are read)");
  CHECK(ora("<image w=\"8\" h=\"8\"><stack><layer name=\"l\" src=\"data/none.png\"/></stack></image>") ==
        "t.ora: the zip container holds no data/none.png");
  CHECK(ora("<image w=\"8\" h=\"8\"><stack><layer name=\"l\" src=\"data/l.jpg\"/></stack></image>") ==
        "t.ora: layer 'l': src data/l.jpg is not a PNG (OpenRaster layers are PNG)");
  CHECK(ora("<image w=\"8\" h=\"8\"><stack><layer name=\"l\" src=\"data/l.png\" opacity=\"2\"/></stack></image>") ==
        "t.ora: layer 'l': opacity 2 is not between 0 and 1");
  CHECK(ora("<image w=\"8\" h=\"8\"><stack>" + layer).rfind("t.ora: stack.xml: ", 0) == 0);
  std::string deep = "<image w=\"8\" h=\"8\"><stack>";
  for (int i = 0; i < 20; ++i) deep += "<stack name=\"s\">";
  for (int i = 0; i < 20; ++i) deep += "</stack>";
  CHECK(ora(deep + "</stack></image>") ==
        "t.ora: layer 's/s/s/s/s/s/s/s/s/s/s/s/s/s/s/s/s': groups nested deeper than 16");
  std::string many = "<image w=\"8\" h=\"8\"><stack>";
  for (int i = 0; i < 1100; ++i) many += "<stack name=\"s\"/>";
  CHECK(ora(many + "</stack></image>") == "t.ora: more than 1024 layers and groups");
  CHECK(Message([] { ReadOpenRasterBytes({'P', 'K', 3, 4}, "z.ora"); }).rfind("z.ora: not an OpenRaster file", 0) == 0);
  // A layer's offset and its pixels: the PNG is drawn at (1, 2).
  const LayeredImage image = ReadOpenRasterBytes(
      MakeOra("<image w=\"8\" h=\"8\"><stack>" + layer + "</stack></image>", {{"data/l.png", png}}), "t.ora");
  REQUIRE(image.layers.size() == 1);
  CHECK((image.layers[0].x == 1 && image.layers[0].y == 2 && image.layers[0].width == 4));
  const std::vector<unsigned char> c = Composite(image.layers, 8, 8);
  CHECK(Pixel(c, 8, 1, 2) == std::array<int, 4>{128, 128, 128, 255});
  CHECK(Pixel(c, 8, 0, 1) == std::array<int, 4>{0, 0, 0, 0});
}
