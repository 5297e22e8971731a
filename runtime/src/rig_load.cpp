// SPDX-License-Identifier: MIT
// LoadRig: every byte is hostile. Each count is bounded before it sizes
// anything, each section's size must equal what the counts imply, each index
// is range-checked and each number must be finite, so that a Rig that loads is
// one every job can evaluate without further checks.
#include <cmath>
#include <cstdarg>
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

}  // namespace

Rig::Rig() = default;
Rig::~Rig() = default;
// A moved-from rig is empty (loaded() false, every span empty), never a
// view into the arena its new owner holds.
Rig::Rig(Rig&& other) noexcept { *this = std::move(other); }

Rig& Rig::operator=(Rig&& other) noexcept {
  if (this == &other) return *this;
  arena_ = std::move(other.arena_);
  arena_size_ = std::exchange(other.arena_size_, 0);
  vertex_count_ = std::exchange(other.vertex_count_, 0);
  triangle_count_ = std::exchange(other.triangle_count_, 0);
  pose_count_ = std::exchange(other.pose_count_, 0);
  path_count_ = std::exchange(other.path_count_, 0);
  triangles_ = std::exchange(other.triangles_, {});
  pose_positions_ = std::exchange(other.pose_positions_, {});
  pose_points_ = std::exchange(other.pose_points_, {});
  pose_centroids_ = std::exchange(other.pose_centroids_, {});
  vertex_masses_ = std::exchange(other.vertex_masses_, {});
  gradients_ = std::exchange(other.gradients_, {});
  angles_ = std::exchange(other.angles_, {});
  stretches_ = std::exchange(other.stretches_, {});
  blend_blocks_ = std::exchange(other.blend_blocks_, {});
  uvs_ = std::exchange(other.uvs_, {});
  canvases_ = std::exchange(other.canvases_, {});
  strings_ = std::exchange(other.strings_, {});
  paths_ = std::exchange(other.paths_, {});
  grid_ = std::exchange(other.grid_, {});
  factor_ = std::exchange(other.factor_, {});
  default_sigma_ = std::exchange(other.default_sigma_, 0);
  texture_filter_ = std::exchange(other.texture_filter_, TextureFilter::kLinear);
  rig_size_ = std::exchange(other.rig_size_, 0);
  kernels_ = std::exchange(other.kernels_, nullptr);
  checksum_ = std::exchange(other.checksum_, 0);
  format_major_ = std::exchange(other.format_major_, 0);
  format_minor_ = std::exchange(other.format_minor_, 0);
  return *this;
}

Isa Rig::isa() const { return kernels_ ? kernels_->isa : Isa::kAuto; }

Span<const double> Rig::pose_positions(std::uint32_t pose) const {
  if (pose >= pose_count_) return {};
  return pose_positions_.subspan(std::size_t(pose) * 2 * vertex_count_, 2 * std::size_t(vertex_count_));
}

Span<const float> Rig::uvs(std::uint32_t pose) const {
  if (pose >= pose_count_ || uvs_.empty()) return {};
  return uvs_.subspan(std::size_t(pose) * 2 * vertex_count_, 2 * std::size_t(vertex_count_));
}

StringView Rig::pose_name(std::uint32_t pose) const { return pose < pose_count_ ? strings_[pose] : StringView{}; }

StringView Rig::pose_image(std::uint32_t pose) const {
  return pose < pose_count_ ? strings_[pose_count_ + pose] : StringView{};
}

DrawingCanvas Rig::pose_canvas(std::uint32_t pose) const {
  if (pose >= pose_count_ || canvases_.empty()) return {};
  const double* c = canvases_.data + 4 * std::size_t(pose);
  return {c[0], c[1], c[2], c[3]};
}

PathView Rig::path(std::uint32_t index) const { return index < path_count_ ? paths_[index] : PathView{}; }

int Rig::FindPath(const char* name) const {
  if (!name) return -1;
  const std::size_t n = std::strlen(name);
  for (std::uint32_t i = 0; i < path_count_; ++i)
    if (paths_[i].name.size == n && std::memcmp(paths_[i].name.data, name, n) == 0) return int(i);
  return -1;
}

