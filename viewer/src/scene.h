// SPDX-License-Identifier: MIT
// What a frame shows: one character at a pose-space point (or a path time),
// or a crowd walking a path at staggered phases. Used by the headless
// capture, the window and the frame-hash tests alike.
#pragma once
#include <string>
#include <vector>

#include "rig_renderer.h"

namespace posemorph::viewer {

struct Scene {
  double x = 0, y = 0;        // pose-space point (when path is empty)
  std::string path;           // a path of the rig: characters follow it
  double time = 0;            // seconds along the path
  double sigma = -1;          // texture sharpening; < 0: the rig's default
  bool shear_limit = true;
  bool linear = false;        // linear vertex blending instead of rigid (the paper's comparison)
  std::uint32_t crowd = 1;    // characters, laid out on a grid, phases spread over the path
  bool wireframe = false;
  bool compare_linear = false;  // two characters: rigid (left) and linear (right) at the same point
  bool show_bases = false;      // the N base poses in a row, each exactly at its point
};

// How many characters the scene draws.
std::uint32_t SceneCharacters(const Rig& rig, const Scene& scene);

// The CPU buffers a scene's evaluation reuses from frame to frame.
struct SceneScratch {
  std::vector<double> raw, shear, texture;  // K x N weights
  std::vector<double> workspace, positions;
};

// Evaluates the characters of a scene with the runtime (one MorphBatchJob
// for rigid characters, MorphJob for linear ones) into the renderer's
// buffers and returns the view that frames them. False with a message for
// an unknown path or more characters than the renderer holds.
bool PrepareScene(const Rig& rig, const Scene& scene, RigRenderer& renderer, SceneScratch& scratch, View* view,
                  std::uint32_t* count, std::string* error);

// The rectangle of rig space that holds every pose of one character.
View CharacterBounds(const Rig& rig);

}  // namespace posemorph::viewer
