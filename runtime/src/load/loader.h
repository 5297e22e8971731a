// SPDX-License-Identifier: MIT
// The loader behind LoadRig, RigMemorySize, LoadRigInPlace and
// ReadRigSections. Every byte is hostile: each count is bounded before it
// sizes anything, each section's size must equal what the counts imply, each
// index is range-checked and each number must be finite and within the
// format's limits, so that a Rig that loads is one every job can evaluate
// without further checks.
//
// The steps, in the order RigLoader::Load runs them, and their files:
//   load.cpp           Load; the public entry points
//   section_table.cpp  ReadHeader, ReadSectionTable (and ReadSections)
//   counts.cpp         ReadCounts (META, bounded), FindSections (sizes implied by the counts)
//   channels.cpp       ReadChannels (CHAN, before the arena), LayoutChannels, LoadAttachments
//   machine.cpp        ReadMachine (MACH, before the arena), LayoutMachine, CheckMachinePaths (after)
//   arena_layout.cpp   PlaceArena, CheckArenaSize, LayoutArena (twice: sizing, then filling)
//   value_checks.cpp   ReadStrings, ReadPaths, ReadEvents, CheckIndices, CheckFactor, ReadParts, CheckNumbers
//   kernel_data.cpp    BuildSolveRows, BuildBlendBlocks, Finish (what the kernels read)
//   solve_bound.cpp    CheckSolveBound (what the solve can give for any weights the jobs take)
//   placement.cpp      ReadPlacement (PLCE, or the default anchor; after Finish)
//   atlas.cpp          ReadAtlas (ATLS, before the arena), LayoutAtlas, FillPages (the pages, or one per drawing)
// The records read are defined once, with the bake's writer, in
// posemorph/format/records.h.
#pragma once
#include <cmath>
#include <cstdint>
#include <cstring>

#include "../compact/compact_rig.h"
#include "../load_error.h"
#include "posemorph/rig.h"
#include "posemorph/rig_format.h"

namespace posemorph {
namespace detail {
struct KernelTable;
}

namespace detail::load {

namespace fmt = format;

constexpr auto Fail = detail::LoadFail;

// A section tag as four printable characters, for messages.
inline void TagName(std::uint32_t tag, char out[5]) {
  for (int i = 0; i < 4; ++i) {
    const char c = char((tag >> (8 * i)) & 0xFFu);
    out[i] = (c >= 32 && c < 127) ? c : '?';
  }
  out[4] = 0;
}

struct Section {
  std::uint32_t tag = 0;
  std::uint64_t offset = 0, size = 0;
};

struct SectionTable {
  Section entries[fmt::kMaxSections];
  std::uint32_t count = 0;
  const Section* Find(std::uint32_t tag) const {
    for (std::uint32_t i = 0; i < count; ++i)
      if (entries[i].tag == tag) return &entries[i];
    return nullptr;
  }
};

// Bump allocator over the arena; the first pass (base == nullptr) only sizes.
// Sizes are counted in 64 bits, so that a 32-bit target (WebAssembly) can
// refuse an arena larger than its address space instead of wrapping around.
struct ArenaLayout {
  unsigned char* base = nullptr;
  std::uint64_t used = 0;
  template <typename T>
  T* Take(std::uint64_t count) {
    used = (used + kRigMemoryAlignment - 1) & ~std::uint64_t(kRigMemoryAlignment - 1);
    T* p = base ? reinterpret_cast<T*>(base + std::size_t(used)) : nullptr;
    used += count * sizeof(T);
    return p;
  }
};

struct Parser {
  const unsigned char* bytes;
  std::uint64_t size;
  SectionTable table;
  Error* err;

