// SPDX-License-Identifier: MIT
// The compact encoding of a baked rig (format 1.3, runtime/FORMAT.md): from
// the exact rig's sections to a rig whose every frame stays within an error
// budget stated in drawing pixels. Positions and the weight grid are
// quantised (the grid also predicted and Exp-Golomb coded), triangles and the
// permutation bit-packed, uvs stored as affine maps of a pose's positions
// when they are (else as UVS); everything the runtime can compute from the
// positions (masses, centroids, gradients, angles, stretches, the factor) is
// computed at load. The steps are chosen by measuring: the encoder evaluates
// both rigs with the runtime at the pose points, over the pose points' convex
// hull and along every path, and keeps the coarsest steps within budget.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "posemorph/bake/rig_sections.h"

namespace posemorph::bake {

struct CompactSettings {
  double max_error_px = 0.01;  // for every vertex of every sampled frame, against the exact rig
  double pixels_per_unit = 1;  // drawing pixels per rig unit
};

struct CompactSection {
  std::string tag;
  std::uint64_t bytes = 0;
  std::string precision;  // what it holds and how, e.g. "17-bit positions, step 0.0031 px"
};

struct CompactReport {
  double max_error_px = 0;      // over every sampled frame (hull, paths, pose points)
  double pose_error_px = 0;     // at the pose points
  std::uint32_t samples = 0;    // frames compared
  double position_step_px = 0;  // quantisation step of positions
  double weight_step = 0;       // quantisation step of the weight grid
  std::uint32_t trials = 0;     // encodings tried
  bool affine_uvs = false;
  bool fell_back = false;  // no encoding within budget: the exact sections were returned
  std::vector<CompactSection> sections;
};

// The compact rig's sections (WriteRig makes its file). When no encoding
// within budget is found (twelve halvings of the position step), returns the
// exact sections and sets report->fell_back. Throws BakeError(file, ...)
// only when the exact rig itself does not load or the settings are not
// positive.
RigSections CompactRig(const RigSections& exact, const CompactSettings& settings, const std::string& file,
                       CompactReport* report = nullptr);

}  // namespace posemorph::bake
