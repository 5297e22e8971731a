// SPDX-License-Identifier: MIT
// posemorph-view's command line: the options, their usage text, and the
// parsing that turns argv into Options (names of parts, channels and
// inputs are resolved against the rig afterwards, in main.cpp).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "camera.h"
#include "scene.h"
#include "window.h"

namespace posemorph::viewer {

// What the command line asks for.
struct Options {
  std::string rig_path, images, output;
  WindowOptions window;
  bool headless = false, validation = false;
  std::uint32_t width = 640, height = 640, frames = 0;
  Scene scene;
  enum class CameraMode { kFit, kOneToOne, kGiven } camera_mode = CameraMode::kFit;
  Camera given_camera;
  Blend blend = Blend::kExact;
  std::vector<std::string> hidden_parts;    // --hide-part, resolved once the rig is loaded
  std::vector<std::string> channels;        // --channel NAME=X,Y or NAME=PATH, resolved likewise
  std::vector<std::string> part_opacities;  // --part-opacity NAME=A, resolved likewise
  std::string inputs;                       // --inputs TIMELINE, resolved likewise
  bool has_inputs = false;
  double fps = 30;
  bool watch = false;  // --watch: rig_path is a description, baked here and again on every change
};

// The options into `o`; -1 to go on, or the exit status (usage, --help).
int ParseOptions(int argc, char** argv, Options& o);
// A usage error: one line naming the option and what it wants; exit status 2.
int Usage(const std::string& problem);
// A number in [lo, hi] (finite, nothing after it).
bool ParseNumber(const char* text, double lo, double hi, double* out);

}  // namespace posemorph::viewer
