// SPDX-License-Identifier: MIT
// Writing morphed meshes where a person can look at them: SVG (single frames,
// film strips, the pose-space contact sheet), JSON and OBJ.
#pragma once
#include <string>
#include <vector>

#include "posemorph/jobs.h"
#include "posemorph/rig.h"

namespace posemorph::bake {

struct Frame {
  double x = 0, y = 0;           // pose-space point
  std::string label;
  std::vector<double> raw, texture;
  std::vector<double> positions;  // 2 x V
};

struct EvalOptions {
  double sigma = -1;  // < 0: the rig's default
  bool shear_limit = true;
  Interpolation interpolation = Interpolation::kRigid;
};

Frame EvaluateFrame(const Rig& rig, double x, double y, const EvalOptions& options);

std::string FramesSvg(const Rig& rig, const std::vector<Frame>& frames, const std::string& title);
std::string FramesJson(const Rig& rig, const std::vector<Frame>& frames);
std::string FrameObj(const Rig& rig, const Frame& frame);
// Base poses, the weight field over pose space, and the morph sampled on a
// grid of pose-space points (interpolation and extrapolation).
std::string ContactSheetSvg(const Rig& rig, const std::string& title, int columns, int rows, const EvalOptions& options);

}  // namespace posemorph::bake
