// SPDX-License-Identifier: MIT
// Built when GLFW or Dear ImGui is not available: the viewer is headless only.
#include <cstdio>

#include "window.h"

namespace posemorph::viewer {

bool EditModeBuilt() { return false; }

int RunWindow(const Rig&, const Drawings&, Scene, const WindowOptions&) {
  std::fprintf(stderr, "posemorph-view: this build has no window support; use --headless -o OUT.png\n");
  return 2;
}

}  // namespace posemorph::viewer
