// SPDX-License-Identifier: MIT
// LoadRig: every byte is hostile. Each count is bounded before it sizes
// anything, each section's size must equal what the counts imply, each index
// is range-checked and each number must be finite, so that a Rig that loads is
// one every job can evaluate without further checks. The steps, in order:
// ReadHeader, ReadSectionTable, ReadCounts (META), FindSections, then twice
// LayoutArena (sizing, then filling), and on the filled arena ReadStrings,
// ReadPaths, CheckIndices, CheckFactor, BuildSolveRows, BuildBlendBlocks and
// CheckNumbers.
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <new>
#include <utility>

#include "compact/compact_rig.h"
#include "isa_select.h"
#include "load_error.h"
#include "posemorph/rig.h"
#include "posemorph/rig_format.h"

#if defined(_MSC_VER) && !defined(__clang__)
// MSVC targets (x86, x64, ARM64) are little-endian.
#elif !defined(__BYTE_ORDER__) || __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "posemorph's loader maps the little-endian format directly; port ReadU32/ReadF64 first"
#endif

namespace posemorph {
namespace {

namespace fmt = format;

constexpr auto Fail = detail::LoadFail;

std::uint16_t ReadU16(const unsigned char* p) {
  std::uint16_t v;
  std::memcpy(&v, p, 2);
  return v;
}
std::uint32_t ReadU32(const unsigned char* p) {
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}
std::uint64_t ReadU64(const unsigned char* p) {
  std::uint64_t v;
  std::memcpy(&v, p, 8);
  return v;
}

void TagName(std::uint32_t tag, char out[5]) {
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
bool CheckFinite(Span<const double> values, const char* what, Error* err, double limit = format::kMaxMagnitude) {
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
};

// The header's fields the later steps use.
struct Header {
  std::uint16_t major = 0, minor = 0;
  std::uint64_t file_size = 0;
  std::uint32_t section_count = 0;
  std::uint64_t table_end = 0;
};

// META, bounded, and the counts derived from it.
struct Counts {
  fmt::Meta meta{};
  std::uint64_t V = 0, T = 0, N = 0, P = 0, nnz = 0;
  std::uint64_t n = 0;        // V - 1 unknowns (vertex 0 is pinned)
  std::uint64_t strings = 0;  // 2N + P (+ 1) (+ M + MN): pose names, image references, path names (, drawing folder)
                              // (, part names, part images)
  std::uint64_t parts = 0;    // M: PART entries (format 1.6), 0 without
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
                      *pose_orders = nullptr;
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
  Span<const double> keys;
  unsigned char* seen = nullptr;
  std::uint32_t* row_start = nullptr;
  bool narrow = false;  // 16-bit solve indices
  std::uint32_t *row_col2 = nullptr, *col_row2 = nullptr;
  std::uint16_t *row_col2_16 = nullptr, *col_row2_16 = nullptr;
  double* row_value = nullptr;
  std::uint32_t* row_fill = nullptr;
  std::uint64_t blocks = 0;
  double* blend = nullptr;
  std::uint32_t* draw_sequence = nullptr;  // the parts back to front (format 1.6); per pose with PORD
};

// CHAN (format 1.7), read before the arena is laid out: the records, the
// names and each nested rig's bytes and arena size.
struct Channels {
  std::uint32_t C = 1, A = 0;
  struct Entry {
    std::uint32_t channel = 0, parent_triangle = 0, joint_triangle = 0;
    double parent_weights[3] = {0, 0, 0}, joint_weights[3] = {0, 0, 0};
    const unsigned char* bytes = nullptr;
    std::uint64_t size = 0;
    std::size_t arena = 0;  // the nested rig's arena (RigMemorySize)
  } entries[fmt::kMaxAttachments];
  const unsigned char* names[fmt::kMaxChannels] = {};
  std::uint32_t name_sizes[fmt::kMaxChannels] = {};
  std::uint64_t name_bytes = 0;
};

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

// The one loader behind LoadRig, RigMemorySize and LoadRigInPlace (a friend
// of Rig): its steps are the static members below, in the order Load runs them.
struct RigLoader {
  static bool Load(const void* data, std::size_t size, Rig* out, Error* err, const LoadOptions& options,
                   const ArenaSource& source);
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
  static bool CheckIndices(const Counts& c, const Scratch& scratch, const Rig& rig, Error* err);
  static bool ReadParts(const Counts& c, const Scratch& scratch, Rig* rig, Error* err);
  static bool CheckFactor(const Counts& c, const Rig& rig, Error* err);
  static void BuildSolveRows(const Counts& c, const Scratch& scratch, Rig* rig);
  static void BuildBlendBlocks(const Counts& c, const Scratch& scratch, Rig* rig);
  static bool CheckNumbers(const Rig& rig, Error* err);
  static bool ReadChannels(const unsigned char* bytes, const Parser& parser, const Counts& c,
                           const LoadOptions& options, bool nested, Channels* ch, Error* err);
  static void LayoutChannels(ArenaLayout& arena, const Channels& ch, Rig* rig, Rig** nested, unsigned char** memory);
  static bool LoadAttachments(const Channels& ch, const LoadOptions& options, Rig* nested, unsigned char* const* memory,
                              Rig* rig, Error* err);
  static void Finish(const unsigned char* bytes, const Header& h, const Counts& c, const detail::KernelTable* kernels,
                     Rig* rig);
};

bool LoadRig(const void* data, std::size_t size, Rig* out, Error* err, const LoadOptions& options) {
  return RigLoader::Load(data, size, out, err, options, ArenaSource{});
}

bool RigMemorySize(const void* data, std::size_t size, std::size_t* needed, Error* err, const LoadOptions& options) {
  if (err) *err = Error{};
  if (!needed) return Fail(err, ErrorCode::kInvalidArgument, "no output size given");
  *needed = 0;
  Rig scratch;
  ArenaSource source;
  source.kind = ArenaSource::kSizeOnly;
  source.needed = needed;
  return RigLoader::Load(data, size, &scratch, err, options, source);
}

bool LoadRigInPlace(const void* data, std::size_t size, void* memory, std::size_t memory_size, Rig* out, Error* err,
                    const LoadOptions& options) {
  ArenaSource source;
  source.kind = ArenaSource::kCaller;
  source.memory = memory;
  source.memory_size = memory_size;
  return RigLoader::Load(data, size, out, err, options, source);
}

bool RigLoader::Load(const void* data, std::size_t size, Rig* out, Error* err, const LoadOptions& options,
                     const ArenaSource& source) {
  if (err) *err = Error{};
  if (!out) return Fail(err, ErrorCode::kInvalidArgument, "no output rig given");
  *out = Rig();
  if (!data && size) return Fail(err, ErrorCode::kInvalidArgument, "null data");
  const detail::KernelTable* kernels = nullptr;
  if (!detail::SelectKernels(options.isa, &kernels, err)) return false;
  const auto* bytes = static_cast<const unsigned char*>(data);

  Header h;
  if (!ReadHeader(bytes, size, options, &h, err)) return false;
  Parser parser{bytes, size, {}, err};
  if (!ReadSectionTable(bytes, size, h, &parser, err)) return false;
  Counts c;
  if (!ReadCounts(parser, &c, err)) return false;
  Sources s;
  if (!FindSections(bytes, h, parser, c, &s, err)) return false;
  Channels channels;
  if (!ReadChannels(bytes, parser, c, options, source.nested, &channels, err)) return false;

  // Two passes over one layout: size the arena, then fill it.
  Rig rig;
  Rig* nested = nullptr;
  unsigned char* nested_memory[fmt::kMaxAttachments] = {};
  Scratch scratch;
  for (int pass = 0; pass < 2; ++pass) {
    ArenaLayout arena;
    if (!PlaceArena(source, pass, &rig, &arena, err)) return false;
    scratch = Scratch{};
    LayoutArena(arena, c, s, options, &rig, &scratch);
    if (pass == 0 && !CheckArenaSize(arena, c, h.file_size, err)) return false;
    LayoutChannels(arena, channels, &rig, &nested, nested_memory);
    if (pass == 0) {
      if (arena.used > std::uint64_t(SIZE_MAX / 2))
        return Fail(err, ErrorCode::kTooLarge, "the rig needs %llu bytes in memory, more than this target addresses",
                    (unsigned long long)arena.used);
      rig.arena_size_ = std::size_t(arena.used);
      if (source.kind == ArenaSource::kSizeOnly) {
        *source.needed = rig.arena_size_;
        return true;
      }
    }
  }
  if (c.compact && !detail::DecodeCompact(s.packed, s.packed_counts, scratch.decoded, err)) return false;
  if (!ReadStrings(c, scratch, &rig, err) || !ReadPaths(c, s, scratch, &rig, err) ||
      !CheckIndices(c, scratch, rig, err) || !CheckFactor(c, rig, err) || !ReadParts(c, scratch, &rig, err))
    return false;
  BuildSolveRows(c, scratch, &rig);
  BuildBlendBlocks(c, scratch, &rig);
  if (!CheckNumbers(rig, err)) return false;
  Finish(bytes, h, c, kernels, &rig);
  if (channels.A && !LoadAttachments(channels, options, nested, nested_memory, &rig, err)) return false;
  *out = std::move(rig);
  return true;
}

bool RigLoader::ReadHeader(const unsigned char* bytes, std::size_t size, const LoadOptions& options, Header* h,
                           Error* err) {
  if (size < fmt::kHeaderSize)
    return Fail(err, ErrorCode::kTruncated, "%zu bytes is shorter than the %u-byte header", size, fmt::kHeaderSize);
  if (std::memcmp(bytes, fmt::kMagic, sizeof(fmt::kMagic)) != 0)
    return Fail(err, ErrorCode::kBadMagic, "not a posemorph rig (bad magic)");
  h->major = ReadU16(bytes + fmt::kOffVersionMajor);
  h->minor = ReadU16(bytes + fmt::kOffVersionMinor);
  if (h->major != fmt::kVersionMajor)
    return Fail(err, ErrorCode::kBadVersion, "format version %u.%u; this runtime reads %u.x", h->major, h->minor,
                fmt::kVersionMajor);
  if (ReadU32(bytes + fmt::kOffHeaderSize) != fmt::kHeaderSize)
    return Fail(err, ErrorCode::kBadLayout, "header size field is %u, expected %u",
                ReadU32(bytes + fmt::kOffHeaderSize), fmt::kHeaderSize);
  h->file_size = ReadU64(bytes + fmt::kOffFileSize);
  if (h->file_size > size)
    return Fail(err, ErrorCode::kTruncated, "header says %llu bytes, only %zu given", (unsigned long long)h->file_size,
                size);
  if (h->file_size < size)
    return Fail(err, ErrorCode::kBadLayout, "header says %llu bytes, %zu given (trailing bytes)",
                (unsigned long long)h->file_size, size);
  if (ReadU32(bytes + fmt::kOffFlags) != 0)
    return Fail(err, ErrorCode::kBadVersion, "unknown header flags 0x%x", ReadU32(bytes + fmt::kOffFlags));
  for (std::uint32_t i = fmt::kOffChecksum + 4; i < fmt::kHeaderSize; ++i)
    if (bytes[i] != 0) return Fail(err, ErrorCode::kBadLayout, "reserved header byte %u is not zero", i);
  h->section_count = ReadU32(bytes + fmt::kOffSectionCount);
  if (h->section_count == 0 || h->section_count > fmt::kMaxSections)
    return Fail(err, ErrorCode::kBadLayout, "section count %u outside 1..%u", h->section_count, fmt::kMaxSections);
  h->table_end = fmt::kHeaderSize + std::uint64_t(h->section_count) * fmt::kSectionEntrySize;
  if (h->table_end > size) return Fail(err, ErrorCode::kTruncated, "section table runs past the end");
  if (options.verify_checksum) {
    const std::uint32_t stored = ReadU32(bytes + fmt::kOffChecksum);
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
    const unsigned char* e = bytes + fmt::kHeaderSize + std::size_t(i) * fmt::kSectionEntrySize;
    Section s{ReadU32(e), ReadU64(e + 8), ReadU64(e + 16)};
    char name[5];
    TagName(s.tag, name);
    if (ReadU32(e + 4) != 0) return Fail(err, ErrorCode::kBadLayout, "section %s: reserved field set", name);
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

// META: counts, bounded before they size anything.
bool RigLoader::ReadCounts(Parser& parser, Counts* c, Error* err) {
  const unsigned char* p = nullptr;
  if (!parser.Get(fmt::kMeta, fmt::kMetaSize, &p)) return false;
  fmt::Meta& meta = c->meta;
  std::memcpy(&meta, p, sizeof(meta));
  static_assert(sizeof(fmt::Meta) == fmt::kMetaSize, "Meta layout");
  const std::uint64_t V = meta.vertex_count, T = meta.triangle_count, N = meta.pose_count, P = meta.path_count,
                      nnz = meta.factor_nonzeros;
  if (V < 3 || V > fmt::kMaxVertices)
    return Fail(err, V < 3 ? ErrorCode::kBadValue : ErrorCode::kTooLarge, "vertex count %llu outside 3..%u",
                (unsigned long long)V, fmt::kMaxVertices);
  if (T < 1 || T > fmt::kMaxTriangles)
    return Fail(err, T < 1 ? ErrorCode::kBadValue : ErrorCode::kTooLarge, "triangle count %llu outside 1..%u",
                (unsigned long long)T, fmt::kMaxTriangles);
  if (N < 2 || N > fmt::kMaxPoses)
    return Fail(err, N < 2 ? ErrorCode::kBadValue : ErrorCode::kTooLarge, "pose count %llu outside 2..%u",
                (unsigned long long)N, fmt::kMaxPoses);
  if (P > fmt::kMaxPaths)
    return Fail(err, ErrorCode::kTooLarge, "path count %llu above %u", (unsigned long long)P, fmt::kMaxPaths);
  if (meta.grid_cells_x < 1 || meta.grid_cells_y < 1 || meta.grid_cells_x > fmt::kMaxGridCells ||
      meta.grid_cells_y > fmt::kMaxGridCells)
    return Fail(err, ErrorCode::kTooLarge, "weight grid %ux%u outside 1..%u cells per axis", meta.grid_cells_x,
                meta.grid_cells_y, fmt::kMaxGridCells);
  if (nnz > fmt::kMaxFactorNonzeros)
    return Fail(err, ErrorCode::kTooLarge, "factor has %llu nonzeros, above %u", (unsigned long long)nnz,
                fmt::kMaxFactorNonzeros);
  if ((meta.flags &
       ~(fmt::kMetaFlagHasUVs | fmt::kMetaFlagGridCentres | fmt::kMetaFlagCompact | fmt::kMetaFlagNearestFilter |
         fmt::kMetaFlagDrawingFolder | fmt::kMetaFlagParts | fmt::kMetaFlagPartPoseOrders)) != 0)
    return Fail(err, ErrorCode::kBadVersion, "unknown META flags 0x%x", meta.flags);
  if (!std::isfinite(meta.grid_origin_x) || !std::isfinite(meta.grid_origin_y) || !std::isfinite(meta.grid_cell_size) ||
      !(meta.grid_cell_size > 0) || !std::isfinite(meta.grid_cell_size * meta.grid_cells_x) ||
      !std::isfinite(meta.grid_cell_size * meta.grid_cells_y) ||
      !std::isfinite(meta.grid_origin_x + meta.grid_cell_size * meta.grid_cells_x) ||
      !std::isfinite(meta.grid_origin_y + meta.grid_cell_size * meta.grid_cells_y))
    return Fail(err, ErrorCode::kBadValue, "weight grid geometry is not finite and positive");
  if (!std::isfinite(meta.default_sigma) || meta.default_sigma < 0 || meta.default_sigma > 1)
    return Fail(err, ErrorCode::kBadValue, "default sigma %g outside [0, 1]", meta.default_sigma);
  if (!std::isfinite(meta.rig_size) || !(meta.rig_size > 0))
    return Fail(err, ErrorCode::kBadValue, "rig size %g is not finite and positive", meta.rig_size);
  c->V = V, c->T = T, c->N = N, c->P = P, c->nnz = nnz;
  c->n = V - 1;
  if (meta.flags & fmt::kMetaFlagParts) {
    const Section* parts = parser.table.Find(fmt::kParts);
    if (!parts) return Fail(err, ErrorCode::kBadLayout, "META says the rig has parts, but there is no PART section");
    if (parts->size % fmt::kPartEntrySize != 0 || parts->size < fmt::kPartEntrySize ||
        parts->size > std::uint64_t(fmt::kMaxParts) * fmt::kPartEntrySize)
      return Fail(err, ErrorCode::kBadLayout, "PART section of %llu bytes: 1..%u entries of %u bytes",
                  (unsigned long long)parts->size, fmt::kMaxParts, fmt::kPartEntrySize);
    c->parts = parts->size / fmt::kPartEntrySize;
  } else if (parser.table.Find(fmt::kParts)) {
    return Fail(err, ErrorCode::kBadLayout, "PART section present but META says the rig has no parts");
  }
  c->part_pose_orders = (meta.flags & fmt::kMetaFlagPartPoseOrders) != 0;
  if (c->part_pose_orders && !c->parts)
    return Fail(err, ErrorCode::kBadLayout, "META says the draw order changes with the pose, but the rig has no parts");
  if (!c->part_pose_orders && parser.table.Find(fmt::kPartPoseOrders))
    return Fail(err, ErrorCode::kBadLayout, "PORD section present but META says the draw order is fixed");
  c->strings = 2 * N + P + ((meta.flags & fmt::kMetaFlagDrawingFolder) ? 1 : 0) + c->parts * (1 + N);
  c->grid_corners = std::uint64_t(meta.grid_cells_x + 1) * (meta.grid_cells_y + 1);
  c->grid_centres = (meta.flags & fmt::kMetaFlagGridCentres) ? std::uint64_t(meta.grid_cells_x) * meta.grid_cells_y : 0;
  c->grid_vertices = c->grid_corners + c->grid_centres;
  c->has_uvs = (meta.flags & fmt::kMetaFlagHasUVs) != 0;
  c->compact = (meta.flags & fmt::kMetaFlagCompact) != 0;
  return true;
}

// Sections with sizes implied by the counts; the compact encoding's layout;
// the path table's key count; the string table.
bool RigLoader::FindSections(const unsigned char* bytes, const Header& h, Parser& parser, const Counts& c, Sources* s,
                             Error* err) {
  const std::uint64_t V = c.V, T = c.T, N = c.N, P = c.P, n = c.n, nnz = c.nnz;
  if (!c.compact &&
      (!parser.Get(fmt::kTriangles, T * 12, &s->tris) || !parser.Get(fmt::kPosePositions, N * V * 16, &s->poses) ||
       !parser.Get(fmt::kPoseCentroids, N * 16, &s->cents) || !parser.Get(fmt::kVertexMasses, V * 8, &s->masses) ||
       !parser.Get(fmt::kGradients, T * 48, &s->grads) || !parser.Get(fmt::kAngles, T * N * 8, &s->angles) ||
       !parser.Get(fmt::kStretches, T * N * 24, &s->stretches) || !parser.Get(fmt::kPermutation, n * 4, &s->perm) ||
       !parser.Get(fmt::kFactorColumns, (n + 1) * 4, &s->lcol) || !parser.Get(fmt::kFactorRows, nnz * 4, &s->lrow) ||
       !parser.Get(fmt::kFactorValues, nnz * 8, &s->lval) || !parser.Get(fmt::kFactorInvDiagonal, n * 8, &s->dinv) ||
       !parser.Get(fmt::kWeightGrid, c.grid_vertices * N * 8, &s->wgrid)))
    return false;
  if (!parser.Get(fmt::kPosePoints, N * 16, &s->points) || !parser.Get(fmt::kPaths, P * fmt::kPathEntrySize, &s->paths))
    return false;
  s->packed_counts =
      detail::CompactCounts{V, T, N, n, nnz, c.meta.grid_cells_x, c.meta.grid_cells_y, c.grid_centres > 0, h.file_size};
  if (c.compact) {
    auto bytes_of = [&](std::uint32_t tag) {
      const Section* section = parser.table.Find(tag);
      return section ? detail::SectionBytes{bytes + section->offset, section->size} : detail::SectionBytes{};
    };
    if (!detail::ReadCompactLayout(bytes_of(fmt::kQuantPositions), bytes_of(fmt::kQuantTriangles),
                                   bytes_of(fmt::kQuantPermutation), bytes_of(fmt::kQuantTurns),
                                   bytes_of(fmt::kQuantGrid), bytes_of(fmt::kAffineUVs), s->packed_counts, &s->packed,
                                   err))
      return false;
    s->affine_uvs = s->packed.has_affine_uvs;
    if (s->affine_uvs && !c.has_uvs)
      return Fail(err, ErrorCode::kBadLayout, "QUVA section present but META says no uvs");
    if (s->affine_uvs && parser.table.Find(fmt::kUVs))
      return Fail(err, ErrorCode::kBadLayout, "both QUVA and UVS present; a rig stores its uvs once");
  }
  if (c.has_uvs && !s->affine_uvs && !parser.Get(fmt::kUVs, N * V * 8, &s->uvs)) return false;
  if (parser.table.Find(fmt::kCanvases) && !parser.Get(fmt::kCanvases, N * 32, &s->canvases)) return false;
  if (c.parts && !parser.Get(fmt::kParts, c.parts * fmt::kPartEntrySize, &s->parts)) return false;
  if (c.part_pose_orders && !parser.Get(fmt::kPartPoseOrders, N * c.parts * 4, &s->pose_orders)) return false;
  if (!c.has_uvs && parser.table.Find(fmt::kUVs))
    return Fail(err, ErrorCode::kBadLayout, "UVS section present but META says none");
  std::uint64_t key_total = 0;
  for (std::uint64_t i = 0; i < P; ++i) {
    const std::uint32_t keys = ReadU32(s->paths + i * fmt::kPathEntrySize);
    const std::uint32_t flags = ReadU32(s->paths + i * fmt::kPathEntrySize + 4);
    if (keys < 1) return Fail(err, ErrorCode::kBadValue, "path %llu has no keys", (unsigned long long)i);
    if ((flags & ~(fmt::kPathFlagLoop | (0xFFu << fmt::kPathInterpolationShift))) != 0 ||
        (flags >> fmt::kPathInterpolationShift) > std::uint32_t(PathInterpolation::kCatmullRom))
      return Fail(err, ErrorCode::kBadValue, "path %llu has unknown flags 0x%x", (unsigned long long)i, flags);
    key_total += keys;
    if (key_total > fmt::kMaxPathKeys)
      return Fail(err, ErrorCode::kTooLarge, "paths hold more than %u keys", fmt::kMaxPathKeys);
  }
  s->key_total = key_total;
  if (!parser.Get(fmt::kPathKeys, key_total * 24, &s->pkeys)) return false;
  const Section* strings_section = parser.table.Find(fmt::kStrings);
  if (!strings_section) return Fail(err, ErrorCode::kBadLayout, "missing section STRS");
  if (strings_section->size > fmt::kMaxStringBytes)
    return Fail(err, ErrorCode::kTooLarge, "string table above %u bytes", fmt::kMaxStringBytes);
  s->strs = bytes + strings_section->offset;
  s->strings_size = strings_section->size;
  return true;
}

// Where the arena is: allocated, the caller's, or nowhere (pass 0 only sizes it).
bool RigLoader::PlaceArena(const ArenaSource& source, int pass, Rig* rig, ArenaLayout* arena, Error* err) {
  if (pass == 1 && source.kind == ArenaSource::kAllocate) {
    // new[] aligns to 16 bytes on x86-64 and aarch64 but to 8 on WebAssembly:
    // take 15 bytes more and start at the first 16-byte boundary, as
    // LoadRigInPlace asks of a caller's memory (an attachment's nested rig is
    // loaded in place inside this arena).
    rig->arena_.reset(new (std::nothrow) unsigned char[rig->arena_size_ + kRigMemoryAlignment - 1]);
    if (!rig->arena_) return Fail(err, ErrorCode::kOutOfMemory, "cannot allocate %zu bytes", rig->arena_size_);
    const std::uintptr_t start = reinterpret_cast<std::uintptr_t>(rig->arena_.get());
    arena->base = rig->arena_.get() + ((kRigMemoryAlignment - start % kRigMemoryAlignment) % kRigMemoryAlignment);
  } else if (pass == 1) {
    if (!source.memory)
      return Fail(err, ErrorCode::kInvalidArgument, "no memory given (the rig needs %zu bytes)", rig->arena_size_);
    if (reinterpret_cast<std::uintptr_t>(source.memory) % kRigMemoryAlignment != 0)
      return Fail(err, ErrorCode::kInvalidArgument, "memory is not aligned to %zu bytes",
                  std::size_t(kRigMemoryAlignment));
    if (source.memory_size < rig->arena_size_)
      return Fail(err, ErrorCode::kInvalidArgument, "%zu bytes of memory given, the rig needs %zu", source.memory_size,
                  rig->arena_size_);
    arena->base = static_cast<unsigned char*>(source.memory);
  }
  return true;
}

// A compact rig expands at load; bound how far, so that a small hostile
// file cannot claim a huge arena (legitimate rigs expand 10-30x).
bool RigLoader::CheckArenaSize(const ArenaLayout& arena, const Counts& c, std::uint64_t file_size, Error* err) {
  if (c.compact && arena.used > fmt::kMaxCompactExpansion * file_size + (std::uint64_t(1) << 20))
    return Fail(err, ErrorCode::kTooLarge,
                "a compact rig of %llu bytes would need %llu bytes in memory (at most %u times its size)",
                (unsigned long long)file_size, (unsigned long long)arena.used, fmt::kMaxCompactExpansion);
  if (arena.used > std::uint64_t(SIZE_MAX / 2))
    return Fail(err, ErrorCode::kTooLarge, "the rig needs %llu bytes in memory, more than this target addresses",
                (unsigned long long)arena.used);
  return true;
}

// A compact rig's spans: decoded and derived at load into the layout an
// exact rig copies into, then the decoder's scratch.
void RigLoader::LayoutCompact(ArenaLayout& arena, const Counts& c, const Sources& s, Rig* rig_out, Scratch* scratch) {
  Rig& rig = *rig_out;
  const std::uint64_t V = c.V, T = c.T, N = c.N, n = c.n, nnz = c.nnz;
  const std::uint64_t grid_corners = c.grid_corners, grid_centres = c.grid_centres, grid_vertices = c.grid_vertices;
  const bool has_uvs = c.has_uvs, affine_uvs = s.affine_uvs;
  detail::CompactOutputs& decoded = scratch->decoded;
  // Decoded and derived into the layout an exact rig copies into.
  decoded.triangles = arena.Take<std::uint32_t>(T * 3);
  decoded.positions = arena.Take<double>(N * V * 2);
  decoded.centroids = arena.Take<double>(N * 2);
  decoded.factor.vertex_masses = arena.Take<double>(V);
  decoded.factor.gradients = arena.Take<double>(T * 6);
  decoded.angles = arena.Take<double>(T * N);
  decoded.stretches = arena.Take<double>(T * N * 3);
  decoded.order = arena.Take<std::uint32_t>(n);
  decoded.factor.col_start = arena.Take<std::uint32_t>(n + 1);
  decoded.factor.row = arena.Take<std::uint32_t>(nnz);
  decoded.factor.value = arena.Take<double>(nnz);
  decoded.factor.inv_diagonal = arena.Take<double>(n);
  decoded.grid_corners = arena.Take<double>(grid_vertices * N);
  decoded.grid_centres = grid_centres && decoded.grid_corners ? decoded.grid_corners + grid_corners * N : nullptr;
  decoded.uvs = affine_uvs ? arena.Take<float>(N * V * 2) : nullptr;
  rig.triangles_ = {decoded.triangles, std::size_t(T * 3)};
  rig.pose_positions_ = {decoded.positions, std::size_t(N * V * 2)};
  rig.pose_points_ = CopyInto<double>(arena, s.points, N * 2);
  rig.pose_centroids_ = {decoded.centroids, std::size_t(N * 2)};
  rig.vertex_masses_ = {decoded.factor.vertex_masses, std::size_t(V)};
  rig.gradients_ = {decoded.factor.gradients, std::size_t(T * 6)};
  rig.angles_ = {decoded.angles, std::size_t(T * N)};
  rig.stretches_ = {decoded.stretches, std::size_t(T * N * 3)};
  rig.factor_.order = {decoded.order, std::size_t(n)};
  rig.factor_.col_start = {decoded.factor.col_start, std::size_t(n + 1)};
  rig.factor_.row = {decoded.factor.row, std::size_t(nnz)};
  rig.factor_.value = {decoded.factor.value, std::size_t(nnz)};
  rig.factor_.inv_diagonal = {decoded.factor.inv_diagonal, std::size_t(n)};
  rig.grid_.weights = {decoded.grid_corners, std::size_t(grid_corners * N)};
  if (decoded.grid_centres) rig.grid_.centre_weights = {decoded.grid_centres, std::size_t(grid_centres * N)};
  if (affine_uvs)
    rig.uvs_ = {decoded.uvs, std::size_t(N * V * 2)};
  else if (has_uvs)
    rig.uvs_ = CopyInto<float>(arena, s.uvs, N * V * 2);
  // Scratch, used once at load.
  decoded.grid_scratch = arena.Take<std::int64_t>(grid_corners);
  decoded.seen = arena.Take<unsigned char>(n);
  detail::ArapFactorBuffers& f = decoded.factor;
  f.position = arena.Take<std::uint32_t>(n);
  f.parent = arena.Take<std::uint32_t>(n);
  f.flag = arena.Take<std::uint32_t>(n);
  f.path = arena.Take<std::uint32_t>(n);
  f.stack = arena.Take<std::uint32_t>(n);
  f.fill = arena.Take<std::uint32_t>(n);
  f.entry_start = arena.Take<std::uint32_t>(n + 1);
  f.entry_row = arena.Take<std::uint32_t>(detail::ArapEntryCapacity(T));
  f.entry_value = arena.Take<double>(detail::ArapEntryCapacity(T));
  f.work = arena.Take<double>(n);
  f.pivot = arena.Take<double>(n);
}

// An exact rig's spans: copies of its sections.
void RigLoader::LayoutExact(ArenaLayout& arena, const Counts& c, const Sources& s, Rig* rig_out) {
  Rig& rig = *rig_out;
  const std::uint64_t V = c.V, T = c.T, N = c.N, n = c.n, nnz = c.nnz;
  const std::uint64_t grid_corners = c.grid_corners, grid_centres = c.grid_centres, grid_vertices = c.grid_vertices;
  rig.triangles_ = CopyInto<std::uint32_t>(arena, s.tris, T * 3);
  rig.pose_positions_ = CopyInto<double>(arena, s.poses, N * V * 2);
  rig.pose_points_ = CopyInto<double>(arena, s.points, N * 2);
  rig.pose_centroids_ = CopyInto<double>(arena, s.cents, N * 2);
  rig.vertex_masses_ = CopyInto<double>(arena, s.masses, V);
  rig.gradients_ = CopyInto<double>(arena, s.grads, T * 6);
  rig.angles_ = CopyInto<double>(arena, s.angles, T * N);
  rig.stretches_ = CopyInto<double>(arena, s.stretches, T * N * 3);
  rig.factor_.order = CopyInto<std::uint32_t>(arena, s.perm, n);
  rig.factor_.col_start = CopyInto<std::uint32_t>(arena, s.lcol, n + 1);
  rig.factor_.row = CopyInto<std::uint32_t>(arena, s.lrow, nnz);
  rig.factor_.value = CopyInto<double>(arena, s.lval, nnz);
  rig.factor_.inv_diagonal = CopyInto<double>(arena, s.dinv, n);
  const Span<const double> grid_all = CopyInto<double>(arena, s.wgrid, grid_vertices * N);
  rig.grid_.weights = {grid_all.data, std::size_t(grid_corners * N)};
  if (grid_centres && grid_all.data)  // (null while the arena is only being measured)
    rig.grid_.centre_weights = grid_all.subspan(std::size_t(grid_corners * N), std::size_t(grid_centres * N));
  if (c.has_uvs) rig.uvs_ = CopyInto<float>(arena, s.uvs, N * V * 2);
}

// Every span of the rig and every load-time buffer, in one fixed order (the
// same on both passes: the first only sizes, base == nullptr).
void RigLoader::LayoutArena(ArenaLayout& arena, const Counts& c, const Sources& s, const LoadOptions& options,
                            Rig* rig_out, Scratch* scratch) {
  Rig& rig = *rig_out;
  const std::uint64_t T = c.T, N = c.N, P = c.P, n = c.n, nnz = c.nnz;
  if (c.compact)
    LayoutCompact(arena, c, s, rig_out, scratch);
  else
    LayoutExact(arena, c, s, rig_out);
  if (s.canvases) rig.canvases_ = CopyInto<double>(arena, s.canvases, N * 4);
  if (s.parts) {
    rig.part_table_ = CopyInto<std::uint32_t>(arena, s.parts, c.parts * 4);
    if (s.pose_orders) rig.part_pose_orders_ = CopyInto<std::uint32_t>(arena, s.pose_orders, N * c.parts);
    scratch->draw_sequence = arena.Take<std::uint32_t>(c.parts * (s.pose_orders ? N : 1));
  }
  scratch->chars = CopyInto<char>(arena, s.strs, s.strings_size);
  scratch->strings = arena.Take<StringView>(c.strings);
  scratch->path_views = arena.Take<PathView>(P);
  scratch->keys = CopyInto<double>(arena, s.pkeys, s.key_total * 3);
  scratch->seen = arena.Take<unsigned char>(n);  // scratch for the permutation check
  scratch->row_start = arena.Take<std::uint32_t>(n + 1);
  // Index arrays for the solve: 16 bits wide when they fit, else 32.
  const bool narrow = scratch->narrow = 2 * n < 65536 && !options.wide_solve_indices;
  scratch->row_col2 = arena.Take<std::uint32_t>(narrow ? 0 : nnz);
  scratch->col_row2 = arena.Take<std::uint32_t>(narrow ? 0 : nnz);
  scratch->row_col2_16 = arena.Take<std::uint16_t>(narrow ? nnz : 0);
  scratch->col_row2_16 = arena.Take<std::uint16_t>(narrow ? nnz : 0);
  scratch->row_value = arena.Take<double>(nnz);
  scratch->row_fill = arena.Take<std::uint32_t>(n);  // scratch for the transpose
  const std::uint64_t blocks = scratch->blocks = (T + 7) / 8;
  scratch->blend = arena.Take<double>(blocks * 4 * N * 8);
}

// Strings: u32 length + bytes, one after another, exactly filling STRS.
bool RigLoader::ReadStrings(const Counts& c, const Scratch& scratch, Rig* rig, Error* err) {
  const Span<const char> chars = scratch.chars;
  const std::uint64_t string_count = c.strings;
  std::uint64_t at = 0;
  for (std::uint64_t i = 0; i < string_count; ++i) {
    if (chars.size - at < 4)
      return Fail(err, ErrorCode::kBadValue, "string table truncated at string %llu", (unsigned long long)i);
    const std::uint32_t len = ReadU32(reinterpret_cast<const unsigned char*>(chars.data + at));
    at += 4;
    if (len > chars.size - at)
      return Fail(err, ErrorCode::kBadValue, "string %llu runs past the string table", (unsigned long long)i);
    scratch.strings[i] = StringView{chars.data + at, len};
    at += len;
  }
  if (at != chars.size) return Fail(err, ErrorCode::kBadValue, "string table has trailing bytes");
  rig->strings_ = {scratch.strings, std::size_t(string_count)};
  return true;
}

// Paths: finite keys, strictly increasing times.
bool RigLoader::ReadPaths(const Counts& c, const Sources& s, const Scratch& scratch, Rig* rig, Error* err) {
  std::uint64_t key_at = 0;
  for (std::uint64_t i = 0; i < c.P; ++i) {
    const std::uint32_t count = ReadU32(s.paths + i * fmt::kPathEntrySize);
    const std::uint32_t flags = ReadU32(s.paths + i * fmt::kPathEntrySize + 4);
    PathView& view = scratch.path_views[i];
    view.name = scratch.strings[2 * c.N + i];
    view.loop = (flags & fmt::kPathFlagLoop) != 0;
    view.interpolation = PathInterpolation(flags >> fmt::kPathInterpolationShift);
    view.keys = scratch.keys.subspan(std::size_t(key_at * 3), std::size_t(count) * 3);
    key_at += count;
    if (!CheckFinite(view.keys, "path key", err, fmt::kMaxPathValue)) return false;
    for (std::uint32_t k = 1; k < count; ++k)
      if (!(view.keys[3 * k] > view.keys[3 * (k - 1)]))
        return Fail(err, ErrorCode::kBadValue, "path %llu: key times not strictly increasing at key %u",
                    (unsigned long long)i, k);
  }
  rig->paths_ = {scratch.path_views, std::size_t(c.P)};
  return true;
}

// Triangles name three distinct vertices in range; the permutation is one.
bool RigLoader::CheckIndices(const Counts& c, const Scratch& scratch, const Rig& rig, Error* err) {
  const std::uint64_t V = c.V, n = c.n;
  for (std::uint64_t t = 0; t < c.T; ++t) {
    const std::uint32_t a = rig.triangles_[3 * t], b = rig.triangles_[3 * t + 1], d = rig.triangles_[3 * t + 2];
    if (a >= V || b >= V || d >= V)
      return Fail(err, ErrorCode::kBadValue, "triangle %llu has a vertex index >= %llu", (unsigned long long)t,
                  (unsigned long long)V);
    if (a == b || b == d || a == d)
      return Fail(err, ErrorCode::kBadValue, "triangle %llu repeats a vertex", (unsigned long long)t);
  }
  std::memset(scratch.seen, 0, n);
  for (std::uint64_t k = 0; k < n; ++k) {
    const std::uint32_t v = rig.factor_.order[k];
    if (v >= n || scratch.seen[v])
      return Fail(err, ErrorCode::kBadValue, "permutation is not a permutation (entry %llu)", (unsigned long long)k);
    scratch.seen[v] = 1;
  }
  return true;
}

// Parts (format 1.6): they tile the triangles in order, none empty, no
// reserved bits; the draw sequence sorts them by draw order, then index.
bool RigLoader::ReadParts(const Counts& c, const Scratch& scratch, Rig* rig, Error* err) {
  if (!c.parts) return true;
  const Span<const std::uint32_t> table = rig->part_table_;
  std::uint64_t next = 0;
  for (std::uint64_t p = 0; p < c.parts; ++p) {
    const std::uint32_t first = table[4 * p], count = table[4 * p + 1];
    if (first != next || count == 0 || count > c.T - next)
      return Fail(err, ErrorCode::kBadValue, "part %llu covers triangles %u..+%u; parts must tile 0..%llu in order",
                  (unsigned long long)p, first, count, (unsigned long long)c.T);
    if (table[4 * p + 3] != 0)
      return Fail(err, ErrorCode::kBadValue, "part %llu: reserved field set", (unsigned long long)p);
    next += count;
  }
  if (next != c.T)
    return Fail(err, ErrorCode::kBadValue, "the parts cover %llu of %llu triangles", (unsigned long long)next,
                (unsigned long long)c.T);
  // Insertion sort (at most kMaxParts): stable, so ties keep the part order.
  // One sequence, or one per pose (PORD).
  const std::uint32_t M = std::uint32_t(c.parts);
  const std::uint64_t sequences = rig->part_pose_orders_.empty() ? 1 : c.N;
  for (std::uint64_t i = 0; i < sequences; ++i) {
    const auto order_of = [&](std::uint32_t p) {
      return std::int32_t(rig->part_pose_orders_.empty() ? table[4 * p + 2] : rig->part_pose_orders_[i * M + p]);
    };
    std::uint32_t* sequence = scratch.draw_sequence + i * M;
    for (std::uint32_t p = 0; p < M; ++p) {
      std::uint32_t at = p;
      const std::int32_t order = order_of(p);
      while (at > 0 && order_of(sequence[at - 1]) > order) {
        sequence[at] = sequence[at - 1];
        --at;
      }
      sequence[at] = p;
    }
  }
  if (!rig->part_pose_orders_.empty())
    for (std::uint32_t p = 0; p < M; ++p)
      if (rig->part_pose_orders_[p] != table[4 * p + 2])
        return Fail(err, ErrorCode::kBadValue, "part %u: PART's draw order %d is not pose 0's in PORD (%d)", p,
                    std::int32_t(table[4 * p + 2]), std::int32_t(rig->part_pose_orders_[p]));
  rig->draw_sequence_ = {scratch.draw_sequence, std::size_t(sequences * M)};
  return true;
}

// L strictly lower, columns in order, rows increasing within a column (the
// triangular solves then touch only rows j < i < n); D^-1 positive and finite.
bool RigLoader::CheckFactor(const Counts& c, const Rig& rig, Error* err) {
  const std::uint64_t n = c.n, nnz = c.nnz;
  const auto& col = rig.factor_.col_start;
  if (col[0] != 0 || col[n] != nnz)
    return Fail(err, ErrorCode::kBadValue, "factor column pointers do not span the nonzeros");
  for (std::uint64_t j = 0; j < n; ++j) {
    if (col[j] > col[j + 1])
      return Fail(err, ErrorCode::kBadValue, "factor column %llu has negative length", (unsigned long long)j);
    for (std::uint32_t q = col[j]; q < col[j + 1]; ++q) {
      const std::uint32_t r = rig.factor_.row[q];
      if (r <= j || r >= n || (q > col[j] && r <= rig.factor_.row[q - 1]))
        return Fail(err, ErrorCode::kBadValue, "factor entry %u (column %llu) has row %u out of order or range", q,
                    (unsigned long long)j, r);
    }
  }
  return true;
}

// The solve's row-major copy of L (from its validated columns: within a row,
// columns ascend) and its index arrays, 16 bits wide when they fit.
void RigLoader::BuildSolveRows(const Counts& c, const Scratch& scratch, Rig* rig_out) {
  Rig& rig = *rig_out;
  const std::uint64_t n = c.n, nnz = c.nnz;
  const auto& col = rig.factor_.col_start;
  std::uint32_t* row_start = scratch.row_start;
  std::memset(row_start, 0, (n + 1) * sizeof(std::uint32_t));
  for (std::uint64_t q = 0; q < nnz; ++q) ++row_start[rig.factor_.row[q] + 1];
  for (std::uint64_t i = 0; i < n; ++i) row_start[i + 1] += row_start[i];
  std::memcpy(scratch.row_fill, row_start, n * sizeof(std::uint32_t));
  for (std::uint64_t j = 0; j < n; ++j)
    for (std::uint32_t q = col[j]; q < col[j + 1]; ++q) {
      const std::uint32_t slot = scratch.row_fill[rig.factor_.row[q]]++;
      scratch.row_value[slot] = rig.factor_.value[q];
      if (scratch.narrow) {
        scratch.row_col2_16[slot] = std::uint16_t(2 * j);
        scratch.col_row2_16[q] = std::uint16_t(2 * rig.factor_.row[q]);
      } else {
        scratch.row_col2[slot] = 2 * std::uint32_t(j);
        scratch.col_row2[q] = 2 * rig.factor_.row[q];  // < 2n < 2^23: no overflow
      }
    }
  rig.factor_.row_start = {row_start, std::size_t(n + 1)};
  rig.factor_.row_value = {scratch.row_value, std::size_t(nnz)};
  if (scratch.narrow) {
    rig.factor_.row_col2_16 = {scratch.row_col2_16, std::size_t(nnz)};
    rig.factor_.col_row2_16 = {scratch.col_row2_16, std::size_t(nnz)};
  } else {
    rig.factor_.row_col2 = {scratch.row_col2, std::size_t(nnz)};
    rig.factor_.col_row2 = {scratch.col_row2, std::size_t(nnz)};
  }
}

// Blend blocks for the SIMD kernels: [block][pose][alpha, s11, s12, s22][lane];
// spare lanes of the last block are zero.
void RigLoader::BuildBlendBlocks(const Counts& c, const Scratch& scratch, Rig* rig) {
  const std::uint64_t T = c.T, N = c.N, blocks = scratch.blocks;
  double* blend = scratch.blend;
  std::memset(blend, 0, blocks * 4 * N * 8 * sizeof(double));
  for (std::uint64_t t = 0; t < T; ++t)
    for (std::uint64_t i = 0; i < N; ++i) {
      double* lane = blend + ((t / 8) * N + i) * 32 + t % 8;
      lane[0] = rig->angles_[t * N + i];
      lane[8] = rig->stretches_[(t * N + i) * 3];
      lane[16] = rig->stretches_[(t * N + i) * 3 + 1];
      lane[24] = rig->stretches_[(t * N + i) * 3 + 2];
    }
  rig->blend_blocks_ = {blend, std::size_t(blocks * 4 * N * 8)};
}

// Every number finite and within the format's limits.
bool RigLoader::CheckNumbers(const Rig& rig, Error* err) {
  for (std::size_t j = 0; j < rig.factor_.inv_diagonal.size; ++j)
    if (!(rig.factor_.inv_diagonal[j] > 0) || !(rig.factor_.inv_diagonal[j] <= fmt::kMaxMagnitude))
      return Fail(err, ErrorCode::kBadValue, "factor diagonal %llu is not positive and at most %g",
                  (unsigned long long)j, fmt::kMaxMagnitude);
  if (!CheckFinite(rig.pose_positions_, "pose positions", err) || !CheckFinite(rig.pose_points_, "pose points", err) ||
      !CheckFinite(rig.pose_centroids_, "pose centroids", err) ||
      !CheckFinite(rig.vertex_masses_, "vertex masses", err) || !CheckFinite(rig.gradients_, "gradients", err) ||
      !CheckFinite(rig.angles_, "angles", err, fmt::kMaxAngle) ||
      !CheckFinite(rig.stretches_, "stretches", err, fmt::kMaxStretch) ||
      !CheckFinite(rig.factor_.value, "factor values", err) ||
      !CheckFinite(rig.grid_.weights, "weight grid", err, fmt::kMaxGridWeight) ||
      !CheckFinite(rig.grid_.centre_weights, "weight grid centres", err, fmt::kMaxGridWeight) ||
      !CheckFinite(rig.canvases_, "canvases", err))
    return false;
  for (std::size_t i = 0; i < rig.canvases_.size; i += 4)
    if (rig.canvases_[i] < 0 || rig.canvases_[i + 1] < 0)
      return Fail(err, ErrorCode::kBadValue, "canvas of pose %zu has a negative size", i / 4);
  for (std::size_t i = 0; i < rig.uvs_.size; ++i)
    if (!std::isfinite(rig.uvs_[i])) return Fail(err, ErrorCode::kBadValue, "uv[%zu] is not finite", i);
  return true;
}

// The counts and geometry every accessor and job reads.
void RigLoader::Finish(const unsigned char* bytes, const Header& h, const Counts& c, const detail::KernelTable* kernels,
                       Rig* rig) {
  rig->vertex_count_ = c.meta.vertex_count;
  rig->triangle_count_ = c.meta.triangle_count;
  rig->pose_count_ = c.meta.pose_count;
  rig->path_count_ = c.meta.path_count;
  rig->grid_.origin_x = c.meta.grid_origin_x;
  rig->grid_.origin_y = c.meta.grid_origin_y;
  rig->grid_.cell = c.meta.grid_cell_size;
  rig->grid_.cells_x = c.meta.grid_cells_x;
  rig->grid_.cells_y = c.meta.grid_cells_y;
  rig->factor_.n = c.meta.vertex_count - 1;
  rig->default_sigma_ = c.meta.default_sigma;
  rig->texture_filter_ =
      (c.meta.flags & fmt::kMetaFlagNearestFilter) ? TextureFilter::kNearest : TextureFilter::kLinear;
  rig->rig_size_ = c.meta.rig_size;
  if (c.meta.flags & fmt::kMetaFlagDrawingFolder) rig->drawing_folder_ = rig->strings_[std::size_t(2 * c.N + c.P)];
  rig->part_strings_ =
      c.parts ? rig->strings_.subspan(std::size_t(c.strings - c.parts * (1 + c.N)), std::size_t(c.parts * (1 + c.N)))
              : Span<const StringView>{};
  rig->kernels_ = kernels;
  rig->checksum_ = ReadU32(bytes + fmt::kOffChecksum);
  rig->format_major_ = h.major;
  rig->format_minor_ = h.minor;
  rig->compact_encoding_ = c.compact;
}

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
  ch->C = ReadU32(p);
  ch->A = ReadU32(p + 4);
  if (ch->C < 2 || ch->C > fmt::kMaxChannels)
    return Fail(err, ch->C < 2 ? ErrorCode::kBadValue : ErrorCode::kTooLarge, "channel count %u outside 2..%u", ch->C,
                fmt::kMaxChannels);
  if (ch->A < 1 || ch->A > fmt::kMaxAttachments)
    return Fail(err, ch->A < 1 ? ErrorCode::kBadValue : ErrorCode::kTooLarge, "attachment count %u outside 1..%u",
                ch->A, fmt::kMaxAttachments);
  if (ReadU32(p + 8) != 0 || ReadU32(p + 12) != 0)
    return Fail(err, ErrorCode::kBadLayout, "CHAN's reserved header fields are not zero");
  std::uint64_t at = fmt::kChannelsHeaderSize + std::uint64_t(ch->A) * fmt::kAttachmentEntrySize;
  if (at > size) return Fail(err, ErrorCode::kBadLayout, "CHAN's %u attachment entries run past the section", ch->A);
  for (std::uint32_t k = 0; k < ch->C; ++k) {
    if (at + 4 > size) return Fail(err, ErrorCode::kBadLayout, "CHAN's channel names run past the section");
    const std::uint32_t n = ReadU32(p + at);
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
    const unsigned char* e = p + fmt::kChannelsHeaderSize + std::size_t(a) * fmt::kAttachmentEntrySize;
    Channels::Entry& entry = ch->entries[a];
    entry.channel = ReadU32(e);
    entry.parent_triangle = ReadU32(e + 4);
    entry.joint_triangle = ReadU32(e + 8);
    if (ReadU32(e + 12) != 0) return Fail(err, ErrorCode::kBadLayout, "attachment %u: reserved field is not zero", a);
    std::memcpy(entry.parent_weights, e + 16, 24);
    std::memcpy(entry.joint_weights, e + 40, 24);
    const std::uint64_t offset = ReadU64(e + 64);
    entry.size = ReadU64(e + 72);
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
    entry.bytes = p + offset;
    at = offset + entry.size;
    std::size_t needed = 0;
    ArenaSource size_only;
    size_only.kind = ArenaSource::kSizeOnly;
    size_only.needed = &needed;
    size_only.nested = true;
    Rig scratch;
    if (!Load(entry.bytes, std::size_t(entry.size), &scratch, err, options, size_only)) return NestedFail(err, a);
    entry.arena = needed;
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
    v.channel = ch.entries[a].channel;
    v.parent_triangle = ch.entries[a].parent_triangle;
    v.joint_triangle = ch.entries[a].joint_triangle;
    for (int k = 0; k < 3; ++k)
      v.parent_weights[k] = ch.entries[a].parent_weights[k], v.joint_weights[k] = ch.entries[a].joint_weights[k];
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
    if (!Load(ch.entries[a].bytes, std::size_t(ch.entries[a].size), &r, err, options, in_place))
      return NestedFail(err, a);
    const std::uint32_t k = ch.entries[a].channel;
    if (ch.entries[a].joint_triangle >= r.triangle_count_)
      return Fail(err, ErrorCode::kBadValue, "attachment %u: joint triangle %u of %u", a, ch.entries[a].joint_triangle,
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

bool ReadRigSections(const void* data, std::size_t size, RigSection* out, std::uint32_t capacity, std::uint32_t* count,
                     Error* err) {
  return RigLoader::ReadSections(data, size, out, capacity, count, err);
}

}  // namespace posemorph
