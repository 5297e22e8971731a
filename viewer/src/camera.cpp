// SPDX-License-Identifier: MIT
#include "camera.h"

#include <algorithm>
#include <cmath>

namespace posemorph::viewer {

Camera FitCamera(const View& rect, std::uint32_t width, std::uint32_t height) {
  Camera c;
  c.centre = {(rect.x0 + rect.x1) / 2, (rect.y0 + rect.y1) / 2};
  const double w = rect.x1 - rect.x0, h = rect.y1 - rect.y0;
  c.zoom = w > 0 && h > 0 ? std::min(width / w, height / h) : 1.0;
  return c;
}

Camera PixelExact(Camera c, std::uint32_t width, std::uint32_t height) {
  c.zoom = std::clamp(std::round(c.zoom), 1.0, Camera::kMaxZoom);
  // Screen x of world x is (x - cx) k + w/2, screen y is h/2 - (y - cy) k:
  // whole for whole x, y when cx k - w/2 and cy k + h/2 are whole.
  c.centre.x = (std::round(c.centre.x * c.zoom - width / 2.0) + width / 2.0) / c.zoom;
  c.centre.y = (std::round(c.centre.y * c.zoom + height / 2.0) - height / 2.0) / c.zoom;
  return c;
}

Camera ZoomAbout(Camera c, glm::dvec2 cursor, double factor, std::uint32_t width, std::uint32_t height) {
  const glm::dvec2 fixed = ToWorld(c, cursor, width, height);
  c.zoom = std::clamp(c.zoom * factor, Camera::kMinZoom, Camera::kMaxZoom);
  // Keep `fixed` under the cursor: centre = fixed - (cursor - viewport centre) / zoom, y flipped.
  c.centre.x = fixed.x - (cursor.x - width / 2.0) / c.zoom;
  c.centre.y = fixed.y + (cursor.y - height / 2.0) / c.zoom;
  return c;
}

Camera Pan(Camera c, glm::dvec2 pixels) {
  c.centre.x -= pixels.x / c.zoom;
  c.centre.y += pixels.y / c.zoom;
  return c;
}

glm::dvec2 ToScreen(const Camera& c, glm::dvec2 p, std::uint32_t width, std::uint32_t height) {
  return {(p.x - c.centre.x) * c.zoom + width / 2.0, height / 2.0 - (p.y - c.centre.y) * c.zoom};
}

glm::dvec2 ToWorld(const Camera& c, glm::dvec2 q, std::uint32_t width, std::uint32_t height) {
  return {c.centre.x + (q.x - width / 2.0) / c.zoom, c.centre.y - (q.y - height / 2.0) / c.zoom};
}

void ClipTransform(const Camera& c, std::uint32_t width, std::uint32_t height, glm::vec2* scale, glm::vec2* offset) {
  const double s = 2 * c.zoom;  // clip space spans 2 over the viewport
  *scale = glm::vec2(float(s / width), float(-s / height));
  *offset = glm::vec2(float(-c.centre.x * s / width), float(c.centre.y * s / height));
}

}  // namespace posemorph::viewer