namespace {

// Where the arena comes from: one allocation (LoadRig), the caller's memory
// (LoadRigInPlace), or nowhere, when only its size is wanted (RigMemorySize).
struct ArenaSource {
  enum Kind { kAllocate, kCaller, kSizeOnly } kind = kAllocate;
  void* memory = nullptr;
  std::size_t memory_size = 0;
  std::size_t* needed = nullptr;
};

}  // namespace

// The one loader behind LoadRig, RigMemorySize and LoadRigInPlace (a friend of Rig).
struct RigLoader {
  static bool Load(const void* data, std::size_t size, Rig* out, Error* err, const LoadOptions& options,
                   const ArenaSource& source);
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

  // Header.
  if (size < fmt::kHeaderSize)
    return Fail(err, ErrorCode::kTruncated, "%zu bytes is shorter than the %u-byte header", size, fmt::kHeaderSize);
  if (std::memcmp(bytes, fmt::kMagic, sizeof(fmt::kMagic)) != 0)
    return Fail(err, ErrorCode::kBadMagic, "not a posemorph rig (bad magic)");
  const std::uint16_t major = ReadU16(bytes + fmt::kOffVersionMajor);
  if (major != fmt::kVersionMajor)
    return Fail(err, ErrorCode::kBadVersion, "format version %u.%u; this runtime reads %u.x", major,
                ReadU16(bytes + fmt::kOffVersionMinor), fmt::kVersionMajor);
  if (ReadU32(bytes + fmt::kOffHeaderSize) != fmt::kHeaderSize)
    return Fail(err, ErrorCode::kBadLayout, "header size field is %u, expected %u",
                ReadU32(bytes + fmt::kOffHeaderSize), fmt::kHeaderSize);
  const std::uint64_t file_size = ReadU64(bytes + fmt::kOffFileSize);
  if (file_size > size)
    return Fail(err, ErrorCode::kTruncated, "header says %llu bytes, only %zu given", (unsigned long long)file_size,
                size);
  if (file_size < size)
    return Fail(err, ErrorCode::kBadLayout, "header says %llu bytes, %zu given (trailing bytes)",
                (unsigned long long)file_size, size);
  if (ReadU32(bytes + fmt::kOffFlags) != 0)
    return Fail(err, ErrorCode::kBadVersion, "unknown header flags 0x%x", ReadU32(bytes + fmt::kOffFlags));
  for (std::uint32_t i = fmt::kOffChecksum + 4; i < fmt::kHeaderSize; ++i)
    if (bytes[i] != 0) return Fail(err, ErrorCode::kBadLayout, "reserved header byte %u is not zero", i);
  const std::uint32_t section_count = ReadU32(bytes + fmt::kOffSectionCount);
  if (section_count == 0 || section_count > fmt::kMaxSections)
    return Fail(err, ErrorCode::kBadLayout, "section count %u outside 1..%u", section_count, fmt::kMaxSections);
  const std::uint64_t table_end = fmt::kHeaderSize + std::uint64_t(section_count) * fmt::kSectionEntrySize;
  if (table_end > size) return Fail(err, ErrorCode::kTruncated, "section table runs past the end");
  if (options.verify_checksum) {
    const std::uint32_t stored = ReadU32(bytes + fmt::kOffChecksum);
    const std::uint32_t actual = fmt::Crc32(bytes + fmt::kHeaderSize, size - fmt::kHeaderSize);
    if (stored != actual)
      return Fail(err, ErrorCode::kBadChecksum, "checksum mismatch (stored %08x, computed %08x)", stored, actual);
  }

