// SPDX-License-Identifier: MIT
// Texture pages (format 1.12, ATLS): a rig the build baked from drawings
// carries its atlas, every list (the body and each attachment) names the
// same pages, every part's uvs in every pose land inside its region; an
// older rig shows its drawings as pages with identity regions; and a
// hostile ATLS is refused with a message naming the section.
#include <doctest/doctest.h>

#include <cstring>
#include <string>
#include <vector>

#include "posemorph/posemorph.h"
#include "runtime_support.h"

using namespace posemorph;
using namespace posemorph::test;

namespace {

std::string Text(StringView s) { return std::string(s.data, s.size); }

const Rig& ListRig(const Rig& rig, std::uint32_t list) { return list == 0 ? rig : *rig.attachment(list - 1).rig; }

// Where the ATLS section of `bytes` starts (the top-level rig's).
std::size_t AtlasOffset(const std::vector<unsigned char>& bytes, std::size_t* size) {
  RigSection sections[format::kMaxSections];
  std::uint32_t count = 0;
  REQUIRE(ReadRigSections(bytes.data(), bytes.size(), sections, format::kMaxSections, &count));
  for (std::uint32_t k = 0; k < count; ++k)
    if (sections[k].tag == format::kAtlas) {
      *size = std::size_t(sections[k].size);
      return std::size_t(sections[k].offset);
    }
  FAIL("no ATLS section");
  return 0;
}

std::string Refusal(const std::vector<unsigned char>& bytes) {
  Rig rig;
  Error err;
  if (LoadRig(bytes.data(), bytes.size(), &rig, &err)) return "(loaded)";
  return err.message;
}

}  // namespace

TEST_CASE("atlas: Pell with a face carries one page for the body and every attachment, each part samples its region") {
  for (const char* name : {"pell-face", "pell-face.compact"}) {
    CAPTURE(name);
    const Rig rig = LoadTestRig(name);
    REQUIRE(rig.has_atlas());
    REQUIRE(rig.attachment_count() == 3);
    const std::string page = Text(rig.page(0).name);
    CHECK(page == std::string(name) + ".page0.png");
    for (std::uint32_t l = 0; l <= rig.attachment_count(); ++l) {
      CAPTURE(l);
      const Rig& r = ListRig(rig, l);
      REQUIRE(r.has_atlas());
      REQUIRE(r.page_count() == 1);
      const TexturePage p = r.page(0);
      CHECK(Text(p.name) == page);
      CHECK((p.atlas && p.premultiplied));
      CHECK(p.width == rig.page(0).width);
      CHECK(p.height == rig.page(0).height);
      for (std::uint32_t part = 0; part < r.part_count(); ++part)
        for (std::uint32_t pose = 0; pose < r.pose_count(); ++pose) {
          const TextureRegion g = r.part_region(part, pose);
          REQUIRE(g.page == 0);
          CHECK((g.width >= 1 && g.height >= 1 && g.x + g.width <= p.width && g.y + g.height <= p.height));
          // Pixel for pixel: the page's scale is the canvas's over the page's.
          CHECK(double(g.scale_u) * p.width == doctest::Approx(r.pose_canvas(pose).width));
          const PartView pv = r.part(part);
          for (std::uint32_t t = pv.first_triangle; t < pv.first_triangle + pv.triangle_count; ++t)
            for (int k = 0; k < 3; ++k) {
              const float* uv = r.uvs(pose).data + 2 * std::size_t(r.triangles()[3 * std::size_t(t) + k]);
              const double x = (uv[0] * g.scale_u + g.offset_u) * p.width;
              const double y = (uv[1] * g.scale_v + g.offset_v) * p.height;
              REQUIRE((x >= g.x && x <= g.x + g.width && y >= g.y && y <= g.y + g.height));
            }
        }
    }
    // The C API says the same.
    const std::vector<unsigned char> bytes = TestRigBytes(name);
    pm_rig* c = nullptr;
    REQUIRE(pm_rig_load(bytes.data(), bytes.size(), &c, nullptr) == PM_OK);
    CHECK(pm_rig_has_atlas(c) == 1);
    CHECK(pm_character_page_count(c, 3) == 1);
    CHECK(pm_character_page_count(c, 4) == 0);
    char text[64];
    size_t length = 0;
    REQUIRE(pm_character_page_name(c, 2, 0, text, sizeof text, &length) == PM_OK);
    CHECK(std::string(text, length) == page);
    pm_page cp{};
    REQUIRE(pm_character_page(c, 0, 0, &cp) == PM_OK);
    CHECK((cp.width == rig.page(0).width && cp.atlas == 1 && cp.premultiplied == 1));
    pm_region cr{};
    REQUIRE(pm_character_part_region(c, 0, 2, 1, &cr) == PM_OK);
    const TextureRegion g = rig.part_region(2, 1);
    CHECK((cr.x == g.x && cr.y == g.y && cr.scale_u == g.scale_u && cr.offset_v == g.offset_v));
    CHECK(pm_character_part_region(c, 0, rig.part_count(), 0, &cr) == PM_ERROR_INVALID_ARGUMENT);
    CHECK(pm_character_page(c, 1, 1, &cp) == PM_ERROR_INVALID_ARGUMENT);
    pm_rig_free(c);
  }
}

