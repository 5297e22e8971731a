// SPDX-License-Identifier: MIT
// The 2D camera of the window and the headless capture: which world point
// sits at the viewport's centre and how many pixels one world unit covers.
// World units are rig units placed by each character's transform (a drawn
// pose's rig units are its drawing's pixels, y up).
#pragma once
#include <cstdint>

#include <glm/vec2.hpp>

namespace posemorph::viewer {

struct View {  // a rectangle of world space
  double x0 = -1, y0 = -1, x1 = 1, y1 = 1;
};

struct Camera {
  glm::dvec2 centre{0, 0};  // world point at the viewport's centre
  double zoom = 1;          // pixels per world unit
  static constexpr double kMinZoom = 1.0 / 256, kMaxZoom = 256;
};

// Shows `rect` whole, centred, in a width x height viewport.
Camera FitCamera(const View& rect, std::uint32_t width, std::uint32_t height);
// Pixel art: zoom rounded to a whole number k >= 1 (k screen pixels per
// drawing pixel) and the centre moved by less than a pixel so that drawing
// pixel edges fall on screen pixel edges.
Camera PixelExact(Camera camera, std::uint32_t width, std::uint32_t height);
// Zoom by `factor` keeping the world point under `cursor` (pixels from the
// viewport's top-left) where it is; zoom stays in [kMinZoom, kMaxZoom].
Camera ZoomAbout(Camera camera, glm::dvec2 cursor, double factor, std::uint32_t width, std::uint32_t height);
// Moves the world with a drag of `pixels` (x right, y down).
Camera Pan(Camera camera, glm::dvec2 pixels);

// World <-> viewport pixels (x right, y down, from the viewport's top-left).
glm::dvec2 ToScreen(const Camera& camera, glm::dvec2 world, std::uint32_t width, std::uint32_t height);
glm::dvec2 ToWorld(const Camera& camera, glm::dvec2 screen, std::uint32_t width, std::uint32_t height);

// World -> clip space for the vertex shader: clip = world * scale + offset
// (y flipped: world is y up, Vulkan's clip space y down).
void ClipTransform(const Camera& camera, std::uint32_t width, std::uint32_t height, glm::vec2* scale,
                   glm::vec2* offset);

}  // namespace posemorph::viewer
