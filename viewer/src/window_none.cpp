// SPDX-License-Identifier: MIT
// Built when GLFW or Dear ImGui is not available: the viewer is headless only.
#include <cstdio>

#include "watch_bake.h"
#include "window.h"

namespace posemorph::viewer {

bool EditModeBuilt() { return false; }

// --watch needs the bake, which this viewer is built without.
std::unique_ptr<WatchedBake> WatchDescription(const std::string&, std::unique_ptr<BakedRig>*, std::string* problem) {
  *problem = "--watch needs a posemorph-view built with the bake (POSEMORPH_VIEWER_EDIT=ON)";
  return nullptr;
}

int RunWindow(const Rig&, const Drawings&, Scene, const WindowOptions&) {
  std::fprintf(stderr, "posemorph-view: this build has no window support; use --headless -o OUT.png\n");
  return 2;
}

}  // namespace posemorph::viewer
