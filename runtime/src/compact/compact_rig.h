// SPDX-License-Identifier: MIT
// The compact encoding (format 1.3, META flag kMetaFlagCompact): reading its
// section headers (before the arena is sized) and decoding and deriving the
// arrays the runtime evaluates (into the arena, in the layout an exact rig
// loads into). Every failure names its section.
#pragma once
#include <cstdint>

#include "arap_factor.h"
#include "posemorph/error.h"

namespace posemorph::detail {

struct SectionBytes {
  const unsigned char* data = nullptr;
  std::uint64_t size = 0;
};

struct CompactCounts {
  std::uint64_t V, T, N, n, nnz;
  std::uint64_t cells_x, cells_y;
  bool grid_centres;
  std::uint64_t file_size;
  std::uint16_t minor;  // the file's format version (1.minor)
};

// What the headers say, checked against the counts and the sections' sizes.
struct CompactLayout {
  SectionBytes positions, triangles, permutation, turns, grid, affine_uvs;
  double position_step = 0;
  unsigned position_k = 0, triangle_k = 0;       // Exp-Golomb orders
  std::uint32_t position_prediction = 0;         // QPOS: kPositionsAgainstPose0, kPositionsFromNeighbours
  unsigned permutation_bits = 0, turn_bits = 0;  // fixed widths
  std::int32_t turn_base = 0;
  double grid_step = 0;
  std::uint32_t grid_coded_poses = 0;
  bool has_affine_uvs = false;
};

// sections: QPOS, QTRI, QPRM, QTRN, QGRD (required), QUVA (optional: data null when absent).
bool ReadCompactLayout(const SectionBytes& qpos, const SectionBytes& qtri, const SectionBytes& qprm,
                       const SectionBytes& qtrn, const SectionBytes& qgrd, const SectionBytes& quva,
                       const CompactCounts& counts, CompactLayout* out, Error* err);

struct CompactOutputs {
  std::uint32_t* triangles;        // 3T
  double* positions;               // 2NV
  double* centroids;               // 2N
  double* angles;                  // TN
  double* stretches;               // 3TN
  std::uint32_t* order;            // n
  double* grid_corners;            // (cells_x+1)(cells_y+1) N
  double* grid_centres;            // cells_x cells_y N, or null
  float* uvs;                      // 2NV when QUVA is present, else null
  std::int64_t* grid_scratch;      // (cells_x+1)(cells_y+1)
  unsigned char* seen;             // n
  std::int64_t* position_codes;    // 2V: one pose's integers (QPOS)
  std::uint32_t* neighbour_start;  // V + 1: the earlier neighbours' lists (QPOS, 1.14)
  std::uint32_t* neighbour_fill;   // V
  std::uint32_t* neighbour_list;   // 3T
  ArapFactorBuffers factor;
};

bool DecodeCompact(const CompactLayout& layout, const CompactCounts& counts, const CompactOutputs& out, Error* err);

}  // namespace posemorph::detail
