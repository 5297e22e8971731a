// SPDX-License-Identifier: MIT
// AddRigSections (texture_atlas.h): a written rig file with sections added,
// in its own rig and in its attachments' (CHAN rebuilt around them).
#include <algorithm>

#include "posemorph/bake/error.h"
#include "posemorph/bake/texture_atlas.h"
#include "posemorph/format/record_codec.h"
#include "posemorph/rig.h"
#include "posemorph/rig_format.h"
#include "rig_writer.h"

namespace posemorph::bake {
namespace {

namespace fmt = format;

RigSections ReadSections(const std::vector<unsigned char>& rig, const std::string& file) {
  RigSection table[fmt::kMaxSections];
  std::uint32_t count = 0;
  Error err;
  if (!ReadRigSections(rig.data(), rig.size(), table, fmt::kMaxSections, &count, &err))
    throw BakeError(file, std::string("internal: the rig written does not read back: ") + err.message);
  RigSections out;
  for (std::uint32_t k = 0; k < count; ++k) {
    const auto* at = rig.data() + table[k].offset;
    out.Add(table[k].tag, std::vector<unsigned char>(at, at + table[k].size));
  }
  return out;
}

void Put(RigSections& sections, const RigSections::Section& added) {
  for (RigSections::Section& s : sections.sections)
    if (s.tag == added.tag) {
      s.bytes = added.bytes;
      return;
    }
  sections.sections.push_back(added);
}

// CHAN with each nested rig given its sections: the header, the entries
// (offsets and sizes anew), the channel names as they were, then the rigs.
std::vector<unsigned char> Channels(const std::vector<unsigned char>& chan,
                                    const std::vector<std::vector<RigSections::Section>>& nested,
                                    const std::string& file) {
  const auto bad = [&] {
    return BakeError(file, "internal: the rig written has a CHAN section this bake cannot read");
  };
  if (chan.size() < fmt::kChannelsHeaderSize) throw bad();
  const auto header = fmt::DecodeRecord<fmt::ChannelsHeader>(chan.data());
  const std::size_t A = header.attachment_count, C = header.channel_count;
  std::size_t at = fmt::kChannelsHeaderSize + A * fmt::kAttachmentEntrySize;
  if (at > chan.size()) throw bad();
  for (std::size_t c = 0; c < C; ++c) {
    if (chan.size() - at < 4) throw bad();
    std::uint32_t n = 0;
    fmt::FieldDecoder{chan.data() + at}(n);
    if (chan.size() - at - 4 < n) throw bad();
    at += 4 + std::size_t(n);
  }
  std::vector<unsigned char> out(chan.begin(), chan.begin() + std::ptrdiff_t(at));
  for (std::size_t a = 0; a < A; ++a) {
    auto entry = fmt::DecodeEntry<fmt::AttachmentEntry>(chan.data() + fmt::kChannelsHeaderSize, a);
    if (entry.offset > chan.size() || entry.size > chan.size() - entry.offset) throw bad();
    const std::vector<unsigned char> old(chan.begin() + std::ptrdiff_t(entry.offset),
                                         chan.begin() + std::ptrdiff_t(entry.offset + entry.size));
    const std::vector<unsigned char> rig = a < nested.size() ? AddRigSections(old, nested[a], {}, file) : old;
    while (out.size() % fmt::kSectionAlignment) out.push_back(0);
    entry.offset = out.size();
    entry.size = rig.size();
    fmt::EncodeRecord(entry, out.data() + fmt::kChannelsHeaderSize + a * fmt::kAttachmentEntrySize);
    out.insert(out.end(), rig.begin(), rig.end());
  }
  return out;
}

}  // namespace

std::vector<unsigned char> AddRigSections(const std::vector<unsigned char>& rig,
                                          const std::vector<RigSections::Section>& top,
                                          const std::vector<std::vector<RigSections::Section>>& nested,
                                          const std::string& file) {
  RigSections sections = ReadSections(rig, file);
  for (const RigSections::Section& s : top) Put(sections, s);
  if (!nested.empty())
    for (RigSections::Section& s : sections.sections)
      if (s.tag == fmt::kChannels) s.bytes = Channels(s.bytes, nested, file);
  return WriteRig(sections);
}

}  // namespace posemorph::bake
