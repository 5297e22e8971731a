// SPDX-License-Identifier: MIT
// The header and the section table: in bounds, aligned, after the table,
// no two overlapping; the checksum.
#include "loader.h"

#include <cstddef>
#include <cstring>
#include <iterator>

namespace posemorph {

using namespace detail::load;  // NOLINT(google-build-using-namespace): the loader's own types

bool RigLoader::ReadHeader(const unsigned char* bytes, std::size_t size, const LoadOptions& options, Header* h,
                           Error* err) {
  if (size < fmt::kHeaderSize)
    return Fail(err, ErrorCode::kTruncated, "%zu bytes is shorter than the %u-byte header", size, fmt::kHeaderSize);
  const fmt::FileHeader header = fmt::DecodeRecord<fmt::FileHeader>(bytes);
  if (std::memcmp(header.magic, fmt::kMagic, sizeof(fmt::kMagic)) != 0)
    return Fail(err, ErrorCode::kBadMagic, "not a posemorph rig (bad magic)");
  h->major = header.version_major;
  h->minor = header.version_minor;
  if (h->major != fmt::kVersionMajor)
    return Fail(err, ErrorCode::kBadVersion, "format version %u.%u; this runtime reads %u.x", h->major, h->minor,
                fmt::kVersionMajor);
  if (header.header_size != fmt::kHeaderSize)
    return Fail(err, ErrorCode::kBadLayout, "header size field is %u, expected %u", header.header_size,
                fmt::kHeaderSize);
  h->file_size = header.file_size;
  if (h->file_size > size)
    return Fail(err, ErrorCode::kTruncated, "header says %llu bytes, only %zu given", (unsigned long long)h->file_size,
                size);
  if (h->file_size < size)
    return Fail(err, ErrorCode::kBadLayout, "header says %llu bytes, %zu given (trailing bytes)",
                (unsigned long long)h->file_size, size);
  if (header.flags != 0) return Fail(err, ErrorCode::kBadVersion, "unknown header flags 0x%x", header.flags);
  for (std::uint32_t i = 0; i < std::size(header.reserved); ++i)
    if (header.reserved[i] != 0)
      return Fail(err, ErrorCode::kBadLayout, "reserved header bytes %u..%u are not zero",
                  std::uint32_t(offsetof(fmt::FileHeader, reserved)) + 4 * i,
                  std::uint32_t(offsetof(fmt::FileHeader, reserved)) + 4 * i + 3);
  h->section_count = header.section_count;
  h->checksum = header.checksum;
  if (h->section_count == 0 || h->section_count > fmt::kMaxSections)
    return Fail(err, ErrorCode::kBadLayout, "section count %u outside 1..%u", h->section_count, fmt::kMaxSections);
  h->table_end = fmt::kHeaderSize + std::uint64_t(h->section_count) * fmt::kSectionEntrySize;
  if (h->table_end > size) return Fail(err, ErrorCode::kTruncated, "section table runs past the end");
  if (options.verify_checksum) {
    const std::uint32_t stored = header.checksum;
    const std::uint32_t actual = fmt::Crc32(bytes + fmt::kHeaderSize, size - fmt::kHeaderSize);
    if (stored != actual)
      return Fail(err, ErrorCode::kBadChecksum, "checksum mismatch (stored %08x, computed %08x)", stored, actual);
  }
  return true;
}

// In bounds, aligned, after the table, no two overlapping.
bool RigLoader::ReadSectionTable(const unsigned char* bytes, std::size_t size, const Header& h, Parser* parser,
                                 Error* err) {
  for (std::uint32_t i = 0; i < h.section_count; ++i) {
    const auto entry = fmt::DecodeEntry<fmt::SectionEntry>(bytes + fmt::kHeaderSize, i);
    const Section s{entry.tag, entry.offset, entry.size};
    char name[5];
    TagName(s.tag, name);
    if (entry.reserved != 0) return Fail(err, ErrorCode::kBadLayout, "section %s: reserved field set", name);
    if (s.offset < h.table_end || s.offset > size || s.size > size - s.offset)
      return Fail(err, ErrorCode::kBadLayout, "section %s lies outside the file", name);
    if (s.offset % fmt::kSectionAlignment != 0)
      return Fail(err, ErrorCode::kBadLayout, "section %s is misaligned", name);
    for (std::uint32_t j = 0; j < parser->table.count; ++j) {
      const Section& o = parser->table.entries[j];
      if (o.tag == s.tag) return Fail(err, ErrorCode::kBadLayout, "section %s appears twice", name);
      if (s.offset < o.offset + o.size && o.offset < s.offset + s.size)
        return Fail(err, ErrorCode::kBadLayout, "section %s overlaps another", name);
    }
    parser->table.entries[parser->table.count++] = s;
  }
  return true;
}

bool RigLoader::ReadSections(const void* data, std::size_t size, RigSection* out, std::uint32_t capacity,
                             std::uint32_t* count, Error* err) {
  if (err) *err = Error{};
  if (!count) return Fail(err, ErrorCode::kInvalidArgument, "no output count given");
  *count = 0;
  if (!data) return Fail(err, ErrorCode::kInvalidArgument, "no rig bytes given");
  const unsigned char* bytes = static_cast<const unsigned char*>(data);
  Header h;
  if (!ReadHeader(bytes, size, LoadOptions(), &h, err)) return false;
  Parser parser{bytes, size, {}, err};
  if (!ReadSectionTable(bytes, size, h, &parser, err)) return false;
  if (!out || capacity < parser.table.count)
    return Fail(err, ErrorCode::kInvalidArgument, "the file has %u sections, room was given for %u", parser.table.count,
                out ? capacity : 0u);
  for (std::uint32_t i = 0; i < parser.table.count; ++i)
    out[i] = RigSection{parser.table.entries[i].tag, parser.table.entries[i].offset, parser.table.entries[i].size};
  *count = parser.table.count;
  return true;
}

}  // namespace posemorph