  // Section table: in bounds, aligned, after the table, no two overlapping.
  Parser parser{bytes, size, {}, err};
  for (std::uint32_t i = 0; i < section_count; ++i) {
    const unsigned char* e = bytes + fmt::kHeaderSize + std::size_t(i) * fmt::kSectionEntrySize;
    Section s{ReadU32(e), ReadU64(e + 8), ReadU64(e + 16)};
    char name[5];
    TagName(s.tag, name);
    if (ReadU32(e + 4) != 0) return Fail(err, ErrorCode::kBadLayout, "section %s: reserved field set", name);
    if (s.offset < table_end || s.offset > size || s.size > size - s.offset)
      return Fail(err, ErrorCode::kBadLayout, "section %s lies outside the file", name);
    if (s.offset % fmt::kSectionAlignment != 0)
      return Fail(err, ErrorCode::kBadLayout, "section %s is misaligned", name);
    for (std::uint32_t j = 0; j < parser.table.count; ++j) {
      const Section& o = parser.table.entries[j];
      if (o.tag == s.tag) return Fail(err, ErrorCode::kBadLayout, "section %s appears twice", name);
      if (s.offset < o.offset + o.size && o.offset < s.offset + s.size)
        return Fail(err, ErrorCode::kBadLayout, "section %s overlaps another", name);
    }
    parser.table.entries[parser.table.count++] = s;
  }

