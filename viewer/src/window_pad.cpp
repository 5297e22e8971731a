// SPDX-License-Identifier: MIT
// The pose pad (window_pad.h): the weight field coloured by the dominant
// pose, the pose points, dragging the point, recording and playing a
// gesture, playing the stored paths.
#include "window_pad.h"

#include <algorithm>
#include <cmath>

#include "drawings.h"
#include "posemorph/bake/pose_colours.h"
#include "posemorph/jobs.h"
#include "posemorph/path.h"

namespace posemorph::viewer::window_impl {

// Colours of the poses in the pad (dominant pose of the weight field): the
// contact sheet's (pose_colours.h).
ImU32 PoseColour(std::uint32_t i, int alpha) {
  const bake::PoseColour c = bake::PoseColourOf(i);
  return IM_COL32(c.r, c.g, c.b, alpha);
}

PosePad::Field PosePad::FieldOf(const Rig& rig) const {
  // The pad's domain: the baked grid, a square around it; its weight-field colours.
  Field f;
  const PoseSpaceGrid& g = rig.grid();
  const double gw = g.cell * g.cells_x, gh = g.cell * g.cells_y;
  f.span = std::max(gw, gh) * 1.1;
  f.x0 = g.origin_x + gw / 2 - f.span / 2;
  f.y0 = g.origin_y + gh / 2 - f.span / 2;
  const std::uint32_t N = rig.pose_count();
  std::vector<double> w(N);
  f.colours.resize(std::size_t(kCells) * kCells);
  for (int j = 0; j < kCells; ++j)
    for (int i = 0; i < kCells; ++i) {
      WeightsJob wj;
      wj.rig = &rig;
      wj.x = f.x0 + (i + 0.5) / kCells * f.span;
      wj.y = f.y0 + (j + 0.5) / kCells * f.span;
      wj.raw = {w.data(), N};
      wj.Run();
      const std::uint32_t top = std::uint32_t(std::max_element(w.begin(), w.end()) - w.begin());
      f.colours[std::size_t(j) * kCells + i] = PoseColour(top, int(60 + 120 * std::clamp(w[top], 0.0, 1.0)));
    }
  return f;
}

void PosePad::Build(const Rig& rig, Scene* scene) {
  body_ = FieldOf(rig);
  channels_.clear();
  for (std::uint32_t c = 1; c < rig.channel_count(); ++c) channels_.push_back(FieldOf(*rig.channel_rig(c)));
  if (rig.channel_count() > 1 && scene->channels.size() < rig.channel_count() - 1) {
    const std::size_t given = scene->channels.size();
    scene->channels.resize(rig.channel_count() - 1);
    for (std::size_t c = given; c < scene->channels.size(); ++c) {
      const Rig& channel = *rig.channel_rig(std::uint32_t(c + 1));
      scene->channels[c].x = channel.pose_points()[0], scene->channels[c].y = channel.pose_points()[1];
    }
  }
  play_channel_.assign(scene->channels.size(), 0);
  for (std::size_t c = 0; c < scene->channels.size(); ++c)
    if (!scene->channels[c].path.empty()) play_channel_[c] = 1;
}

bool PosePad::TakeMove(PoseMove* move) {
  if (!has_move_) return false;
  *move = moved_;
  has_move_ = false;
  return true;
}

bool PosePad::Draw(const Rig& rig, const Field& f, const char* id, const Gesture* trail, double* px, double* py,
                   bool movable) {
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
  const float cell = size / float(kCells);
  for (int j = 0; j < kCells; ++j)
    for (int i = 0; i < kCells; ++i) {
      const ImVec2 a(origin.x + i * cell, origin.y + (kCells - 1 - j) * cell);
      draw->AddRectFilled(a, ImVec2(a.x + cell + 1, a.y + cell + 1), f.colours[std::size_t(j) * kCells + i]);
    }
  draw->AddRect(to_screen(g.origin_x, g.origin_y + g.cell * g.cells_y),
                to_screen(g.origin_x + g.cell * g.cells_x, g.origin_y), IM_COL32(60, 60, 60, 160));
  // "move pose points": a press within 8 px of one drags it.
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  const bool moving = movable && move_points_;
  if (moving && ImGui::IsItemActivated()) {
    moving_ = -1;
    for (std::uint32_t i = 0; i < rig.pose_count(); ++i) {
      const ImVec2 p = to_screen(rig.pose_points().data[2 * i], rig.pose_points().data[2 * i + 1]);
      if (std::hypot(p.x - mouse.x, p.y - mouse.y) <= 8) moving_ = int(i);
    }
  }
  const bool dragging_point = moving && moving_ >= 0;
  if (dragging_point) {
    moving_x_ = f.x0 + (mouse.x - origin.x) / size * f.span;
    moving_y_ = f.y0 + (1 - (mouse.y - origin.y) / size) * f.span;
    if (!active) {  // let go: saved by the viewer
      moved_ = PoseMove{std::uint32_t(moving_), moving_x_, moving_y_};
      has_move_ = true;
      moving_ = -1;
    }
  }
  for (std::uint32_t i = 0; i < rig.pose_count(); ++i) {
    ImVec2 p = to_screen(rig.pose_points().data[2 * i], rig.pose_points().data[2 * i + 1]);
    if (dragging_point && int(i) == moving_) {
      draw->AddLine(p, mouse, IM_COL32(30, 30, 30, 200), 1.5f);
      p = mouse;
    }
    draw->AddCircleFilled(p, 6, PoseColour(i, 255));
    draw->AddCircle(p, 6, IM_COL32(30, 30, 30, 255));
    const StringView name = rig.pose_name(i);
    draw->AddText(ImVec2(p.x + 8, p.y - 7), IM_COL32(20, 20, 20, 255), name.data, name.data + name.size);
  }
  if (trail && trail->keys.size() > 1)
    for (std::size_t k = 1; k < trail->keys.size(); ++k)
      draw->AddLine(to_screen(trail->keys[k - 1][1], trail->keys[k - 1][2]),
                    to_screen(trail->keys[k][1], trail->keys[k][2]), IM_COL32(40, 40, 40, 200), 2);
  const ImVec2 cur = to_screen(*px, *py);
  draw->AddCircle(cur, 9, IM_COL32(255, 255, 255, 255), 0, 3);
  draw->AddCircle(cur, 11, IM_COL32(20, 20, 20, 255), 0, 1.5f);
  if (active && !dragging_point) {
    const ImVec2 m = ImGui::GetIO().MousePos;
    *px = f.x0 + (m.x - origin.x) / size * f.span;
    *py = f.y0 + (1 - (m.y - origin.y) / size) * f.span;
  }
  return active;
}

bool PosePad::Ui(const Rig& rig, Scene* scene, double* clock) {
  // The first channel's pad: dragging it stops any playback and feeds a recording gesture.
  if (rig.channel_count() > 1) {
    const StringView name = rig.channel_name(0);
    ImGui::Text("Channel 1 '%s' (drag; beyond the points extrapolates)",
                Printable(std::string(name.data, name.size), 24).c_str());
  } else {
    ImGui::TextUnformatted("Pose space (drag; beyond the points extrapolates)");
  }
  if (Draw(rig, body_, "pad", &gesture_, &scene->x, &scene->y, true) && moving_ < 0) {
    scene->path.clear();
    play_path_ = false;
    gesture_.playing = false;
    if (gesture_.recording) gesture_.keys.push_back({*clock - gesture_.start, scene->x, scene->y});
  }
  ImGui::Text("point (%.3f, %.3f)", scene->x, scene->y);
  ImGui::SameLine();
  ImGui::Checkbox("move pose points", &move_points_);

  // A pad per later channel, each with its first path's play toggle.
  for (std::uint32_t c = 1; c < rig.channel_count() && c - 1 < channels_.size(); ++c) {
    ImGui::Separator();
    const StringView name = rig.channel_name(c);
    const std::string label = Printable(std::string(name.data, name.size), 40);
    ImGui::Text("Channel %u '%s' (its own pose space)", c + 1, label.c_str());
    const Rig& channel = *rig.channel_rig(c);
    ChannelInput& in = scene->channels[c - 1];
    const std::string id = "pad" + std::to_string(c);
    if (Draw(channel, channels_[c - 1], id.c_str(), nullptr, &in.x, &in.y)) play_channel_[c - 1] = 0;
    ImGui::Text("point (%.3f, %.3f)", in.x, in.y);
    if (channel.path_count() > 0) {
      ImGui::SameLine();
      bool play = play_channel_[c - 1] != 0;
      const StringView path = channel.path(0).name;
      if (ImGui::Checkbox(("play '" + Printable(std::string(path.data, path.size), 24) + "'##" + id).c_str(), &play))
        play_channel_[c - 1] = play ? 1 : 0;
    }
  }

  ImGui::Separator();
  ImGui::TextUnformatted("Gesture");
  if (!gesture_.recording && ImGui::Button("Record")) {
    gesture_ = Gesture{};
    gesture_.recording = true;
    gesture_.start = *clock;
  } else if (gesture_.recording && ImGui::Button("Stop")) {
    gesture_.recording = false;
  }
  ImGui::SameLine();
  if (ImGui::Button(gesture_.playing ? "Pause" : "Play") && gesture_.keys.size() > 1) {
    gesture_.playing = !gesture_.playing;
    gesture_.start = *clock;
    play_path_ = false;
  }
  ImGui::SameLine();
  const bool save = ImGui::Button("Save") && gesture_.keys.size() > 1;
  ImGui::Text("%zu keys%s", gesture_.keys.size(), gesture_.recording ? ", recording" : "");

  if (rig.path_count() > 0) {
    ImGui::Separator();
    ImGui::TextUnformatted("Stored paths");
    std::vector<std::string> names;
    for (std::uint32_t i = 0; i < rig.path_count(); ++i)
      names.emplace_back(rig.path(i).name.data, rig.path(i).name.size);
    if (ImGui::BeginCombo("path", names[std::size_t(path_index_)].c_str())) {
      for (std::size_t i = 0; i < names.size(); ++i)
        if (ImGui::Selectable(names[i].c_str(), int(i) == path_index_)) path_index_ = int(i);
      ImGui::EndCombo();
    }
    ImGui::SameLine();
    if (ImGui::Checkbox("play", &play_path_) && play_path_) gesture_.playing = false, *clock = 0;
  }
  return save;
}

Scene PosePad::Shown(const Rig& rig, Scene* scene, double clock) {
  Scene shown = *scene;
  if (play_path_ && rig.path_count() > 0) {
    shown.path =
        std::string(rig.path(std::uint32_t(path_index_)).name.data, rig.path(std::uint32_t(path_index_)).name.size);
    shown.time = clock;
    SamplePath(rig, std::uint32_t(path_index_), clock, &scene->x, &scene->y);
  } else if (gesture_.playing && gesture_.keys.size() > 1) {
    const double length = gesture_.keys.back()[0];
    const double t = length > 0 ? std::fmod(clock - gesture_.start, length) : 0;
    std::size_t k = 1;
    while (k + 1 < gesture_.keys.size() && gesture_.keys[k][0] < t) ++k;
    const auto& a = gesture_.keys[k - 1];
    const auto& b = gesture_.keys[k];
    const double u = b[0] > a[0] ? std::clamp((t - a[0]) / (b[0] - a[0]), 0.0, 1.0) : 1.0;
    scene->x = shown.x = a[1] + u * (b[1] - a[1]);
    scene->y = shown.y = a[2] + u * (b[2] - a[2]);
  }
  // Later channels on their first path: each pad's point moves with it.
  for (std::size_t c = 0; c < scene->channels.size() && c < play_channel_.size(); ++c) {
    shown.channels[c].path.clear();
    if (!play_channel_[c]) continue;
    const Rig& channel = *rig.channel_rig(std::uint32_t(c + 1));
    if (channel.path_count() == 0) continue;
    const StringView name = channel.path(0).name;
    shown.channels[c].path = std::string(name.data, name.size);
    if (!play_path_) shown.time = clock;
    SamplePath(channel, 0, shown.time, &scene->channels[c].x, &scene->channels[c].y);
    shown.channels[c].x = scene->channels[c].x, shown.channels[c].y = scene->channels[c].y;
    if (shown.crowd <= 1) shown.channels[c].path.clear();
  }
  if (!shown.path.empty() && shown.crowd <= 1) shown.path.clear();  // one character sits at the sampled point
  return shown;
}

}  // namespace posemorph::viewer::window_impl
