// SPDX-License-Identifier: MIT
// CHAN (format 1.7): the attachments' records and names, read before the
// arena is laid out; their views in it; each nested rig loaded in place.
#include "loader.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <new>

namespace posemorph {

using namespace detail::load;  // NOLINT(google-build-using-namespace): the loader's own types

namespace {

// A nested rig's error, prefixed with the attachment it came from.
bool NestedFail(Error* err, std::uint32_t a) {
  if (err) {
    char prefix[32];
    const int n = std::snprintf(prefix, sizeof(prefix), "attachment %u: ", a);
    const std::size_t p = n > 0 ? std::size_t(n) : 0, room = sizeof(err->message) - 1 - p;
    const std::size_t length = std::strlen(err->message);
    const std::size_t kept = length < room ? length : room;
    std::memmove(err->message + p, err->message, kept);
    std::memcpy(err->message, prefix, p);
    err->message[p + kept] = 0;
  }
  return false;
}

}  // namespace

// CHAN: the table, the names and the nested rigs' places, each nested rig's
// header, table and counts (its arena size); its values when it is loaded.
bool RigLoader::ReadChannels(const unsigned char* bytes, const Parser& parser, const Counts& c,
                             const LoadOptions& options, bool nested, Channels* ch, Error* err) {
  const Section* section = parser.table.Find(fmt::kChannels);
  if (!section) return true;
  if (nested) return Fail(err, ErrorCode::kBadLayout, "an attachment's rig has a CHAN section of its own");
  const unsigned char* p = bytes + section->offset;
  const std::uint64_t size = section->size;
  if (size < fmt::kChannelsHeaderSize)
    return Fail(err, ErrorCode::kBadLayout, "CHAN section of %llu bytes is shorter than its header",
                (unsigned long long)size);
  const fmt::ChannelsHeader header = fmt::DecodeRecord<fmt::ChannelsHeader>(p);  // fits: checked above
  ch->C = header.channel_count;
  ch->A = header.attachment_count;
  if (ch->C < 2 || ch->C > fmt::kMaxChannels)
    return Fail(err, ch->C < 2 ? ErrorCode::kBadValue : ErrorCode::kTooLarge, "channel count %u outside 2..%u", ch->C,
                fmt::kMaxChannels);
  if (ch->A < 1 || ch->A > fmt::kMaxAttachments)
    return Fail(err, ch->A < 1 ? ErrorCode::kBadValue : ErrorCode::kTooLarge, "attachment count %u outside 1..%u",
                ch->A, fmt::kMaxAttachments);
  if (header.reserved[0] != 0 || header.reserved[1] != 0)
    return Fail(err, ErrorCode::kBadLayout, "CHAN's reserved header fields are not zero");
  std::uint64_t at = fmt::kChannelsHeaderSize + std::uint64_t(ch->A) * fmt::kAttachmentEntrySize;
  if (at > size) return Fail(err, ErrorCode::kBadLayout, "CHAN's %u attachment entries run past the section", ch->A);
  for (std::uint32_t k = 0; k < ch->C; ++k) {
    if (at + 4 > size) return Fail(err, ErrorCode::kBadLayout, "CHAN's channel names run past the section");
    std::uint32_t n = 0;
    fmt::FieldDecoder{p + at}(n);
    if (n < 1 || n > fmt::kMaxChannelName)
      return Fail(err, ErrorCode::kBadValue, "channel %u's name is %u bytes, outside 1..%u", k, n,
                  fmt::kMaxChannelName);
    if (at + 4 + n > size) return Fail(err, ErrorCode::kBadLayout, "CHAN's channel names run past the section");
    ch->names[k] = p + at + 4;
    ch->name_sizes[k] = n;
    ch->name_bytes += n;
    for (std::uint32_t j = 0; j < k; ++j)
      if (ch->name_sizes[j] == n && std::memcmp(ch->names[j], ch->names[k], n) == 0)
        return Fail(err, ErrorCode::kBadValue, "channels %u and %u have the same name", j, k);
    at += 4 + n;
  }
  bool driven[fmt::kMaxChannels] = {};
  for (std::uint32_t a = 0; a < ch->A; ++a) {
    Channels::Entry& slot = ch->entries[a];
    slot.record = fmt::DecodeEntry<fmt::AttachmentEntry>(p + fmt::kChannelsHeaderSize, a);  // inside: checked above
    const fmt::AttachmentEntry& entry = slot.record;
    if (entry.reserved != 0) return Fail(err, ErrorCode::kBadLayout, "attachment %u: reserved field is not zero", a);
    const std::uint64_t offset = entry.offset;
    if (entry.channel < 1 || entry.channel >= ch->C)
      return Fail(err, ErrorCode::kBadValue, "attachment %u: channel %u outside 1..%u", a, entry.channel, ch->C - 1);
    driven[entry.channel] = true;
    if (entry.parent_triangle >= c.T)
      return Fail(err, ErrorCode::kBadValue, "attachment %u: parent triangle %u of %llu", a, entry.parent_triangle,
                  (unsigned long long)c.T);
    for (const double* w : {entry.parent_weights, entry.joint_weights}) {
      const double sum = w[0] + w[1] + w[2];
      for (int k = 0; k < 3; ++k)
        if (!(w[k] >= -fmt::kMaxJointWeightOutside && w[k] <= 1 + fmt::kMaxJointWeightOutside))
          return Fail(err, ErrorCode::kBadValue, "attachment %u: a joint weight (%g) is outside [0, 1]", a, w[k]);
      if (!(std::fabs(sum - 1) <= fmt::kMaxJointWeightOutside))
        return Fail(err, ErrorCode::kBadValue, "attachment %u: joint weights sum to %g, not 1", a, sum);
    }
    if (offset % fmt::kSectionAlignment != 0 || offset < at || entry.size > size || offset > size - entry.size)
      return Fail(err, ErrorCode::kBadLayout,
                  "attachment %u: its rig's bytes (%llu at %llu) are not aligned, after the last, inside CHAN", a,
                  (unsigned long long)entry.size, (unsigned long long)offset);
    slot.bytes = p + offset;
    at = offset + entry.size;
    std::size_t needed = 0;
    ArenaSource size_only;
    size_only.kind = ArenaSource::kSizeOnly;
    size_only.needed = &needed;
    size_only.nested = true;
    std::uint64_t vertices = 0, nonzeros = 0;
    size_only.vertices = &vertices, size_only.nonzeros = &nonzeros;
    Rig scratch;
    if (!Load(slot.bytes, std::size_t(entry.size), &scratch, err, options, size_only)) return NestedFail(err, a);
    slot.arena = needed;
    ch->vertices += vertices, ch->nonzeros += nonzeros;
  }
  for (std::uint32_t k = 1; k < ch->C; ++k)
    if (!driven[k]) return Fail(err, ErrorCode::kBadValue, "channel %u drives no attachment", k);
  return true;
}

// The attachments' views, the channel names and offsets, the nested Rig
// objects and each nested rig's arena.
void RigLoader::LayoutChannels(ArenaLayout& arena, const Channels& ch, Rig* rig, Rig** nested, unsigned char** memory) {
  if (ch.A == 0) return;
  AttachmentView* views = arena.Take<AttachmentView>(ch.A);
  StringView* names = arena.Take<StringView>(ch.C);
  std::uint32_t* offsets = arena.Take<std::uint32_t>(ch.C);
  char* chars = arena.Take<char>(ch.name_bytes);
  *nested = arena.Take<Rig>(ch.A);
  static_assert(alignof(Rig) <= kRigMemoryAlignment, "Rig objects live in the arena");
  for (std::uint32_t a = 0; a < ch.A; ++a) memory[a] = arena.Take<unsigned char>(ch.entries[a].arena);
  if (!views) return;  // the sizing pass
  std::size_t used = 0;
  for (std::uint32_t k = 0; k < ch.C; ++k) {
    std::memcpy(chars + used, ch.names[k], ch.name_sizes[k]);
    names[k] = {chars + used, ch.name_sizes[k]};
    used += ch.name_sizes[k];
  }
  for (std::uint32_t a = 0; a < ch.A; ++a) {
    new (*nested + a) Rig();
    AttachmentView& v = views[a];
    v = AttachmentView{};
    v.rig = *nested + a;
    const fmt::AttachmentEntry& entry = ch.entries[a].record;
    v.channel = entry.channel;
    v.parent_triangle = entry.parent_triangle;
    v.joint_triangle = entry.joint_triangle;
    for (int k = 0; k < 3; ++k)
      v.parent_weights[k] = entry.parent_weights[k], v.joint_weights[k] = entry.joint_weights[k];
  }
  rig->attachments_ = {views, ch.A};
  rig->channel_names_ = {names, ch.C};
  rig->channel_offsets_ = {offsets, ch.C};
  rig->channel_count_ = ch.C;
}

// Each nested rig, loaded into its part of the arena; then what the jobs
// need across them: a channel's attachments share its pose count, and the
// joint triangle is in range.
bool RigLoader::LoadAttachments(const Channels& ch, const LoadOptions& options, Rig* nested,
                                unsigned char* const* memory, Rig* rig, Error* err) {
  std::uint32_t poses[fmt::kMaxChannels] = {};
  poses[0] = rig->pose_count_;
  std::uint64_t vertices = 0, workspace = 0;
  for (std::uint32_t a = 0; a < ch.A; ++a) {
    ArenaSource in_place;
    in_place.kind = ArenaSource::kCaller;
    in_place.memory = memory[a];
    in_place.memory_size = ch.entries[a].arena;
    in_place.nested = true;
    Rig& r = nested[a];
    const fmt::AttachmentEntry& entry = ch.entries[a].record;
    if (!Load(ch.entries[a].bytes, std::size_t(entry.size), &r, err, options, in_place)) return NestedFail(err, a);
    const std::uint32_t k = entry.channel;
    if (entry.joint_triangle >= r.triangle_count_)
      return Fail(err, ErrorCode::kBadValue, "attachment %u: joint triangle %u of %u", a, entry.joint_triangle,
                  r.triangle_count_);
    if (poses[k] == 0) poses[k] = r.pose_count_;
    if (poses[k] != r.pose_count_)
      return Fail(err, ErrorCode::kBadValue, "attachment %u has %u poses, its channel %u has %u", a, r.pose_count_, k,
                  poses[k]);
    vertices += r.vertex_count_;
    const std::uint64_t need = r.batch_workspace_size();
    if (need > workspace) workspace = need;
  }
  if (vertices > fmt::kMaxVertices)
    return Fail(err, ErrorCode::kTooLarge, "the attachments have %llu vertices, above %u", (unsigned long long)vertices,
                fmt::kMaxVertices);
  auto* offsets = const_cast<std::uint32_t*>(rig->channel_offsets_.data);
  std::uint32_t total = 0;
  for (std::uint32_t k = 0; k < ch.C; ++k) {
    offsets[k] = k == 0 ? 0 : total;
    if (k) total += poses[k];
  }
  rig->attached_vertex_count_ = std::uint32_t(vertices);
  rig->attached_weight_count_ = total;
  rig->attach_workspace_ = std::size_t(workspace);
  return true;
}

}  // namespace posemorph
