// SPDX-License-Identifier: MIT
#include "rig_writer.h"

#include "posemorph/bake/rig_sections.h"
#include "posemorph/rig_format.h"

namespace posemorph::bake {

void AppendString(std::vector<unsigned char>& out, const std::string& s) {
  const std::size_t at = out.size();
  out.resize(at + 4);
  format::FieldEncoder{out.data() + at}(std::uint32_t(s.size()));
  out.insert(out.end(), s.begin(), s.end());
}

namespace {

std::uint64_t Aligned(std::uint64_t v) {
  return (v + format::kSectionAlignment - 1) / format::kSectionAlignment * format::kSectionAlignment;
}

}  // namespace

std::uint64_t RigFileSize(const RigSections& rig) {
  std::uint64_t at = Aligned(format::kHeaderSize + rig.sections.size() * format::kSectionEntrySize);
  for (const RigSections::Section& s : rig.sections) at = Aligned(at + s.bytes.size());
  return at;
}

std::vector<unsigned char> WriteRig(const RigSections& rig) {
  const std::vector<RigSections::Section>& sections = rig.sections;
  namespace fmt = format;
  std::uint64_t at = Aligned(fmt::kHeaderSize + sections.size() * fmt::kSectionEntrySize);
  std::vector<std::uint64_t> offsets;
  for (const RigSections::Section& s : sections) {
    offsets.push_back(at);
    at = Aligned(at + s.bytes.size());
  }
  std::vector<unsigned char> out(at, 0);
  for (std::size_t i = 0; i < sections.size(); ++i) {
    fmt::SectionEntry entry{};
    entry.tag = sections[i].tag;
    entry.offset = offsets[i];
    entry.size = sections[i].bytes.size();
    fmt::EncodeRecord(entry, out.data() + fmt::kHeaderSize + i * fmt::kSectionEntrySize);
    if (entry.size) std::memcpy(out.data() + offsets[i], sections[i].bytes.data(), std::size_t(entry.size));
  }
  fmt::FileHeader header{};
  std::memcpy(header.magic, fmt::kMagic, sizeof(fmt::kMagic));
  header.version_major = fmt::kVersionMajor;
  header.version_minor = fmt::kVersionMinor;
  header.header_size = fmt::kHeaderSize;
  header.file_size = out.size();
  header.section_count = std::uint32_t(sections.size());
  // The checksum covers the table and the sections, written above.
  header.checksum = fmt::Crc32(out.data() + fmt::kHeaderSize, out.size() - fmt::kHeaderSize);
  fmt::EncodeRecord(header, out.data());
  return out;
}

}  // namespace posemorph::bake
