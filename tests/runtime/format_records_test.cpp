// SPDX-License-Identifier: MIT
// The format's records (posemorph/format/records.h): the bytes EncodeRecord
// writes are the layout FORMAT.md gives, DecodeRecord reads them back, the
// bounded reader refuses a record that does not fit, and the records of
// baked rigs decode to what the loaded rig says.
#include <cstring>
#include <vector>

#include "posemorph/format/records.h"
#include "posemorph/rig_format.h"
#include "runtime_support.h"

using namespace posemorph;
using namespace posemorph::test;

namespace {

template <typename R>
std::vector<unsigned char> Encoded(const R& r) {
  std::vector<unsigned char> out(R::kSize, 0xEE);
  format::EncodeRecord(r, out.data());
  return out;
}

// The little-endian bytes of v.
std::vector<unsigned char> Le(std::uint64_t v, int bytes) {
  std::vector<unsigned char> out;
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
  return out;
}

void Splice(std::vector<unsigned char>& into, std::size_t at, const std::vector<unsigned char>& bytes) {
  std::memcpy(into.data() + at, bytes.data(), bytes.size());
}

}  // namespace

TEST_CASE("records encode little-endian at the offsets FORMAT.md gives, and decode back") {
  format::AttachmentEntry a{};
  a.channel = 2;
  a.parent_triangle = 0x01020304;
  a.joint_triangle = 7;
  a.parent_weights[1] = 0.25;
  a.joint_weights[2] = -1.5;
  a.offset = 0x1122334455667788ull;
  a.size = 96;
  std::vector<unsigned char> expected(80, 0);
  Splice(expected, 0, Le(2, 4));
  Splice(expected, 4, Le(0x01020304, 4));
  Splice(expected, 8, Le(7, 4));
  std::uint64_t bits = 0;
  double w = 0.25;
  std::memcpy(&bits, &w, 8);
  Splice(expected, 16 + 8, Le(bits, 8));
  w = -1.5;
  std::memcpy(&bits, &w, 8);
  Splice(expected, 40 + 16, Le(bits, 8));
  Splice(expected, 64, Le(0x1122334455667788ull, 8));
  Splice(expected, 72, Le(96, 8));
  const std::vector<unsigned char> bytes = Encoded(a);
  CHECK(bytes == expected);
  const auto back = format::DecodeRecord<format::AttachmentEntry>(bytes.data());
  CHECK(std::memcmp(&back, &a, sizeof(a)) == 0);

  format::GridPoseCode code{3, 17, 2};
  CHECK(Encoded(code) == std::vector<unsigned char>{3, 17, 2, 0});
  format::TurnsHeader turns{-2, 5};
  CHECK(Encoded(turns) == std::vector<unsigned char>{0xFE, 0xFF, 0xFF, 0xFF, 5, 0, 0, 0});
  format::PartEntry part{10, 20, -3, 0};
  const auto part_back = format::DecodeRecord<format::PartEntry>(Encoded(part).data());
  CHECK(part_back.first_triangle == 10);
  CHECK(part_back.triangle_count == 20);
  CHECK(part_back.draw_order == -3);
}

TEST_CASE("the bounded reader refuses a record that does not lie inside the bytes, and writes nothing") {
  const std::vector<unsigned char> bytes(40, 1);
  format::SectionEntry e{};
  e.tag = 99;
  CHECK(format::ReadRecord(bytes.data(), bytes.size(), 16, &e));  // 16 + 24 = 40: fits exactly
  CHECK(e.tag == 0x01010101u);
  e.tag = 99;
  CHECK_FALSE(format::ReadRecord(bytes.data(), bytes.size(), 17, &e));
  CHECK_FALSE(format::ReadRecord(bytes.data(), bytes.size(), 41, &e));
  CHECK_FALSE(format::ReadRecord(bytes.data(), bytes.size(), ~std::uint64_t(0), &e));  // no wrap-around
  CHECK(e.tag == 99);
}

TEST_CASE("a baked rig's header, table and CHAN records decode to what the loaded rig says") {
  for (const char* name : {"pip", "pip.compact", "pell-face", "pell-face.compact"}) {
    CAPTURE(name);
    const std::vector<unsigned char> bytes = TestRigBytes(name);
    const Rig rig = LoadTestRig(name);
    format::FileHeader h{};
    REQUIRE(format::ReadRecord(bytes.data(), bytes.size(), 0, &h));
    CHECK(std::memcmp(h.magic, format::kMagic, 8) == 0);
    CHECK(h.version_major == rig.format_major());
    CHECK(h.version_minor == rig.format_minor());
    CHECK(h.header_size == format::kHeaderSize);
    CHECK(h.file_size == bytes.size());
    CHECK(h.checksum == rig.checksum());
    CHECK(h.checksum == format::Crc32(bytes.data() + format::kHeaderSize, bytes.size() - format::kHeaderSize));
    // The table: every entry inside the file; META decodes to the rig's counts.
    bool meta_seen = false;
    const format::SectionEntry* chan = nullptr;
    std::vector<format::SectionEntry> table;
    for (std::uint32_t i = 0; i < h.section_count; ++i) {
      format::SectionEntry e{};
      REQUIRE(format::ReadRecord(bytes.data(), bytes.size(), format::kHeaderSize + std::uint64_t(i) * 24, &e));
      CHECK(e.reserved == 0);
      CHECK(e.offset + e.size <= bytes.size());
      table.push_back(e);
    }
    for (const format::SectionEntry& e : table) {
      if (e.tag == format::kChannels) chan = &e;
      if (e.tag != format::kMeta) continue;
      format::Meta meta{};
      REQUIRE(format::ReadRecord(bytes.data() + e.offset, e.size, 0, &meta));
      CHECK(meta.vertex_count == rig.vertex_count());
      CHECK(meta.triangle_count == rig.triangle_count());
      CHECK(meta.pose_count == rig.pose_count());
      CHECK(meta.grid_cells_x == rig.grid().cells_x);
      CHECK(meta.rig_size == rig.bounding_box_diagonal());
      meta_seen = true;
    }
    CHECK(meta_seen);
    CHECK((chan != nullptr) == (rig.attachment_count() > 0));
    if (!chan) continue;
    const unsigned char* c = bytes.data() + chan->offset;
    format::ChannelsHeader ch{};
    REQUIRE(format::ReadRecord(c, chan->size, 0, &ch));
    CHECK(ch.channel_count == rig.channel_count());
    REQUIRE(ch.attachment_count == rig.attachment_count());
    for (std::uint32_t a = 0; a < ch.attachment_count; ++a) {
      format::AttachmentEntry e{};
      REQUIRE(format::ReadRecord(c, chan->size, format::ChannelsHeader::kSize + std::uint64_t(a) * 80, &e));
      const AttachmentView v = rig.attachment(a);
      CHECK(e.channel == v.channel);
      CHECK(e.parent_triangle == v.parent_triangle);
      CHECK(e.joint_triangle == v.joint_triangle);
      for (int k = 0; k < 3; ++k) {
        CHECK(e.parent_weights[k] == v.parent_weights[k]);
        CHECK(e.joint_weights[k] == v.joint_weights[k]);
      }
      // The nested rig is a rig file of its own, with its own header.
      format::FileHeader nested{};
      REQUIRE(format::ReadRecord(c, chan->size, e.offset, &nested));
      CHECK(nested.file_size == e.size);
      CHECK(nested.checksum == v.rig->checksum());
    }
  }
}