  // The section with `tag`, which must be exactly `expected` bytes long.
  bool Get(std::uint32_t tag, std::uint64_t expected, const unsigned char** out) {
    char name[5];
    TagName(tag, name);
    const Section* s = table.Find(tag);
    if (!s) return Fail(err, ErrorCode::kBadLayout, "missing section %s", name);
    if (s->size != expected)
      return Fail(err, ErrorCode::kBadLayout, "section %s is %llu bytes, the counts imply %llu", name,
                  (unsigned long long)s->size, (unsigned long long)expected);
    *out = bytes + s->offset;
    return true;
  }
};

// An array section copied into the arena (it is little-endian in the file,
// as the host is: load.cpp refuses to build otherwise).
template <typename T>
Span<const T> CopyInto(ArenaLayout& arena, const unsigned char* src, std::uint64_t count) {
  T* dst = arena.Take<T>(count);
  if (dst && count) std::memcpy(dst, src, std::size_t(count) * sizeof(T));
  return {dst, std::size_t(count)};
}

// Finite, and at most `limit` in magnitude. The limits (rig_format.h) keep
// every evaluation finite for every pose-space point and every weight a job
// accepts: finite but huge values (an angle of 1e53) used to load and give
// NaN positions.
inline bool CheckFinite(Span<const double> values, const char* what, Error* err, double limit = format::kMaxMagnitude) {
  for (std::size_t i = 0; i < values.size; ++i) {
    if (!std::isfinite(values[i])) return Fail(err, ErrorCode::kBadValue, "%s[%zu] is not a finite number", what, i);
    if (!(std::fabs(values[i]) <= limit))
      return Fail(err, ErrorCode::kBadValue, "%s[%zu] is %g, beyond the limit of %g", what, i, values[i], limit);
  }
  return true;
}

// Where the arena comes from: one allocation (LoadRig), the caller's memory
// (LoadRigInPlace), or nowhere, when only its size is wanted (RigMemorySize).
struct ArenaSource {
  enum Kind { kAllocate, kCaller, kSizeOnly } kind = kAllocate;
  void* memory = nullptr;
  std::size_t memory_size = 0;
  std::size_t* needed = nullptr;
  bool nested = false;  // an attachment's rig (format 1.7): no CHAN of its own
  // A nested size-only load reports its counts here (the character's totals, LoadLimits).
  std::uint64_t* vertices = nullptr;
  std::uint64_t* nonzeros = nullptr;
};

// The header's fields the later steps use.
struct Header {
  std::uint16_t major = 0, minor = 0;
  std::uint64_t file_size = 0;
  std::uint32_t section_count = 0;
  std::uint32_t checksum = 0;
  std::uint64_t table_end = 0;
};

// META, bounded, and the counts derived from it.
struct Counts {
  fmt::Meta meta{};
  std::uint64_t V = 0, T = 0, N = 0, P = 0, nnz = 0;
  std::uint64_t n = 0;        // V - 1 unknowns (vertex 0 is pinned)
  std::uint64_t strings = 0;  // 2N + P (+ 1) (+ M + MN): pose names, image references, path names (, drawing folder)
                              // (, part names, part images) (, event names)
  std::uint64_t parts = 0;    // M: PART entries (format 1.6), 0 without
  std::uint64_t events = 0;   // E: EVNT entries (format 1.8), 0 without
  bool part_pose_orders = false;  // PORD: a draw order per pose (format 1.6)
  std::uint64_t grid_corners = 0, grid_centres = 0, grid_vertices = 0;
  bool has_uvs = false, compact = false;
};

// Where each section's bytes are, their sizes checked against the counts
// (null: absent, or not stored in this encoding).
struct Sources {
  const unsigned char *tris = nullptr, *poses = nullptr, *points = nullptr, *cents = nullptr, *masses = nullptr,
                      *grads = nullptr, *angles = nullptr, *stretches = nullptr, *perm = nullptr, *lcol = nullptr,
                      *lrow = nullptr, *lval = nullptr, *dinv = nullptr, *wgrid = nullptr, *uvs = nullptr,
                      *paths = nullptr, *strs = nullptr, *pkeys = nullptr, *canvases = nullptr, *parts = nullptr,
                      *pose_orders = nullptr, *events = nullptr, *placement = nullptr;
  std::uint64_t strings_size = 0, key_total = 0;
  detail::CompactLayout packed;
  detail::CompactCounts packed_counts{};
  bool affine_uvs = false;
};

// The arena's parts besides the Rig's own spans: what the load reads and
// builds in, and the solve's index arrays before they become spans.
struct Scratch {
  detail::CompactOutputs decoded{};
  Span<const char> chars;
  StringView* strings = nullptr;
  PathView* path_views = nullptr;
  EventView* event_views = nullptr;
  Span<const double> keys;
  unsigned char* seen = nullptr;
  std::uint32_t* row_start = nullptr;
  bool narrow = false;  // 16-bit solve indices
  std::uint32_t *row_col2 = nullptr, *col_row2 = nullptr;
  std::uint16_t *row_col2_16 = nullptr, *col_row2_16 = nullptr;
  double* row_value = nullptr;
  std::uint32_t* row_fill = nullptr;
  double* solve_bound = nullptr;  // n, for CheckSolveBound
  std::uint64_t blocks = 0;
  double* blend = nullptr;
  std::uint32_t* draw_sequence = nullptr;  // the parts back to front (format 1.6); per pose with PORD
};

// CHAN (format 1.7), read before the arena is laid out: the records, the
// names and each nested rig's bytes and arena size.
struct Channels {
  std::uint32_t C = 1, A = 0;
  struct Entry {
    fmt::AttachmentEntry record{};
    const unsigned char* bytes = nullptr;
    std::size_t arena = 0;  // the nested rig's arena (RigMemorySize)
  } entries[fmt::kMaxAttachments];
  const unsigned char* names[fmt::kMaxChannels] = {};
  std::uint32_t name_sizes[fmt::kMaxChannels] = {};
  std::uint64_t name_bytes = 0;
  std::uint64_t vertices = 0, nonzeros = 0;  // the attachments' together
};

// MACH (format 1.9), read before the arena is laid out: its header and
// where its entries and names lie.
struct Machine {
  bool present = false;
  fmt::MachineHeader h{};
  const unsigned char *inputs = nullptr, *layers = nullptr, *states = nullptr, *transitions = nullptr,
                      *conditions = nullptr, *behaviours = nullptr, *colours = nullptr, *names = nullptr;
  std::uint64_t name_bytes = 0;    // without their lengths
  std::uint32_t part_colours = 0;  // colour entries for a part (the rest are a state's character colour)
};

// ATLS (format 1.12), read before the arena is laid out: its header and
// where its entries and names lie.
struct Atlas {
  bool present = false;
  fmt::AtlasHeader h{};
  const unsigned char *pages = nullptr, *regions = nullptr, *names = nullptr;
  const unsigned char* canvases = nullptr;  // CANV: the poses' canvases, which the regions' maps take
  std::uint64_t name_bytes = 0;             // without their lengths
};

}  // namespace detail::load

// The one loader (a friend of Rig): its steps are the static members below,
// in the order Load runs them (loader.h's list says which file holds each).
struct RigLoader {
  using ArenaLayout = detail::load::ArenaLayout;
  using ArenaSource = detail::load::ArenaSource;
  using Channels = detail::load::Channels;
  using Counts = detail::load::Counts;
  using Header = detail::load::Header;
  using Machine = detail::load::Machine;
  using Atlas = detail::load::Atlas;
  using Parser = detail::load::Parser;
  using Scratch = detail::load::Scratch;
  using Sources = detail::load::Sources;

