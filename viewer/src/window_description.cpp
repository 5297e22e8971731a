// SPDX-License-Identifier: MIT
// Saving into the rig description: gestures as paths, edited poses as deformations, written back atomically.
#include "posemorph/bake/input_file.h"
#include "window_impl.h"

namespace posemorph::viewer::window_impl {

void Viewer::SaveIntoDescription(const char* what, const std::vector<bake::PoseDescription>& poses,
                                 const std::vector<bake::PathDescription>& paths) {
  if (options_.description.empty()) {
    status_ = std::string("start with --description RIG.json to save ") + what;
    return;
  }
  try {
    const std::vector<unsigned char> bytes =
        bake::ReadInputFile(options_.description, bake::kMaxTextFileBytes, "a rig description");
    const bake::DescriptionAddition added =
        bake::AddToRigDescription(std::string(bytes.begin(), bytes.end()), options_.description, poses, paths);
    bake::WriteFileAtomic(options_.description, std::vector<unsigned char>(added.text.begin(), added.text.end()));
    std::string names;
    for (const std::string& n : added.pose_names) names += (names.empty() ? "" : ", ") + ("pose \"" + n + "\"");
    for (const std::string& n : added.path_names) names += (names.empty() ? "" : ", ") + ("path \"" + n + "\"");
    status_ = "saved " + names + " into " + options_.description + " (bake again to use it)";
  } catch (const std::exception& e) {
    status_ = std::string("cannot save: ") + e.what();
  }
}

// The edited pose as a deformation of the pose it started from, at the pad's point.
void Viewer::SavePose() {
  bake::PoseDescription pose;
  pose.name = "edit";
  pose.point = {scene_.x, scene_.y};
  pose.deformed = true;
  const StringView from = rig_.pose_name(std::uint32_t(edit_.pose));
  pose.deform.from.assign(from.data, from.size);
  for (std::size_t k = 0; k < edit_.handles.size(); ++k) {
    bake::HandleDescription h;
    h.by_vertex = true;
    h.vertex = edit_.handles[k];
    h.to = edit_.targets[k];
    pose.deform.handles.push_back(h);
  }
  SaveIntoDescription("poses", {pose}, {});
}

}  // namespace posemorph::viewer::window_impl
