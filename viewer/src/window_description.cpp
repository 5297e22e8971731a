// SPDX-License-Identifier: MIT
// Saving into the rig description: gestures as paths, edited poses as deformations, written back atomically.
// Part of the edit component (with window_edit.cpp): it links the bake.
#include <cstdio>

#include "posemorph/bake/bake.h"
#include "posemorph/bake/input_file.h"
#include "posemorph/bake/rig_description.h"
#include "window_editor.h"

namespace posemorph::viewer::window_impl {
namespace {

// Adds them to the rig description and writes it back; the status line says what.
std::string SaveIntoDescription(const std::string& description, bool watched, const char* what,
                                const std::vector<bake::PoseDescription>& poses,
                                const std::vector<bake::PathDescription>& paths) {
  if (description.empty()) return std::string("start with --description RIG.json to save ") + what;
  try {
    const std::vector<unsigned char> bytes =
        bake::ReadInputFile(description, bake::kMaxTextFileBytes, "a rig description");
    const bake::DescriptionAddition added =
        bake::AddToRigDescription(std::string(bytes.begin(), bytes.end()), description, poses, paths);
    bake::WriteFileAtomic(description, std::vector<unsigned char>(added.text.begin(), added.text.end()));
    std::string names;
    for (const std::string& n : added.pose_names) names += (names.empty() ? "" : ", ") + ("pose \"" + n + "\"");
    for (const std::string& n : added.path_names) names += (names.empty() ? "" : ", ") + ("path \"" + n + "\"");
    return "saved " + names + " into " + description + (watched ? " (baked again)" : " (bake again to use it)");
  } catch (const std::exception& e) {
    return std::string("cannot save: ") + e.what();
  }
}

}  // namespace

void Editor::SaveGesture(const Gesture& gesture, std::string* status) const {
  bake::PathDescription path;
  path.name = "gesture";
  path.loop = true;
  double last = -1;  // key times must increase strictly
  for (const auto& k : gesture.keys)
    if (k[0] > last + 1e-3) path.keys.push_back({k[0], k[1], k[2]}), last = k[0];
  *status = SaveIntoDescription(description_, watched_, "gestures", {}, {path});
}

void Editor::SavePose(const Scene& scene, std::string* status) const {
  bake::PoseDescription pose;
  pose.name = "edit";
  pose.point = {scene.x, scene.y};
  pose.deformed = true;
  const StringView from = rig_->pose_name(std::uint32_t(edit_.pose));
  pose.deform.from.assign(from.data, from.size);
  // Each handle saved where its vertex lies in the source pose, not by the
  // vertex's number: the bake takes the nearest vertex of the triangle
  // there, so the pose survives a re-bake that meshes the drawings anew
  // (a landmark added, a drawing edited), which numbers the vertices anew.
  const Span<const double> at = rig_->pose_positions(std::uint32_t(edit_.pose));
  for (std::size_t k = 0; k < edit_.handles.size(); ++k) {
    bake::HandleDescription h;
    h.at = Eigen::Vector2d(at[2 * std::size_t(edit_.handles[k])], at[2 * std::size_t(edit_.handles[k]) + 1]);
    h.to = Eigen::Vector2d(edit_.targets[k].x, edit_.targets[k].y);
    pose.deform.handles.push_back(h);
  }
  *status = SaveIntoDescription(description_, watched_, "poses", {pose}, {});
}

void Editor::SavePosePoint(std::uint32_t pose, double x, double y, std::string* status) const {
  if (description_.empty()) {
    *status = "start with --description RIG.json (or --watch RIG.json) to move pose points";
    return;
  }
  if (pose >= rig_->pose_count()) return;
  const StringView n = rig_->pose_name(pose);
  const std::string name(n.data, n.size);
  try {
    const std::vector<unsigned char> bytes =
        bake::ReadInputFile(description_, bake::kMaxTextFileBytes, "a rig description");
    const std::string text = bake::MovePosePoint(std::string(bytes.begin(), bytes.end()), description_, name, x, y);
    bake::WriteFileAtomic(description_, std::vector<unsigned char>(text.begin(), text.end()));
    char at[64];
    std::snprintf(at, sizeof at, "(%.4g, %.4g)", x, y);
    *status = "moved pose \"" + name + "\" to " + at + " in " + description_ +
              (watched_ ? " (baked again)" : " (bake again to use it)");
  } catch (const std::exception& e) {
    *status = std::string("cannot save: ") + e.what();
  }
}

}  // namespace posemorph::viewer::window_impl
