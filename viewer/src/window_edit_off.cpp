// SPDX-License-Identifier: MIT
// A viewer built with POSEMORPH_VIEWER_EDIT=OFF: no edit mode and no saving
// into the description (the component that links the bake is left out, so
// this viewer needs the runtime, Vulkan, GLFW and Dear ImGui alone). The
// panel says so where the controls would be.
#include "window_impl.h"

namespace posemorph::viewer::window_impl {

class EditDeformer {};
void EditDeformerDelete::operator()(EditDeformer* d) const { delete d; }

bool EditModeBuilt() { return false; }

void Viewer::EditUi() {
  ImGui::Separator();
  ImGui::TextWrapped("Edit mode is not in this build (POSEMORPH_VIEWER_EDIT=OFF)");
}

void Viewer::EditInput(std::int32_t, std::uint32_t, std::uint32_t) {}

bool Viewer::EditScene(SceneBounds*, std::uint32_t*) { return false; }

void Viewer::SaveGesture() { status_ = "saving gestures needs a viewer built with POSEMORPH_VIEWER_EDIT=ON"; }

void Viewer::SavePose() { status_ = "saving poses needs a viewer built with POSEMORPH_VIEWER_EDIT=ON"; }

}  // namespace posemorph::viewer::window_impl
