// SPDX-License-Identifier: MIT
// ReadRigSections: the section table as the loader reads it, for tools
// (posemorph-bake info) that show where a rig's bytes go.
#include <algorithm>
#include <cstring>

#include "posemorph/rig_format.h"
#include "runtime_support.h"

using namespace posemorph;
using namespace posemorph::test;

namespace {

std::vector<RigSection> Sections(const std::vector<unsigned char>& bytes) {
  std::vector<RigSection> sections(format::kMaxSections);
  std::uint32_t count = 0;
  Error err;
  REQUIRE_MESSAGE(ReadRigSections(bytes.data(), bytes.size(), sections.data(), format::kMaxSections, &count, &err),
                  err.message);
  sections.resize(count);
  return sections;
}

std::uint32_t Tag(const char (&name)[5]) {
  std::uint32_t tag = 0;
  std::memcpy(&tag, name, 4);
  return tag;
}

}  // namespace

TEST_CASE("the sections of exact and compact rigs: the header's count, inside the file, apart, in table order") {
  for (const char* name : {"small", "small.compact", "pip", "pip.compact"}) {
    CAPTURE(name);
    const std::vector<unsigned char> bytes = TestRigBytes(name);
    const std::vector<RigSection> sections = Sections(bytes);
    std::uint32_t header_count = 0;
    std::memcpy(&header_count, bytes.data() + format::kOffSectionCount, 4);
    REQUIRE(sections.size() == header_count);
    const std::uint64_t table_end = format::kHeaderSize + std::uint64_t(header_count) * format::kSectionEntrySize;
    std::uint64_t total = 0;
    for (std::size_t i = 0; i < sections.size(); ++i) {
      std::uint32_t tag = 0;
      std::memcpy(&tag, bytes.data() + format::kHeaderSize + i * format::kSectionEntrySize, 4);
      CHECK(sections[i].tag == tag);
      CHECK(sections[i].offset >= table_end);
      CHECK(sections[i].offset + sections[i].size <= bytes.size());
      CHECK(sections[i].offset % format::kSectionAlignment == 0);
      if (i > 0) CHECK(sections[i].offset >= sections[i - 1].offset + sections[i - 1].size);
      total += sections[i].size;
    }
    CHECK(total + table_end <= bytes.size());
    CHECK(sections[0].tag == format::kMeta);
    CHECK(sections[0].size == format::kMetaSize);
    const bool compact = std::strstr(name, "compact") != nullptr;
    CHECK(std::any_of(sections.begin(), sections.end(), [&](const RigSection& s) { return s.tag == Tag("QPOS"); }) ==
          compact);
    Rig rig;
    REQUIRE(LoadRig(bytes.data(), bytes.size(), &rig, nullptr));
    CHECK(rig.compact_encoding() == compact);
    const Rig moved = std::move(rig);
    CHECK(moved.compact_encoding() == compact);
  }
}

TEST_CASE("a table the loader refuses is refused with the loader's message, and a short output is refused") {
  std::vector<unsigned char> bytes = TestRigBytes("small");
  std::vector<RigSection> out(format::kMaxSections);
  std::uint32_t count = 99;
  Error err, load_err;
  Rig rig;

  std::vector<unsigned char> truncated(bytes.begin(), bytes.begin() + 40);
  CHECK(!ReadRigSections(truncated.data(), truncated.size(), out.data(), format::kMaxSections, &count, &err));
  CHECK(!LoadRig(truncated.data(), truncated.size(), &rig, &load_err));
  CHECK(err.code == load_err.code);
  CHECK(std::string(err.message) == load_err.message);
  CHECK(count == 0);

  std::vector<unsigned char> overlapping = bytes;  // the second section starts where the first does
  std::memcpy(overlapping.data() + format::kHeaderSize + format::kSectionEntrySize + 8,
              overlapping.data() + format::kHeaderSize + 8, 8);
  const std::uint32_t crc =
      format::Crc32(overlapping.data() + format::kHeaderSize, overlapping.size() - format::kHeaderSize);
  std::memcpy(overlapping.data() + format::kOffChecksum, &crc, 4);
  CHECK(!ReadRigSections(overlapping.data(), overlapping.size(), out.data(), format::kMaxSections, &count, &err));
  CHECK(!LoadRig(overlapping.data(), overlapping.size(), &rig, &load_err));
  CHECK(std::string(err.message) == load_err.message);

  const std::vector<RigSection> sections = Sections(bytes);
  CHECK(!ReadRigSections(bytes.data(), bytes.size(), out.data(), std::uint32_t(sections.size() - 1), &count, &err));
  CHECK(err.code == ErrorCode::kInvalidArgument);
  CHECK(count == 0);
  CHECK(!ReadRigSections(bytes.data(), bytes.size(), nullptr, format::kMaxSections, &count, &err));
  CHECK(err.code == ErrorCode::kInvalidArgument);
  CHECK(!ReadRigSections(nullptr, 0, out.data(), format::kMaxSections, &count, &err));
  CHECK(err.code == ErrorCode::kInvalidArgument);
  CHECK(!ReadRigSections(bytes.data(), bytes.size(), out.data(), format::kMaxSections, nullptr, &err));
  CHECK(err.code == ErrorCode::kInvalidArgument);
}
