// SPDX-License-Identifier: MIT
// The window's camera controls: fit, zoom about the cursor, pan, one drawing pixel per screen pixel.
#include "window_camera.h"

#include <cmath>

namespace posemorph::viewer::window_impl {

void ViewCamera::Ui() {
  ImGui::Separator();
  ImGui::TextUnformatted("Camera (wheel: zoom; middle/right or space + drag: pan)");
  if (ImGui::Button("fit character")) fit_ = Fit::kCharacter;
  ImGui::SameLine();
  if (ImGui::Button("fit crowd")) fit_ = Fit::kAll;
  ImGui::SameLine();
  if (ImGui::Button("1:1")) fit_ = Fit::kNone, one_to_one_ = true;
  ImGui::Text("zoom %.3g px per unit", camera_.zoom);
}

void ViewCamera::Input(GLFWwindow* window, std::int32_t x0, std::uint32_t w, std::uint32_t h) {
  const ImGuiIO& io = ImGui::GetIO();
  const glm::dvec2 cursor(io.MousePos.x - x0, io.MousePos.y);
  const bool inside = io.MousePos.x >= float(x0) && cursor.y >= 0 && cursor.y < h && !io.WantCaptureMouse;
  if (inside && io.MouseWheel != 0) {
    camera_ = ZoomAbout(camera_, cursor, std::pow(1.15, double(io.MouseWheel)), w, h);
    fit_ = Fit::kNone;
  }
  const bool space = window && glfwGetKey(window, GLFW_KEY_SPACE) == GLFW_PRESS;
  const bool pan_button = io.MouseDown[1] || io.MouseDown[2] || (space && io.MouseDown[0]);
  if (!pan_button)
    panning_ = false;
  else if (inside && !panning_ && (io.MouseClicked[1] || io.MouseClicked[2] || io.MouseClicked[0]))
    panning_ = true;
  if (panning_ && (io.MouseDelta.x != 0 || io.MouseDelta.y != 0)) {
    camera_ = Pan(camera_, {io.MouseDelta.x, io.MouseDelta.y});
    fit_ = Fit::kNone;
  }
  if (!io.WantCaptureKeyboard) {
    if (ImGui::IsKeyPressed(GLFW_KEY_F)) fit_ = Fit::kCharacter;
    if (ImGui::IsKeyPressed(GLFW_KEY_A)) fit_ = Fit::kAll;
    if (ImGui::IsKeyPressed(GLFW_KEY_1)) fit_ = Fit::kNone, one_to_one_ = true;
  }
}

void ViewCamera::Follow(const SceneBounds& bounds, bool character, std::uint32_t w, std::uint32_t h) {
  if (fit_ == Fit::kNone && !one_to_one_) return;
  camera_ = FitCamera(fit_ == Fit::kCharacter || character ? bounds.first : bounds.all, w, h);
  if (one_to_one_) camera_.zoom = 1, camera_ = PixelExact(camera_, w, h), one_to_one_ = false;
}

}  // namespace posemorph::viewer::window_impl
