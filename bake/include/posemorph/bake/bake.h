// SPDX-License-Identifier: MIT
// The whole bake: description in, rig bytes out (DESIGN.md section 2).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "posemorph/bake/compact_rig.h"
#include "posemorph/bake/inbetween_check.h"
#include "posemorph/bake/rig_description.h"

namespace posemorph::bake {

struct BakeReport {
  std::uint32_t vertices = 0, triangles = 0, poses = 0, paths = 0;
  std::uint64_t factor_nonzeros = 0;  // strict lower part of L
  std::uint64_t matrix_nonzeros = 0;  // lower part of K, diagonal included
  std::uint32_t grid_cells_x = 0, grid_cells_y = 0;
  std::uint64_t bytes = 0;
  double max_reproduction_error = 0;  // at the pose points, relative to the rig size (checked by the runtime)
  double seconds = 0;
  bool compact = false;            // the encoding written
  std::uint64_t exact_bytes = 0;   // size of the exact encoding
  double max_error_px = 0;         // the budget (compact)
  double pixels_per_unit = 0;      // drawing pixels per rig unit used for it
  CompactReport compact_report;    // what the compact encoding reached
  InbetweenCheck inbetweens;       // the rig written, evaluated over the pose hull and the paths
  std::vector<std::string> warnings;  // "FILE: ..." (folds, when allowed)
};

// Validates (may reorient triangles), analyses, factors, solves the weight
// grid and serialises. The result is loaded back with the runtime, every pose
// is checked at its point and the in-betweens for folds (a fold throws unless
// rig.parameters.allow_folds) before it is returned. Throws BakeError.
std::vector<unsigned char> BakeRig(RigDescription& rig, BakeReport* report = nullptr);

// Writes bytes to path via a temporary file in the same folder and a rename,
// so readers never see a partial rig. Throws BakeError.
void WriteFileAtomic(const std::string& path, const std::vector<unsigned char>& bytes);

}  // namespace posemorph::bake