  static bool Load(const void* data, std::size_t size, Rig* out, Error* err, const LoadOptions& options,
                   const ArenaSource& source);
  static bool CheckLimits(const Counts& c, const LoadLimits& limits, Error* err);
  static bool CheckCharacterLimits(const Counts& c, const LoadLimits& limits, const Channels& ch, Error* err);
  static bool ReadHeader(const unsigned char* bytes, std::size_t size, const LoadOptions& options, Header* h,
                         Error* err);
  static bool ReadSectionTable(const unsigned char* bytes, std::size_t size, const Header& h, Parser* parser,
                               Error* err);
  static bool ReadCounts(Parser& parser, Counts* c, Error* err);
  // ReadRigSections: the header and table steps alone.
  static bool ReadSections(const void* data, std::size_t size, RigSection* out, std::uint32_t capacity,
                           std::uint32_t* count, Error* err);
  static bool FindSections(const unsigned char* bytes, const Header& h, Parser& parser, const Counts& c, Sources* s,
                           Error* err);
  static void LayoutArena(ArenaLayout& arena, const Counts& c, const Sources& s, const LoadOptions& options, Rig* rig,
                          Scratch* scratch);
  static void LayoutCompact(ArenaLayout& arena, const Counts& c, const Sources& s, Rig* rig, Scratch* scratch);
  static void LayoutExact(ArenaLayout& arena, const Counts& c, const Sources& s, Rig* rig);
  static bool PlaceArena(const ArenaSource& source, int pass, Rig* rig, ArenaLayout* arena, Error* err);
  static bool CheckArenaSize(const ArenaLayout& arena, const Counts& c, std::uint64_t file_size, Error* err);
  static bool ReadStrings(const Counts& c, const Scratch& scratch, Rig* rig, Error* err);
  static bool ReadPaths(const Counts& c, const Sources& s, const Scratch& scratch, Rig* rig, Error* err);
  static bool ReadEvents(const Counts& c, const Sources& s, const Scratch& scratch, Rig* rig, Error* err);
  static bool CheckIndices(const Counts& c, const Scratch& scratch, const Rig& rig, Error* err);
  static bool ReadParts(const Counts& c, const Scratch& scratch, Rig* rig, Error* err);
  static bool CheckFactor(const Counts& c, const Rig& rig, Error* err);
  static void BuildSolveRows(const Counts& c, const Scratch& scratch, Rig* rig);
  static void BuildBlendBlocks(const Counts& c, const Scratch& scratch, Rig* rig);
  static bool CheckNumbers(const Rig& rig, Error* err);
  static bool CheckSolveBound(const Counts& c, const Scratch& scratch, const Rig& rig, Error* err);
  static bool ReadChannels(const unsigned char* bytes, const Parser& parser, const Counts& c,
                           const LoadOptions& options, bool nested, Channels* ch, Error* err);
  static void LayoutChannels(ArenaLayout& arena, const Channels& ch, Rig* rig, Rig** nested, unsigned char** memory);
  static bool LoadAttachments(const Channels& ch, const LoadOptions& options, Rig* nested, unsigned char* const* memory,
                              Rig* rig, Error* err);
  static void Finish(const Header& h, const Counts& c, const detail::KernelTable* kernels, Rig* rig);
  static bool ReadMachine(const unsigned char* bytes, const Parser& parser, bool nested, std::uint32_t channel_count,
                          Machine* m, Error* err);
  static void LayoutMachine(ArenaLayout& arena, const Machine& m, Rig* rig);
  static bool CheckMachinePaths(const Rig& rig, Error* err);
  static bool ReadPlacement(const Sources& s, bool nested, Rig* rig, Error* err);
  static bool ReadAtlas(const unsigned char* bytes, const Parser& parser, const Counts& c, const Sources& s, Atlas* a,
                        Error* err);
  static void LayoutAtlas(ArenaLayout& arena, const Counts& c, const Atlas& a, Rig* rig);
  static void FillPages(const Atlas& a, Rig* rig);
};

}  // namespace posemorph
