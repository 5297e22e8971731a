// SPDX-License-Identifier: MIT
// A viewer built with POSEMORPH_VIEWER_EDIT=OFF: no edit mode and no saving
// into the description (the component that links the bake is left out, so
// this viewer needs the runtime, Vulkan, GLFW and Dear ImGui alone). The
// panel says so where the controls would be.
#include "watch_bake.h"
#include "window_editor.h"

namespace posemorph::viewer {
bool EditModeBuilt() { return false; }

// --watch needs the bake, which this viewer is built without.
std::unique_ptr<WatchedBake> WatchDescription(const std::string&, std::unique_ptr<BakedRig>*, std::string* problem) {
  *problem = "--watch needs a posemorph-view built with the bake (POSEMORPH_VIEWER_EDIT=ON)";
  return nullptr;
}
}  // namespace posemorph::viewer

namespace posemorph::viewer::window_impl {

class EditDeformer {};
void EditDeformerDelete::operator()(EditDeformer* d) const { delete d; }
class DrawnPoints {};
void DrawnPointsDelete::operator()(DrawnPoints* d) const { delete d; }

void Editor::Ui(const Scene&, std::string*) {
  ImGui::Separator();
  ImGui::TextWrapped("Edit mode is not in this build (POSEMORPH_VIEWER_EDIT=OFF)");
}

void Editor::Input(const ViewMap&, bool, std::string*) {}

bool Editor::Prepare(RigRenderer&, SceneBounds*, std::uint32_t*, std::string*) { return false; }

void Editor::SaveGesture(const Gesture&, std::string* status) const {
  *status = "saving gestures needs a viewer built with POSEMORPH_VIEWER_EDIT=ON";
}

void Editor::SavePose(const Scene&, std::string* status) const {
  *status = "saving poses needs a viewer built with POSEMORPH_VIEWER_EDIT=ON";
}

void Editor::SavePosePoint(std::uint32_t, double, double, std::string* status) const {
  *status = "moving pose points needs a viewer built with POSEMORPH_VIEWER_EDIT=ON";
}

}  // namespace posemorph::viewer::window_impl
