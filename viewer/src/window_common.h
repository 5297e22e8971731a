// SPDX-License-Identifier: MIT
// What the window's parts share: the panel's size, the crowd's bound, the
// pad's pose colours, the joints of a layered character, and the map between
// rig units and window pixels.
#pragma once
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "camera.h"
#include "posemorph/rig.h"

namespace posemorph::viewer::window_impl {

constexpr float kPanelWidth = 320;
constexpr std::uint32_t kMaxCharacters = 400;
const float kBackground[4] = {0.93f, 0.94f, 0.95f, 1.0f};

ImU32 PoseColour(std::uint32_t i, int alpha);  // the pad's colour of pose i (pose_colours.h)

// The vertices used by triangles of two parts or more: a layered
// character's joints, in index order.
std::vector<std::uint32_t> JointVertices(const Rig& rig);

// The joint markers' fill: a colour no sample draws, found again in screenshots.
constexpr ImU32 kJointColour = IM_COL32(255, 0, 255, 255);

// The same mapping as RigRenderer::Record: world <-> window pixels, for a
// viewport at x0 (the edited character stands at the identity transform).
struct ViewMap {
  Camera camera;
  std::int32_t x0;
  std::uint32_t w, h;
  double s() const { return camera.zoom; }
  ImVec2 ToScreen(const glm::dvec2& p) const {
    const glm::dvec2 q = viewer::ToScreen(camera, p, w, h);
    return ImVec2(float(q.x + x0), float(q.y));
  }
  glm::dvec2 ToRig(const ImVec2& q) const { return ToWorld(camera, {q.x - x0, q.y}, w, h); }
};

}  // namespace posemorph::viewer::window_impl
