// SPDX-License-Identifier: MIT
// The arena: where it lives, how large it may be, and every span of the rig
// and every load-time buffer in one fixed order.
#include "loader.h"

#include <cstdint>
#include <new>

namespace posemorph {

using namespace detail::load;  // NOLINT(google-build-using-namespace): the loader's own types

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
  rig.solve_.order = {decoded.order, std::size_t(n)};
  rig.solve_.col_start = {decoded.factor.col_start, std::size_t(n + 1)};
  rig.solve_.row = {decoded.factor.row, std::size_t(nnz)};
  rig.solve_.value = {decoded.factor.value, std::size_t(nnz)};
  rig.solve_.inv_diagonal = {decoded.factor.inv_diagonal, std::size_t(n)};
  rig.grid_.weights = {decoded.grid_corners, std::size_t(grid_corners * N)};
  if (decoded.grid_centres) rig.grid_.centre_weights = {decoded.grid_centres, std::size_t(grid_centres * N)};
  if (affine_uvs)
    rig.uvs_ = {decoded.uvs, std::size_t(N * V * 2)};
  else if (has_uvs)
    rig.uvs_ = CopyInto<float>(arena, s.uvs, N * V * 2);
  // Scratch, used once at load.
  decoded.grid_scratch = arena.Take<std::int64_t>(grid_corners);
  decoded.seen = arena.Take<unsigned char>(n);
  decoded.position_codes = arena.Take<std::int64_t>(2 * V);
  decoded.neighbour_start = arena.Take<std::uint32_t>(V + 1);
  decoded.neighbour_fill = arena.Take<std::uint32_t>(V);
  decoded.neighbour_list = arena.Take<std::uint32_t>(3 * T);
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
  rig.solve_.order = CopyInto<std::uint32_t>(arena, s.perm, n);
  rig.solve_.col_start = CopyInto<std::uint32_t>(arena, s.lcol, n + 1);
  rig.solve_.row = CopyInto<std::uint32_t>(arena, s.lrow, nnz);
  rig.solve_.value = CopyInto<double>(arena, s.lval, nnz);
  rig.solve_.inv_diagonal = CopyInto<double>(arena, s.dinv, n);
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
  scratch->event_views = arena.Take<EventView>(c.events);
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
  scratch->row_fill = arena.Take<std::uint32_t>(n);  // scratch for the transpose, then CheckSolveBound
  scratch->solve_bound = arena.Take<double>(n);
  const std::uint64_t blocks = scratch->blocks = (T + 7) / 8;
  scratch->blend = arena.Take<double>(blocks * 4 * N * 8);
}

}  // namespace posemorph
