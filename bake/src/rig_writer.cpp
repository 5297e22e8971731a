// SPDX-License-Identifier: MIT
#include "rig_writer.h"

#include "posemorph/rig_format.h"

namespace posemorph::bake {
namespace {

void Put(std::vector<unsigned char>& out, std::size_t at, const void* value, std::size_t size) {
  std::memcpy(out.data() + at, value, size);
}

}  // namespace

void AppendString(std::vector<unsigned char>& out, const std::string& s) {
  const std::uint32_t len = std::uint32_t(s.size());
  const auto* p = reinterpret_cast<const unsigned char*>(&len);
  out.insert(out.end(), p, p + 4);
  out.insert(out.end(), s.begin(), s.end());
}

std::vector<unsigned char> RigWriter::Finish() const {
  namespace fmt = format;
  auto align = [](std::uint64_t v) {
    return (v + fmt::kSectionAlignment - 1) / fmt::kSectionAlignment * fmt::kSectionAlignment;
  };
  std::uint64_t at = align(fmt::kHeaderSize + sections_.size() * fmt::kSectionEntrySize);
  std::vector<std::uint64_t> offsets;
  for (const Section& s : sections_) {
    offsets.push_back(at);
    at = align(at + s.bytes.size());
  }
  std::vector<unsigned char> out(at, 0);
  std::memcpy(out.data(), fmt::kMagic, sizeof(fmt::kMagic));
  Put(out, fmt::kOffVersionMajor, &fmt::kVersionMajor, 2);
  Put(out, fmt::kOffVersionMinor, &fmt::kVersionMinor, 2);
  Put(out, fmt::kOffHeaderSize, &fmt::kHeaderSize, 4);
  const std::uint64_t file_size = out.size();
  Put(out, fmt::kOffFileSize, &file_size, 8);
  const std::uint32_t count = std::uint32_t(sections_.size());
  Put(out, fmt::kOffSectionCount, &count, 4);
  for (std::size_t i = 0; i < sections_.size(); ++i) {
    const std::size_t e = fmt::kHeaderSize + i * fmt::kSectionEntrySize;
    const std::uint64_t size = sections_[i].bytes.size();
    Put(out, e, &sections_[i].tag, 4);
    Put(out, e + 8, &offsets[i], 8);
    Put(out, e + 16, &size, 8);
    if (size) std::memcpy(out.data() + offsets[i], sections_[i].bytes.data(), size);
  }
  const std::uint32_t crc = fmt::Crc32(out.data() + fmt::kHeaderSize, out.size() - fmt::kHeaderSize);
  Put(out, fmt::kOffChecksum, &crc, 4);
  return out;
}

}  // namespace posemorph::bake
