// SPDX-License-Identifier: MIT
// What the kernels read, built at load from the validated arrays: the
// solve's row-major copy of L, the SIMD blend blocks, and the counts.
#include "loader.h"

#include <cstring>

namespace posemorph {

using namespace detail::load;  // NOLINT(google-build-using-namespace): the loader's own types

// The solve's row-major copy of L (from its validated columns: within a row,
// columns ascend) and its index arrays, 16 bits wide when they fit.
void RigLoader::BuildSolveRows(const Counts& c, const Scratch& scratch, Rig* rig_out) {
  Rig& rig = *rig_out;
  const std::uint64_t n = c.n, nnz = c.nnz;
  const auto& col = rig.solve_.col_start;
  std::uint32_t* row_start = scratch.row_start;
  std::memset(row_start, 0, (n + 1) * sizeof(std::uint32_t));
  for (std::uint64_t q = 0; q < nnz; ++q) ++row_start[rig.solve_.row[q] + 1];
  for (std::uint64_t i = 0; i < n; ++i) row_start[i + 1] += row_start[i];
  std::memcpy(scratch.row_fill, row_start, n * sizeof(std::uint32_t));
  for (std::uint64_t j = 0; j < n; ++j)
    for (std::uint32_t q = col[j]; q < col[j + 1]; ++q) {
      const std::uint32_t slot = scratch.row_fill[rig.solve_.row[q]]++;
      scratch.row_value[slot] = rig.solve_.value[q];
      if (scratch.narrow) {
        scratch.row_col2_16[slot] = std::uint16_t(2 * j);
        scratch.col_row2_16[q] = std::uint16_t(2 * rig.solve_.row[q]);
      } else {
        scratch.row_col2[slot] = 2 * std::uint32_t(j);
        scratch.col_row2[q] = 2 * rig.solve_.row[q];  // < 2n < 2^23: no overflow
      }
    }
  rig.solve_.row_start = {row_start, std::size_t(n + 1)};
  rig.solve_.row_value = {scratch.row_value, std::size_t(nnz)};
  if (scratch.narrow) {
    rig.solve_.row_col2_16 = {scratch.row_col2_16, std::size_t(nnz)};
    rig.solve_.col_row2_16 = {scratch.col_row2_16, std::size_t(nnz)};
  } else {
    rig.solve_.row_col2 = {scratch.row_col2, std::size_t(nnz)};
    rig.solve_.col_row2 = {scratch.col_row2, std::size_t(nnz)};
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

// The counts and geometry every accessor and job reads.
void RigLoader::Finish(const Header& h, const Counts& c, const detail::KernelTable* kernels, Rig* rig) {
  rig->vertex_count_ = c.meta.vertex_count;
  rig->triangle_count_ = c.meta.triangle_count;
  rig->pose_count_ = c.meta.pose_count;
  rig->path_count_ = c.meta.path_count;
  rig->grid_.origin_x = c.meta.grid_origin_x;
  rig->grid_.origin_y = c.meta.grid_origin_y;
  rig->grid_.cell = c.meta.grid_cell_size;
  rig->grid_.cells_x = c.meta.grid_cells_x;
  rig->grid_.cells_y = c.meta.grid_cells_y;
  rig->solve_.n = c.meta.vertex_count - 1;
  rig->default_sigma_ = c.meta.default_sigma;
  rig->texture_filter_ =
      (c.meta.flags & fmt::kMetaFlagNearestFilter) ? TextureFilter::kNearest : TextureFilter::kLinear;
  rig->rig_size_ = c.meta.rig_size;
  if (c.meta.flags & fmt::kMetaFlagDrawingFolder) rig->drawing_folder_ = rig->strings_[std::size_t(2 * c.N + c.P)];
  rig->part_strings_ = c.parts ? rig->strings_.subspan(std::size_t(c.strings - c.events - c.parts * (1 + c.N)),
                                                       std::size_t(c.parts * (1 + c.N)))
                               : Span<const StringView>{};
  rig->kernels_ = kernels;
  rig->checksum_ = h.checksum;
  rig->format_major_ = h.major;
  rig->format_minor_ = h.minor;
  rig->compact_encoding_ = c.compact;
}

}  // namespace posemorph
