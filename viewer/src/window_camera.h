// SPDX-License-Identifier: MIT
// The window's camera controls: fitted to the scene every frame until the
// user zooms (wheel, about the cursor) or pans (middle or right button, or
// space and drag); buttons and keys fit the character (F), the crowd (A) or
// show one drawing pixel per screen pixel (1).
#pragma once
#include <cstdint>

#include "scene.h"
#include "window_common.h"

namespace posemorph::viewer::window_impl {

class ViewCamera {
 public:
  enum class Fit { kAll, kCharacter, kNone };

  void Ui();
  // The wheel, the pan buttons and the keys, for the view at x0 of w x h pixels.
  void Input(GLFWwindow* window, std::int32_t x0, std::uint32_t w, std::uint32_t h);
  // After the frame's characters are known: fitted to the first character
  // (or, with `character`, always to it) or to all of them, unless the user
  // moved the camera; a pending 1:1 is applied.
  void Follow(const SceneBounds& bounds, bool character, std::uint32_t w, std::uint32_t h);

  const Camera& camera() const { return camera_; }
  Fit fit() const { return fit_; }
  void set_fit(Fit fit) { fit_ = fit; }
  bool panning() const { return panning_; }

 private:
  Fit fit_ = Fit::kAll;
  Camera camera_;
  bool one_to_one_ = false;  // applied once the next frame's bounds are known
  bool panning_ = false;
};

}  // namespace posemorph::viewer::window_impl
