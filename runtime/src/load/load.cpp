// SPDX-License-Identifier: MIT
// LoadRig, RigMemorySize, LoadRigInPlace and ReadRigSections: the loader's
// entry points, and Load, which runs its steps in order (loader.h).
#include "loader.h"

#include <cstdint>
#include <utility>

#include "../isa_select.h"

#if defined(_MSC_VER) && !defined(__clang__)
// MSVC targets (x86, x64, ARM64) are little-endian.
#elif !defined(__BYTE_ORDER__) || __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "posemorph's loader copies the little-endian array sections directly; port CopyInto (loader.h) first"
#endif

namespace posemorph {

using namespace detail::load;  // NOLINT(google-build-using-namespace): the loader's own types

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
  const LoadLimits& limits = options.limits;
  if (!source.nested && limits.max_bytes && size > limits.max_bytes)
    return Fail(err, ErrorCode::kTooLarge, "the file is %zu bytes, above the limit of %llu (LoadLimits::max_bytes)",
                size, (unsigned long long)limits.max_bytes);

  Header h;
  if (!ReadHeader(bytes, size, options, &h, err)) return false;
  Parser parser{bytes, size, {}, err};
  if (!ReadSectionTable(bytes, size, h, &parser, err)) return false;
  Counts c;
  if (!ReadCounts(parser, &c, err) || !CheckLimits(c, limits, err)) return false;
  if (source.vertices) *source.vertices = c.V;
  if (source.nonzeros) *source.nonzeros = c.nnz;
  Sources s;
  if (!FindSections(bytes, h, parser, c, &s, err)) return false;
  Channels channels;
  if (!ReadChannels(bytes, parser, c, options, source.nested, &channels, err)) return false;
  if (limits.max_attachments && channels.A > limits.max_attachments)
    return Fail(err, ErrorCode::kTooLarge, "%u attachments, above the limit of %u (LoadLimits::max_attachments)",
                channels.A, limits.max_attachments);
  if (channels.A && !CheckCharacterLimits(c, limits, channels, err)) return false;
  Machine machine;
  if (!ReadMachine(bytes, parser, source.nested, channels.C, &machine, err)) return false;
  Atlas atlas;
  if (!ReadAtlas(bytes, parser, c, s, &atlas, err)) return false;

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
    LayoutMachine(arena, machine, &rig);
    LayoutAtlas(arena, c, atlas, &rig);
    if (pass == 0) {
      if (arena.used > std::uint64_t(SIZE_MAX / 2))
        return Fail(err, ErrorCode::kTooLarge, "the rig needs %llu bytes in memory, more than this target addresses",
                    (unsigned long long)arena.used);
      if (!source.nested && limits.max_memory && arena.used > limits.max_memory)
        return Fail(err, ErrorCode::kTooLarge,
                    "the rig needs %llu bytes in memory, above the limit of %llu (LoadLimits::max_memory)",
                    (unsigned long long)arena.used, (unsigned long long)limits.max_memory);
      rig.arena_size_ = std::size_t(arena.used);
      if (source.kind == ArenaSource::kSizeOnly) {
        *source.needed = rig.arena_size_;
        return true;
      }
    }
  }
  if (c.compact && !detail::DecodeCompact(s.packed, s.packed_counts, scratch.decoded, err)) return false;
  if (!ReadStrings(c, scratch, &rig, err) || !ReadPaths(c, s, scratch, &rig, err) ||
      !ReadEvents(c, s, scratch, &rig, err) || !CheckIndices(c, scratch, rig, err) || !CheckFactor(c, rig, err) ||
      !ReadParts(c, scratch, &rig, err))
    return false;
  BuildSolveRows(c, scratch, &rig);
  BuildBlendBlocks(c, scratch, &rig);
  if (!CheckNumbers(rig, err) || (options.bound_solve && !CheckSolveBound(c, scratch, rig, err))) return false;
  Finish(h, c, kernels, &rig);
  FillPages(atlas, &rig);
  if (!ReadPlacement(s, source.nested, &rig, err)) return false;
  if (channels.A && !LoadAttachments(channels, options, nested, nested_memory, &rig, err)) return false;
  if (machine.present && !CheckMachinePaths(rig, err)) return false;
  *out = std::move(rig);
  return true;
}

// One pose space's counts against the bounds (each attachment's too, as it loads).
bool RigLoader::CheckLimits(const Counts& c, const LoadLimits& limits, Error* err) {
  if (limits.max_vertices && c.V > limits.max_vertices)
    return Fail(err, ErrorCode::kTooLarge, "%llu vertices, above the limit of %u (LoadLimits::max_vertices)",
                (unsigned long long)c.V, limits.max_vertices);
  if (limits.max_poses && c.N > limits.max_poses)
    return Fail(err, ErrorCode::kTooLarge, "%llu poses, above the limit of %u (LoadLimits::max_poses)",
                (unsigned long long)c.N, limits.max_poses);
  if (limits.max_factor_nonzeros && c.nnz > limits.max_factor_nonzeros)
    return Fail(err, ErrorCode::kTooLarge,
                "a factor of %llu nonzeros, above the limit of %llu "
                "(LoadLimits::max_factor_nonzeros)",
                (unsigned long long)c.nnz, (unsigned long long)limits.max_factor_nonzeros);
  std::uint64_t bits = 1;  // ceil(log2 V), at least 1
  while (bits < 63 && (std::uint64_t(1) << bits) < c.V) ++bits;
  if (limits.max_fill && c.nnz > std::uint64_t(limits.max_fill) * c.V * bits)
    return Fail(err, ErrorCode::kTooLarge,
                "a factor of %llu nonzeros for %llu vertices, above %u x V x log2 V (LoadLimits::max_fill): "
                "a fill-reducing order the bake does not write",
                (unsigned long long)c.nnz, (unsigned long long)c.V, limits.max_fill);
  return true;
}

// A character's totals: the body's vertices and factor with its attachments'.
bool RigLoader::CheckCharacterLimits(const Counts& c, const LoadLimits& limits, const Channels& ch, Error* err) {
  const std::uint64_t vertices = c.V + ch.vertices, nonzeros = c.nnz + ch.nonzeros;
  if (limits.max_vertices && vertices > limits.max_vertices)
    return Fail(err, ErrorCode::kTooLarge,
                "%llu vertices with the attachments', above the limit of %u (LoadLimits::max_vertices)",
                (unsigned long long)vertices, limits.max_vertices);
  if (limits.max_factor_nonzeros && nonzeros > limits.max_factor_nonzeros)
    return Fail(err, ErrorCode::kTooLarge,
                "factors of %llu nonzeros with the attachments', above the limit of %llu "
                "(LoadLimits::max_factor_nonzeros)",
                (unsigned long long)nonzeros, (unsigned long long)limits.max_factor_nonzeros);
  return true;
}

bool ReadRigSections(const void* data, std::size_t size, RigSection* out, std::uint32_t capacity, std::uint32_t* count,
                     Error* err) {
  return RigLoader::ReadSections(data, size, out, capacity, count, err);
}

}  // namespace posemorph
