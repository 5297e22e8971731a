// SPDX-License-Identifier: MIT
// One pass of the bake's pipeline (bake_attempt.cpp), from the description
// to the in-between check, and the ghosting measure of what it baked: what
// BakeOne (bake.cpp) and the mapping's variants (map_again.h) compare and
// report. Internal to the bake.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "posemorph/bake/compact_rig.h"
#include "posemorph/bake/ghosting.h"
#include "posemorph/bake/inbetween_check.h"
#include "posemorph/bake/map_drawings.h"
#include "posemorph/bake/pose_meshes.h"
#include "posemorph/bake/reproduction_check.h"
#include "posemorph/bake/rig_description.h"
#include "posemorph/bake/rig_sections.h"

namespace posemorph::bake {

// One pass of the pipeline, up to the in-between check; what the report needs.
struct Attempt {
  MappedDrawings drawings;
  PoseMeshes meshes;
  std::uint64_t factor_nonzeros = 0, matrix_nonzeros = 0;
  int grid_cells_x = 0, grid_cells_y = 0;
  bool grid_coarsened = false;       // a coarser grid than the default (grid_resolution.h)
  double grid_move_px = 0;           // and its estimate
  std::uint64_t exact_bytes = 0;     // the exact encoding's file size
  RigSections sections;              // what is written: the exact or the compact encoding
  std::vector<unsigned char> bytes;  // WriteRig(sections), as the verification loaded them
  CompactSettings compact_settings;
  CompactReport compact;
  bool is_compact = false;
  ReproductionCheck written;
  InbetweenCheck inbetweens;
  std::vector<std::string> weight_warnings;
  std::vector<std::uint32_t> joints;  // a layered character's glue joints (join_parts.h)
  std::optional<Ghosting> ghosting;   // its measure, once taken (GhostingOf)
};

// Maps (or joins the parts of) `description`, deforms, validates, factors,
// solves the weights, writes, encodes and verifies the rig, and checks its
// in-betweens. Throws BakeError as each step does.
Attempt BakeOnce(const RigDescription& description);

// Every pose's PNG drawing, reduced for the ghosting measure (ghosting.h),
// read once per bake; `skipped` says why there are none when a pose has no
// PNG drawing (or draws another image).
struct GhostingDrawings {
  std::vector<std::vector<unsigned char>> pixels;
  std::vector<std::array<std::uint32_t, 2>> sizes;  // width, height
  std::string skipped;
};

// Throws BakeError naming the pose when a PNG drawing cannot be read.
GhostingDrawings ReadGhostingDrawings(const RigDescription& description);

// The ghosting measure of a's rig (MeasureGhosting), or nothing where
// g.skipped says why; measured once per attempt, kept in a.ghosting.
const Ghosting& GhostingOf(Attempt& a, const GhostingDrawings& g, const std::string& file);

}  // namespace posemorph::bake
