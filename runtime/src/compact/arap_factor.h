// SPDX-License-Identifier: MIT
// The ARAP system of a compact rig, computed at load from the decoded rest
// pose: per-triangle gradients and lumped masses, the pinned cotangent matrix
// K permuted by the stored fill-reducing order, and its sparse LDL^T factor
// (elimination tree, column counts, then an up-looking numeric pass). The
// same arithmetic in the same order on every target, so a compact rig gives
// the same bits everywhere.
#pragma once
#include <cstdint>

#include "posemorph/error.h"

namespace posemorph::detail {

// Scratch and outputs, all carved from the rig's arena by the loader.
struct ArapFactorBuffers {
  // Outputs.
  double* vertex_masses;     // V, sum 1
  double* gradients;         // 6T: area * (E^-T D)^T, row-major 3x2
  std::uint32_t* col_start;  // n + 1
  std::uint32_t* row;        // nnz
  double* value;             // nnz
  double* inv_diagonal;      // n
  // Scratch.
  std::uint32_t* position;     // n: inverse of the order
  std::uint32_t* parent;       // n: elimination tree
  std::uint32_t* flag;         // n
  std::uint32_t* path;         // n
  std::uint32_t* stack;        // n
  std::uint32_t* fill;         // n: next free slot per column of L
  std::uint32_t* entry_start;  // n + 1: the upper part of K by column
  std::uint32_t* entry_row;    // 6T
  double* entry_value;         // 6T
  double* work;                // n: dense row of the up-looking pass
  double* pivot;               // n: D
};

// Entries of K's upper part at most 6 per triangle (3 diagonal, 3 edges).
inline std::uint64_t ArapEntryCapacity(std::uint64_t triangles) { return 6 * triangles; }

// positions: pose 0, 2V interleaved; triangles: validated indices, 3T;
// order: validated permutation of the n = V - 1 free unknowns. nnz is the
// count META declares: the computed structure must match it exactly.
// Fails (with the triangle, pivot or count named) on a triangle that is not
// counter-clockwise with positive area, a structure other than declared,
// work above kMaxCompactFactorWork, or a pivot that is not positive.
bool BuildArapFactor(const double* positions, std::uint64_t V, const std::uint32_t* triangles, std::uint64_t T,
                     const std::uint32_t* order, std::uint64_t nnz, const ArapFactorBuffers& b, Error* err);

}  // namespace posemorph::detail