  // META: counts, bounded before they size anything.
  const unsigned char* p = nullptr;
  if (!parser.Get(fmt::kMeta, fmt::kMetaSize, &p)) return false;
  fmt::Meta meta;
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
       ~(fmt::kMetaFlagHasUVs | fmt::kMetaFlagGridCentres | fmt::kMetaFlagCompact | fmt::kMetaFlagNearestFilter)) != 0)
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
  const std::uint64_t n = V - 1;
  const std::uint64_t grid_corners = std::uint64_t(meta.grid_cells_x + 1) * (meta.grid_cells_y + 1);
  const std::uint64_t grid_centres =
      (meta.flags & fmt::kMetaFlagGridCentres) ? std::uint64_t(meta.grid_cells_x) * meta.grid_cells_y : 0;
  const std::uint64_t grid_vertices = grid_corners + grid_centres;
  const bool has_uvs = (meta.flags & fmt::kMetaFlagHasUVs) != 0;

  const bool compact = (meta.flags & fmt::kMetaFlagCompact) != 0;

  // Sections with sizes implied by the counts.
  const unsigned char *tris = nullptr, *poses = nullptr, *points, *cents = nullptr, *masses = nullptr, *grads = nullptr,
                      *angles = nullptr, *shears = nullptr, *perm = nullptr, *lcol = nullptr, *lrow = nullptr,
                      *lval = nullptr, *dinv = nullptr, *wgrid = nullptr, *uvs = nullptr, *paths, *strs, *pkeys;
  if (!compact &&
      (!parser.Get(fmt::kTriangles, T * 12, &tris) || !parser.Get(fmt::kPosePositions, N * V * 16, &poses) ||
       !parser.Get(fmt::kPoseCentroids, N * 16, &cents) || !parser.Get(fmt::kVertexMasses, V * 8, &masses) ||
       !parser.Get(fmt::kGradients, T * 48, &grads) || !parser.Get(fmt::kAngles, T * N * 8, &angles) ||
       !parser.Get(fmt::kStretches, T * N * 24, &shears) || !parser.Get(fmt::kPermutation, n * 4, &perm) ||
       !parser.Get(fmt::kFactorColumns, (n + 1) * 4, &lcol) || !parser.Get(fmt::kFactorRows, nnz * 4, &lrow) ||
       !parser.Get(fmt::kFactorValues, nnz * 8, &lval) || !parser.Get(fmt::kFactorInvDiagonal, n * 8, &dinv) ||
       !parser.Get(fmt::kWeightGrid, grid_vertices * N * 8, &wgrid)))
    return false;
  if (!parser.Get(fmt::kPosePoints, N * 16, &points) || !parser.Get(fmt::kPaths, P * fmt::kPathEntrySize, &paths))
    return false;
  detail::CompactLayout packed;
  const detail::CompactCounts packed_counts{
      V, T, N, n, nnz, meta.grid_cells_x, meta.grid_cells_y, grid_centres > 0, file_size};
  bool affine_uvs = false;
  if (compact) {
    auto bytes_of = [&](std::uint32_t tag) {
      const Section* s = parser.table.Find(tag);
      return s ? detail::SectionBytes{bytes + s->offset, s->size} : detail::SectionBytes{};
    };
    if (!detail::ReadCompactLayout(bytes_of(fmt::kQuantPositions), bytes_of(fmt::kQuantTriangles),
                                   bytes_of(fmt::kQuantPermutation), bytes_of(fmt::kQuantTurns),
                                   bytes_of(fmt::kQuantGrid), bytes_of(fmt::kAffineUVs), packed_counts, &packed, err))
      return false;
    affine_uvs = packed.has_affine_uvs;
    if (affine_uvs && !has_uvs) return Fail(err, ErrorCode::kBadLayout, "QUVA section present but META says no uvs");
    if (affine_uvs && parser.table.Find(fmt::kUVs))
      return Fail(err, ErrorCode::kBadLayout, "both QUVA and UVS present; a rig stores its uvs once");
  }
  if (has_uvs && !affine_uvs && !parser.Get(fmt::kUVs, N * V * 8, &uvs)) return false;
  const unsigned char* canvases = nullptr;
  if (parser.table.Find(fmt::kCanvases) && !parser.Get(fmt::kCanvases, N * 32, &canvases)) return false;
  if (!has_uvs && parser.table.Find(fmt::kUVs))
    return Fail(err, ErrorCode::kBadLayout, "UVS section present but META says none");
  std::uint64_t key_total = 0;
  for (std::uint64_t i = 0; i < P; ++i) {
    const std::uint32_t keys = ReadU32(paths + i * fmt::kPathEntrySize);
    const std::uint32_t flags = ReadU32(paths + i * fmt::kPathEntrySize + 4);
    if (keys < 1) return Fail(err, ErrorCode::kBadValue, "path %llu has no keys", (unsigned long long)i);
    if ((flags & ~(fmt::kPathFlagLoop | (0xFFu << fmt::kPathInterpolationShift))) != 0 ||
        (flags >> fmt::kPathInterpolationShift) > std::uint32_t(PathInterpolation::kCatmullRom))
      return Fail(err, ErrorCode::kBadValue, "path %llu has unknown flags 0x%x", (unsigned long long)i, flags);
    key_total += keys;
    if (key_total > fmt::kMaxPathKeys)
      return Fail(err, ErrorCode::kTooLarge, "paths hold more than %u keys", fmt::kMaxPathKeys);
  }
  if (!parser.Get(fmt::kPathKeys, key_total * 24, &pkeys)) return false;
  const Section* strings_section = parser.table.Find(fmt::kStrings);
  if (!strings_section) return Fail(err, ErrorCode::kBadLayout, "missing section STRS");
  if (strings_section->size > fmt::kMaxStringBytes)
    return Fail(err, ErrorCode::kTooLarge, "string table above %u bytes", fmt::kMaxStringBytes);
  strs = bytes + strings_section->offset;
  const std::uint64_t string_count = 2 * N + P;

  // Two passes over one layout: size the arena, then fill it.
  Rig rig;
  for (int pass = 0; pass < 2; ++pass) {
    ArenaLayout arena;
    if (pass == 1 && source.kind == ArenaSource::kAllocate) {
      rig.arena_.reset(new (std::nothrow) unsigned char[rig.arena_size_]);
      if (!rig.arena_) return Fail(err, ErrorCode::kOutOfMemory, "cannot allocate %zu bytes", rig.arena_size_);
      arena.base = rig.arena_.get();
    } else if (pass == 1) {
      if (!source.memory)
        return Fail(err, ErrorCode::kInvalidArgument, "no memory given (the rig needs %zu bytes)", rig.arena_size_);
      if (reinterpret_cast<std::uintptr_t>(source.memory) % kRigMemoryAlignment != 0)
        return Fail(err, ErrorCode::kInvalidArgument, "memory is not aligned to %zu bytes",
                    std::size_t(kRigMemoryAlignment));
      if (source.memory_size < rig.arena_size_)
        return Fail(err, ErrorCode::kInvalidArgument, "%zu bytes of memory given, the rig needs %zu",
                    source.memory_size, rig.arena_size_);
      arena.base = static_cast<unsigned char*>(source.memory);
    }
    detail::CompactOutputs decoded{};
    if (compact) {
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
      rig.pose_points_ = CopyInto<double>(arena, points, N * 2);
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
        rig.uvs_ = CopyInto<float>(arena, uvs, N * V * 2);
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
    } else {
      rig.triangles_ = CopyInto<std::uint32_t>(arena, tris, T * 3);
      rig.pose_positions_ = CopyInto<double>(arena, poses, N * V * 2);
      rig.pose_points_ = CopyInto<double>(arena, points, N * 2);
      rig.pose_centroids_ = CopyInto<double>(arena, cents, N * 2);
      rig.vertex_masses_ = CopyInto<double>(arena, masses, V);
      rig.gradients_ = CopyInto<double>(arena, grads, T * 6);
      rig.angles_ = CopyInto<double>(arena, angles, T * N);
      rig.stretches_ = CopyInto<double>(arena, shears, T * N * 3);
      rig.factor_.order = CopyInto<std::uint32_t>(arena, perm, n);
      rig.factor_.col_start = CopyInto<std::uint32_t>(arena, lcol, n + 1);
      rig.factor_.row = CopyInto<std::uint32_t>(arena, lrow, nnz);
      rig.factor_.value = CopyInto<double>(arena, lval, nnz);
      rig.factor_.inv_diagonal = CopyInto<double>(arena, dinv, n);
      const Span<const double> grid_all = CopyInto<double>(arena, wgrid, grid_vertices * N);
      rig.grid_.weights = {grid_all.data, std::size_t(grid_corners * N)};
      if (grid_centres && grid_all.data)  // (null while the arena is only being measured)
        rig.grid_.centre_weights = grid_all.subspan(std::size_t(grid_corners * N), std::size_t(grid_centres * N));
      if (has_uvs) rig.uvs_ = CopyInto<float>(arena, uvs, N * V * 2);
    }
    if (canvases) rig.canvases_ = CopyInto<double>(arena, canvases, N * 4);
    const Span<const char> chars = CopyInto<char>(arena, strs, strings_section->size);
    StringView* strings = arena.Take<StringView>(string_count);
    PathView* path_views = arena.Take<PathView>(P);
    const Span<const double> keys = CopyInto<double>(arena, pkeys, key_total * 3);
    unsigned char* seen = arena.Take<unsigned char>(n);  // scratch for the permutation check
    std::uint32_t* row_start = arena.Take<std::uint32_t>(n + 1);
    // Index arrays for the solve: 16 bits wide when they fit, else 32.
    const bool narrow = 2 * n < 65536 && !options.wide_solve_indices;
    std::uint32_t* row_col2 = arena.Take<std::uint32_t>(narrow ? 0 : nnz);
    std::uint32_t* col_row2 = arena.Take<std::uint32_t>(narrow ? 0 : nnz);
    std::uint16_t* row_col2_16 = arena.Take<std::uint16_t>(narrow ? nnz : 0);
    std::uint16_t* col_row2_16 = arena.Take<std::uint16_t>(narrow ? nnz : 0);
    double* row_value = arena.Take<double>(nnz);
    std::uint32_t* row_fill = arena.Take<std::uint32_t>(n);  // scratch for the transpose
    const std::uint64_t blocks = (T + 7) / 8;
    double* blend = arena.Take<double>(blocks * 4 * N * 8);
    if (pass == 0) {
      // A compact rig expands at load; bound how far, so that a small hostile
      // file cannot claim a huge arena (legitimate rigs expand 10-30x).
      if (compact && arena.used > fmt::kMaxCompactExpansion * file_size + (std::uint64_t(1) << 20))
        return Fail(err, ErrorCode::kTooLarge,
                    "a compact rig of %llu bytes would need %llu bytes in memory (at most %u times its size)",
                    (unsigned long long)file_size, (unsigned long long)arena.used, fmt::kMaxCompactExpansion);
      if (arena.used > std::uint64_t(SIZE_MAX / 2))
        return Fail(err, ErrorCode::kTooLarge, "the rig needs %llu bytes in memory, more than this target addresses",
                    (unsigned long long)arena.used);
      rig.arena_size_ = std::size_t(arena.used);
      if (source.kind == ArenaSource::kSizeOnly) {
        *source.needed = rig.arena_size_;
        return true;
      }
      continue;
    }
    if (compact && !detail::DecodeCompact(packed, packed_counts, decoded, err)) return false;

    // Strings: u32 length + bytes, one after another, exactly filling STRS.
    std::uint64_t at = 0;
    for (std::uint64_t i = 0; i < string_count; ++i) {
      if (chars.size - at < 4)
        return Fail(err, ErrorCode::kBadValue, "string table truncated at string %llu", (unsigned long long)i);
      const std::uint32_t len = ReadU32(reinterpret_cast<const unsigned char*>(chars.data + at));
      at += 4;
      if (len > chars.size - at)
        return Fail(err, ErrorCode::kBadValue, "string %llu runs past the string table", (unsigned long long)i);
      strings[i] = StringView{chars.data + at, len};
      at += len;
    }
    if (at != chars.size) return Fail(err, ErrorCode::kBadValue, "string table has trailing bytes");
    rig.strings_ = {strings, std::size_t(string_count)};

    // Paths: finite keys, strictly increasing times.
    std::uint64_t key_at = 0;
    for (std::uint64_t i = 0; i < P; ++i) {
      const std::uint32_t count = ReadU32(paths + i * fmt::kPathEntrySize);
      const std::uint32_t flags = ReadU32(paths + i * fmt::kPathEntrySize + 4);
      PathView& view = path_views[i];
      view.name = strings[2 * N + i];
      view.loop = (flags & fmt::kPathFlagLoop) != 0;
      view.interpolation = PathInterpolation(flags >> fmt::kPathInterpolationShift);
      view.keys = keys.subspan(std::size_t(key_at * 3), std::size_t(count) * 3);
      key_at += count;
      if (!CheckFinite(view.keys, "path key", err, fmt::kMaxPathValue)) return false;
      for (std::uint32_t k = 1; k < count; ++k)
        if (!(view.keys[3 * k] > view.keys[3 * (k - 1)]))
          return Fail(err, ErrorCode::kBadValue, "path %llu: key times not strictly increasing at key %u",
                      (unsigned long long)i, k);
    }
    rig.paths_ = {path_views, std::size_t(P)};

    // Indices.
    for (std::uint64_t t = 0; t < T; ++t) {
      const std::uint32_t a = rig.triangles_[3 * t], b = rig.triangles_[3 * t + 1], c = rig.triangles_[3 * t + 2];
      if (a >= V || b >= V || c >= V)
        return Fail(err, ErrorCode::kBadValue, "triangle %llu has a vertex index >= %llu", (unsigned long long)t,
                    (unsigned long long)V);
      if (a == b || b == c || a == c)
        return Fail(err, ErrorCode::kBadValue, "triangle %llu repeats a vertex", (unsigned long long)t);
    }
    std::memset(seen, 0, n);
    for (std::uint64_t k = 0; k < n; ++k) {
      const std::uint32_t v = rig.factor_.order[k];
      if (v >= n || seen[v])
        return Fail(err, ErrorCode::kBadValue, "permutation is not a permutation (entry %llu)", (unsigned long long)k);
      seen[v] = 1;
    }
    // L strictly lower, columns in order, rows increasing within a column: the
    // triangular solves then touch only rows j < i < n.
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
    // Rows of L from its (now validated) columns: within a row, columns ascend.
    std::memset(row_start, 0, (n + 1) * sizeof(std::uint32_t));
    for (std::uint64_t q = 0; q < nnz; ++q) ++row_start[rig.factor_.row[q] + 1];
    for (std::uint64_t i = 0; i < n; ++i) row_start[i + 1] += row_start[i];
    std::memcpy(row_fill, row_start, n * sizeof(std::uint32_t));
    for (std::uint64_t j = 0; j < n; ++j)
      for (std::uint32_t q = col[j]; q < col[j + 1]; ++q) {
        const std::uint32_t slot = row_fill[rig.factor_.row[q]]++;
        row_value[slot] = rig.factor_.value[q];
        if (narrow) {
          row_col2_16[slot] = std::uint16_t(2 * j);
          col_row2_16[q] = std::uint16_t(2 * rig.factor_.row[q]);
        } else {
          row_col2[slot] = 2 * std::uint32_t(j);
          col_row2[q] = 2 * rig.factor_.row[q];  // < 2n < 2^23: no overflow
        }
      }
    // Blend blocks: [block][pose][alpha, s11, s12, s22][lane]; spare lanes of
    // the last block are zero.
    std::memset(blend, 0, blocks * 4 * N * 8 * sizeof(double));
    for (std::uint64_t t = 0; t < T; ++t)
      for (std::uint64_t i = 0; i < N; ++i) {
        double* lane = blend + ((t / 8) * N + i) * 32 + t % 8;
        lane[0] = rig.angles_[t * N + i];
        lane[8] = rig.stretches_[(t * N + i) * 3];
        lane[16] = rig.stretches_[(t * N + i) * 3 + 1];
        lane[24] = rig.stretches_[(t * N + i) * 3 + 2];
      }
    rig.blend_blocks_ = {blend, std::size_t(blocks * 4 * N * 8)};
    rig.factor_.row_start = {row_start, std::size_t(n + 1)};
    rig.factor_.row_value = {row_value, std::size_t(nnz)};
    if (narrow) {
      rig.factor_.row_col2_16 = {row_col2_16, std::size_t(nnz)};
      rig.factor_.col_row2_16 = {col_row2_16, std::size_t(nnz)};
    } else {
      rig.factor_.row_col2 = {row_col2, std::size_t(nnz)};
      rig.factor_.col_row2 = {col_row2, std::size_t(nnz)};
    }
    for (std::uint64_t j = 0; j < n; ++j)
      if (!(rig.factor_.inv_diagonal[j] > 0) || !std::isfinite(rig.factor_.inv_diagonal[j]))
        return Fail(err, ErrorCode::kBadValue, "factor diagonal %llu is not positive and finite",
                    (unsigned long long)j);

    // Numbers.
    if (!CheckFinite(rig.pose_positions_, "pose positions", err) ||
        !CheckFinite(rig.pose_points_, "pose points", err) ||
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
  }

  rig.vertex_count_ = meta.vertex_count;
  rig.triangle_count_ = meta.triangle_count;
  rig.pose_count_ = meta.pose_count;
  rig.path_count_ = meta.path_count;
  rig.grid_.origin_x = meta.grid_origin_x;
  rig.grid_.origin_y = meta.grid_origin_y;
  rig.grid_.cell = meta.grid_cell_size;
  rig.grid_.cells_x = meta.grid_cells_x;
  rig.grid_.cells_y = meta.grid_cells_y;
  rig.factor_.n = meta.vertex_count - 1;
  rig.default_sigma_ = meta.default_sigma;
  rig.texture_filter_ = (meta.flags & fmt::kMetaFlagNearestFilter) ? TextureFilter::kNearest : TextureFilter::kLinear;
  rig.rig_size_ = meta.rig_size;
  rig.kernels_ = kernels;
  rig.checksum_ = ReadU32(bytes + fmt::kOffChecksum);
  rig.format_major_ = major;
  rig.format_minor_ = ReadU16(bytes + fmt::kOffVersionMinor);
  *out = std::move(rig);
  return true;
}

const char* ErrorCodeName(ErrorCode code) {
  switch (code) {
    case ErrorCode::kOk:
      return "ok";
    case ErrorCode::kInvalidArgument:
      return "invalid argument";
    case ErrorCode::kTruncated:
      return "truncated";
    case ErrorCode::kBadMagic:
      return "bad magic";
    case ErrorCode::kBadVersion:
      return "unsupported version";
    case ErrorCode::kBadChecksum:
      return "bad checksum";
    case ErrorCode::kBadLayout:
      return "bad layout";
    case ErrorCode::kBadValue:
      return "bad value";
    case ErrorCode::kTooLarge:
      return "too large";
    case ErrorCode::kOutOfMemory:
      return "out of memory";
    case ErrorCode::kUnsupportedIsa:
      return "unsupported code path";
  }
  return "unknown";
}

}  // namespace posemorph