TEST_CASE("atlas: a rig without one shows each part's drawing in each pose as a page of its own") {
  const Rig rig = LoadTestRig("arm");  // baked from meshes with images, no atlas
  CHECK_FALSE(rig.has_atlas());
  const std::uint32_t N = rig.pose_count();
  REQUIRE(rig.page_count() == rig.part_count() * N);
  for (std::uint32_t p = 0; p < rig.part_count(); ++p)
    for (std::uint32_t i = 0; i < N; ++i) {
      const TextureRegion g = rig.part_region(p, i);
      CHECK(g.page == p * N + i);
      CHECK((g.scale_u == 1 && g.offset_u == 0 && g.scale_v == 1 && g.offset_v == 0));
      const TexturePage page = rig.page(g.page);
      CHECK(Text(page.name) == Text(rig.part_image(p, i)));
      CHECK_FALSE(page.atlas);
      CHECK_FALSE(page.premultiplied);
    }
  CHECK(rig.page(rig.page_count()).name.size == 0);
  CHECK(rig.part_region(rig.part_count(), 0).page == 0);
}

TEST_CASE("atlas: a hostile ATLS is refused, naming the section and the problem") {
  const std::vector<unsigned char> bytes = TestRigBytes("pip");
  std::size_t size = 0;
  const std::size_t at = AtlasOffset(bytes, &size);
  const std::size_t pages = at + format::AtlasHeader::kSize;
  const std::size_t regions = pages + format::AtlasPageEntry::kSize;        // Pip: one page
  const std::size_t names = regions + 5 * format::AtlasRegionEntry::kSize;  // five poses
  CHECK(Refusal(bytes) == "(loaded)");
  CHECK(Refusal(WithValue<std::uint32_t>(bytes, at, 0)).find("ATLS: 0 pages, outside 1..64") != std::string::npos);
  CHECK(Refusal(WithValue<std::uint32_t>(bytes, at + 4, 4)).find("ATLS: 4 regions for 1 parts and 5 poses") !=
        std::string::npos);
  CHECK(Refusal(WithValue<std::uint32_t>(bytes, at + 8, 2)).find("ATLS: unknown flags") != std::string::npos);
  CHECK(Refusal(WithValue<std::uint32_t>(bytes, pages, 0)).find("ATLS page 0 is 0x") != std::string::npos);
  CHECK(Refusal(WithValue<std::uint32_t>(bytes, pages, 20000)).find("outside 1..16384") != std::string::npos);
  CHECK(Refusal(WithValue<std::uint16_t>(bytes, regions, 1)).find("ATLS region 0: page 1 of 1") != std::string::npos);
  CHECK(Refusal(WithValue<std::uint16_t>(bytes, regions + 2, 65535)).find("is not inside its") != std::string::npos);
  CHECK(Refusal(WithValue<std::uint16_t>(bytes, regions + 6, 0)).find("ATLS region 0: 0x") != std::string::npos);
  CHECK(Refusal(WithValue<std::int32_t>(bytes, regions + 12, -(1 << 21))).find("beyond +-1048576") !=
        std::string::npos);
  CHECK(Refusal(WithValue<std::uint32_t>(bytes, names, 0)).find("ATLS page 0's name of 0 bytes") != std::string::npos);
  CHECK(Refusal(WithValue<std::uint32_t>(bytes, names, 1000)).find("past the section") != std::string::npos);
  CHECK(Refusal(WithValue<char>(bytes, names + 4, '/')).find("does not name a file beside the rig") !=
        std::string::npos);
  // Every byte of the section changed to every one of a few values: refused
  // or loaded, never a crash, and a load keeps its regions inside their pages.
  for (std::size_t k = at; k < at + size; ++k)
    for (unsigned char v : {0x00, 0x01, 0x7F, 0x80, 0xFF}) {
      Rig rig;
      const std::vector<unsigned char> changed = WithValue<unsigned char>(bytes, k, v);
      if (!LoadRig(changed.data(), changed.size(), &rig, nullptr)) continue;
      for (std::uint32_t i = 0; i < rig.pose_count(); ++i) {
        const TextureRegion g = rig.part_region(0, i);
        const TexturePage p = rig.page(g.page);
        REQUIRE((g.page < rig.page_count() && g.x + g.width <= p.width && g.y + g.height <= p.height));
      }
    }
}
