// SPDX-License-Identifier: MIT
// The pose-space pad: the weight field coloured by the dominant pose, the pose points, dragging the point, recording a
// gesture.
#include "posemorph/bake/pose_colours.h"
#include "window_impl.h"

namespace posemorph::viewer::window_impl {

// Colours of the poses in the pad (dominant pose of the weight field): the
// contact sheet's (pose_colours.h).
ImU32 PoseColour(std::uint32_t i, int alpha) {
  const bake::PoseColour c = bake::PoseColourOf(i);
  return IM_COL32(c.r, c.g, c.b, alpha);
}

bool Viewer::DrawPad(const Rig& rig, const PadField& f, const char* id, double* px, double* py) {
  const PoseSpaceGrid& g = rig.grid();
  const float size = kPanelWidth - 24;
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton(id, ImVec2(size, size));
  const bool active = ImGui::IsItemActive();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  auto to_screen = [&](double x, double y) {
    return ImVec2(origin.x + float((x - f.x0) / f.span * size), origin.y + float((1 - (y - f.y0) / f.span) * size));
  };
  // The weight field: each cell coloured by its dominant pose, stronger where it dominates more.
  const float cell = size / float(field_cells_);
  for (int j = 0; j < field_cells_; ++j)
    for (int i = 0; i < field_cells_; ++i) {
      const ImVec2 a(origin.x + i * cell, origin.y + (field_cells_ - 1 - j) * cell);
      draw->AddRectFilled(a, ImVec2(a.x + cell + 1, a.y + cell + 1), f.colours[std::size_t(j) * field_cells_ + i]);
    }
  draw->AddRect(to_screen(g.origin_x, g.origin_y + g.cell * g.cells_y),
                to_screen(g.origin_x + g.cell * g.cells_x, g.origin_y), IM_COL32(60, 60, 60, 160));
  for (std::uint32_t i = 0; i < rig.pose_count(); ++i) {
    const ImVec2 p = to_screen(rig.pose_points().data[2 * i], rig.pose_points().data[2 * i + 1]);
    draw->AddCircleFilled(p, 6, PoseColour(i, 255));
    draw->AddCircle(p, 6, IM_COL32(30, 30, 30, 255));
    const StringView name = rig.pose_name(i);
    draw->AddText(ImVec2(p.x + 8, p.y - 7), IM_COL32(20, 20, 20, 255), name.data, name.data + name.size);
  }
  if (&rig == &rig_ && gesture_.keys.size() > 1)
    for (std::size_t k = 1; k < gesture_.keys.size(); ++k)
      draw->AddLine(to_screen(gesture_.keys[k - 1][1], gesture_.keys[k - 1][2]),
                    to_screen(gesture_.keys[k][1], gesture_.keys[k][2]), IM_COL32(40, 40, 40, 200), 2);
  const ImVec2 cur = to_screen(*px, *py);
  draw->AddCircle(cur, 9, IM_COL32(255, 255, 255, 255), 0, 3);
  draw->AddCircle(cur, 11, IM_COL32(20, 20, 20, 255), 0, 1.5f);
  if (active) {
    const ImVec2 m = ImGui::GetIO().MousePos;
    *px = f.x0 + (m.x - origin.x) / size * f.span;
    *py = f.y0 + (1 - (m.y - origin.y) / size) * f.span;
  }
  return active;
}

void Viewer::Pad() {
  if (rig_.channel_count() > 1) {
    const StringView name = rig_.channel_name(0);
    ImGui::Text("Channel 1 '%s' (drag; beyond the points extrapolates)",
                Printable(std::string(name.data, name.size), 24).c_str());
  } else {
    ImGui::TextUnformatted("Pose space (drag; beyond the points extrapolates)");
  }
  PadField body{field_, pad_x0_, pad_y0_, pad_span_};
  if (DrawPad(rig_, body, "pad", &scene_.x, &scene_.y)) {
    scene_.path.clear();
    play_path_ = false;
    gesture_.playing = false;
    if (gesture_.recording) gesture_.keys.push_back({clock_ - gesture_.start, scene_.x, scene_.y});
  }
}

void Viewer::ChannelPads() {
  for (std::uint32_t c = 1; c < rig_.channel_count() && c - 1 < channel_fields_.size(); ++c) {
    ImGui::Separator();
    const StringView name = rig_.channel_name(c);
    const std::string label = Printable(std::string(name.data, name.size), 40);
    ImGui::Text("Channel %u '%s' (its own pose space)", c + 1, label.c_str());
    const Rig& channel = *rig_.channel_rig(c);
    ChannelInput& in = scene_.channels[c - 1];
    const std::string id = "pad" + std::to_string(c);
    if (DrawPad(channel, channel_fields_[c - 1], id.c_str(), &in.x, &in.y)) play_channel_[c - 1] = 0;
    ImGui::Text("point (%.3f, %.3f)", in.x, in.y);
    if (channel.path_count() > 0) {
      ImGui::SameLine();
      bool play = play_channel_[c - 1] != 0;
      const StringView path = channel.path(0).name;
      if (ImGui::Checkbox(("play '" + Printable(std::string(path.data, path.size), 24) + "'##" + id).c_str(), &play))
        play_channel_[c - 1] = play ? 1 : 0;
    }
  }
}

}  // namespace posemorph::viewer::window_impl
