// SPDX-License-Identifier: MIT
// The window's editor: edit mode (handles dragged on one base pose's mesh
// make a new pose, as-rigid-as-possible shape manipulation: the bake's
// ArapDeformer) and saving gestures and poses into the rig description.
// window_edit.cpp and window_description.cpp implement it and are the one
// component that links the bake; a build with POSEMORPH_VIEWER_EDIT=OFF
// takes window_edit_off.cpp in their place.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "rig_renderer.h"
#include "scene.h"
#include "window_common.h"
#include "window_pad.h"

namespace posemorph::viewer::window_impl {

// The deformer behind edit mode (the bake's ArapDeformer, window_edit.cpp).
class EditDeformer;
struct EditDeformerDelete {
  void operator()(EditDeformer* d) const;
};
// The description's landmarks and features (window_points.cpp).
class DrawnPoints;
struct DrawnPointsDelete {
  void operator()(DrawnPoints* d) const;
};

// Edit mode's state: the base pose, the handles (vertices) and where they
// are dragged, the mesh as deformed.
struct Edit {
  bool on = false;
  int pose = 0;
  std::vector<std::uint32_t> handles;
  std::vector<glm::dvec2> targets;
  std::unique_ptr<EditDeformer, EditDeformerDelete> deformer;  // for this handle set
  std::vector<glm::dvec2> rest, current;
  int dragging = -1;
};

class Editor {
 public:
  // `description`: the rig description to save into ("" refuses saving with a status line).
  Editor(const Rig& rig, std::string description) : rig_(&rig), description_(std::move(description)) {}
  // --watch: the description is baked again after each save (the status says so).
  void SetWatched(bool watched) { watched_ = watched; }
  // Another rig from now on (a --watch re-bake): edit mode ends, its handles go.
  void Rebind(const Rig& rig) {
    rig_ = &rig;
    edit_ = Edit{};
    point_drag_ = -1;
  }

  // The panel's edit controls; saving the pose needs the pad's point.
  void Ui(const Scene& scene, std::string* status);
  // Handles: a click on the mesh adds one, a drag moves one (not while the
  // camera pans); or, with "click adds: landmarks" or "features", the
  // description's points over the pose's outline, placed by clicking and
  // saved (window_points.cpp); `status` says what was saved.
  void Input(const ViewMap& map, bool panning, std::string* status);
  // The edited pose into the renderer's first character, standing unmoved;
  // false when this build has no edit mode.
  bool Prepare(RigRenderer& renderer, SceneBounds* bounds, std::uint32_t* count, std::string* status);
  // The gesture as a path, and the edited pose as a deformation of the pose
  // it started from at the pad's point, added to the rig description
  // (bake::AddToRigDescription; the names are stems) and written back
  // atomically; `status` says what was done.
  void SaveGesture(const Gesture& gesture, std::string* status) const;
  void SavePose(const Scene& scene, std::string* status) const;
  // Pose `pose`'s point moved to (x, y) in the description (MovePosePoint),
  // written back atomically; `status` says what was done.
  void SavePosePoint(std::uint32_t pose, double x, double y, std::string* status) const;

  Edit& state() { return edit_; }
  // What a click in edit mode adds: 0 handles, 1 landmarks, 2 features (the smoke test's way to choose).
  void SetClick(int mode) { click_ = Click(mode), point_drag_ = -1; }
  bool on() const { return edit_.on; }

 private:
  [[maybe_unused]] const Rig* rig_;  // unused in a build without edit mode
  // window_points.cpp: the "click adds" choice, and the points' overlay and clicks.
  void PointsUi();
  bool PointsInput(const ViewMap& map, bool panning, std::string* status);

  std::string description_;
  bool watched_ = false;
  Edit edit_;
  enum class Click { kHandles, kLandmarks, kFeatures } click_ = Click::kHandles;
  int point_drag_ = -1;    // the landmark or feature being dragged
  std::string drag_part_;  // and its part's name
  std::unique_ptr<DrawnPoints, DrawnPointsDelete> points_;
};

}  // namespace posemorph::viewer::window_impl
