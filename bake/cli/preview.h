// SPDX-License-Identifier: MIT
// Writing morphed meshes where a person can look at them: SVG (single frames,
// film strips, the pose-space contact sheet), JSON and OBJ.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "posemorph/jobs.h"
#include "posemorph/rig.h"

namespace posemorph::bake {

struct Frame {
  double x = 0, y = 0;  // pose-space point
  std::string label;
  std::vector<double> raw, texture;
  std::vector<double> positions;  // 2 x V
};

struct EvalOptions {
  double sigma = -1;  // < 0: the rig's default
  bool limit_weights = true;
  Interpolation interpolation = Interpolation::kRigid;
};

Frame EvaluateFrame(const Rig& rig, double x, double y, const EvalOptions& options);

std::string FramesSvg(const Rig& rig, const std::vector<Frame>& frames, const std::string& title);
std::string FramesJson(const Rig& rig, const std::vector<Frame>& frames);
std::string FrameObj(const Rig& rig, const Frame& frame);
// Base poses, the weight field over pose space, and the morph sampled on a
// grid of pose-space points (interpolation and extrapolation).
std::string ContactSheetSvg(const Rig& rig, const std::string& title, int columns, int rows,
                            const EvalOptions& options);
// The contact sheet's pose-space points, row by row: the pose points' box
// grown by a quarter of their spread (the outer ring extrapolates). One row
// when the points lie on a horizontal line.
// `box` (optional) gets the sampled box: x0, y0, x1, y1.
std::vector<std::array<double, 2>> SheetPoints(const Rig& rig, int columns, int rows,
                                               std::array<double, 4>* box = nullptr);

}  // namespace posemorph::bake
