// SPDX-License-Identifier: MIT
// Edit mode's landmarks and features: the description's drawn points over
// a base pose's mesh and its outline, placed by clicking and saved into the
// description (bake::SetDrawnPoints). Part of the edit component: it links
// the bake.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>

#include "posemorph/bake/error.h"
#include "posemorph/bake/input_file.h"
#include "posemorph/bake/output_file.h"
#include "posemorph/bake/rig_description.h"
#include "window_editor.h"

namespace posemorph::viewer::window_impl {

namespace fs = std::filesystem;

// The description's drawn poses as the bake reads them: per part (the
// rig's own poses: part "") and pose, its origin and its landmarks and
// features in drawing coordinates; read again when the file changes.
class DrawnPoints {
 public:
  struct Pose {
    Eigen::Vector2d origin{0, 0};
    std::vector<Eigen::Vector2d> landmarks, features;
  };
  struct Part {
    std::string name;
    std::vector<Pose> poses;
  };
  std::vector<Part> parts;
  std::string problem;  // why the description cannot be read, or ""

  void Refresh(const std::string& description) {
    std::error_code ec;
    const fs::file_time_type time = fs::last_write_time(description, ec);
    if (read_ && !ec && time == stamp_) return;
    read_ = true, stamp_ = time, problem.clear(), parts.clear();
    try {
      const bake::RigDescription d = bake::ReadRigDescription(description);
      if (!d.channels.empty()) {
        problem = "a rig with channels: place its landmarks in the description by hand";
        return;
      }
      auto poses_of = [](const std::vector<bake::PoseDescription>& list) {
        std::vector<Pose> out;
        for (const bake::PoseDescription& p : list) out.push_back({p.origin, p.landmarks, p.features});
        return out;
      };
      if (d.parts.empty()) parts.push_back({"", poses_of(d.poses)});
      for (const bake::PartDescription& part : d.parts) parts.push_back({part.name, poses_of(part.poses)});
    } catch (const bake::BakeError& e) {
      problem = e.what();
    }
  }
  const Part* Find(const std::string& name) const {
    for (const Part& p : parts)
      if (p.name == name) return &p;
    return nullptr;
  }

 private:
  bool read_ = false;
  fs::file_time_type stamp_;
};

void DrawnPointsDelete::operator()(DrawnPoints* d) const { delete d; }

namespace {

Eigen::Vector2d InDrawing(const glm::dvec2& p, const Eigen::Vector2d& origin) {
  return {p.x + origin.x(), -p.y + origin.y()};
}
glm::dvec2 InRig(const Eigen::Vector2d& p, const Eigen::Vector2d& origin) {
  return {p.x() - origin.x(), -(p.y() - origin.y())};
}

// A rig part's outline in a pose: its boundary loop (edges of one triangle),
// counter-clockwise on screen (positive area, y up), as vertex indices.
std::vector<std::uint32_t> BoundaryLoop(const Rig& rig, std::uint32_t part, const std::vector<glm::dvec2>& at) {
  const PartView view = rig.part(part);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (std::uint32_t t = view.first_triangle; t < view.first_triangle + view.triangle_count; ++t)
    for (int k = 0; k < 3; ++k) edges.emplace_back(rig.triangles()[3 * t + k], rig.triangles()[3 * t + (k + 1) % 3]);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> sorted = edges;
  for (auto& e : sorted)
    if (e.first > e.second) std::swap(e.first, e.second);
  std::sort(sorted.begin(), sorted.end());
  std::vector<std::pair<std::uint32_t, std::uint32_t>> boundary;
  for (const auto& e : edges) {
    const auto key = std::minmax(e.first, e.second);
    const auto range = std::equal_range(sorted.begin(), sorted.end(), std::make_pair(key.first, key.second));
    if (range.second - range.first == 1) boundary.push_back(e);
  }
  if (boundary.empty()) return {};
  // Follow the directed boundary edges from the first one (the outer loop
  // of a disk-like part: one loop).
  std::vector<std::uint32_t> loop{boundary[0].first};
  std::uint32_t v = boundary[0].second;
  while (v != loop[0] && loop.size() <= boundary.size()) {
    loop.push_back(v);
    const auto next = std::find_if(boundary.begin(), boundary.end(), [&](const auto& e) { return e.first == v; });
    if (next == boundary.end()) break;
    v = next->second;
  }
  double area = 0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const glm::dvec2& a = at[loop[i]];
    const glm::dvec2& b = at[loop[(i + 1) % loop.size()]];
    area += a.x * b.y - b.x * a.y;
  }
  if (area < 0) std::reverse(loop.begin(), loop.end());
  return loop;
}

// The point of the loop nearest p, and its arc length from the loop's start.
glm::dvec2 Nearest(const std::vector<std::uint32_t>& loop, const std::vector<glm::dvec2>& at, const glm::dvec2& p,
                   double* arc) {
  double best = 1e300, run = 0;
  glm::dvec2 out = p;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const glm::dvec2 a = at[loop[i]], b = at[loop[(i + 1) % loop.size()]];
    const glm::dvec2 d = b - a;
    const double len2 = glm::dot(d, d), len = std::sqrt(len2);
    const double u = len2 > 0 ? std::clamp(glm::dot(p - a, d) / len2, 0.0, 1.0) : 0.0;
    const glm::dvec2 q = a + u * d;
    const double dist = glm::length(p - q);
    if (dist < best) best = dist, out = q, *arc = run + u * len;
    run += len;
  }
  return out;
}

double LoopLength(const std::vector<std::uint32_t>& loop, const std::vector<glm::dvec2>& at) {
  double run = 0;
  for (std::size_t i = 0; i < loop.size(); ++i) run += glm::length(at[loop[(i + 1) % loop.size()]] - at[loop[i]]);
  return run;
}

}  // namespace

void Editor::PointsUi() {
  ImGui::TextUnformatted("click adds:");
  ImGui::SameLine();
  int mode = int(click_);
  ImGui::RadioButton("handles", &mode, 0);
  ImGui::SameLine();
  ImGui::RadioButton("landmarks", &mode, 1);
  ImGui::SameLine();
  ImGui::RadioButton("features", &mode, 2);
  if (mode != int(click_)) {
    click_ = Click(mode);
    edit_.handles.clear(), edit_.targets.clear(), edit_.deformer.reset(), point_drag_ = -1;
  }
  if (click_ == Click::kHandles) return;
  if (description_.empty()) {
    ImGui::TextWrapped("start with --description RIG.json (or --watch RIG.json) to place them");
    return;
  }
  if (!points_) points_.reset(new DrawnPoints);
  points_->Refresh(description_);
  if (!points_->problem.empty()) {
    ImGui::TextWrapped("%s", points_->problem.c_str());
    return;
  }
  ImGui::TextWrapped(click_ == Click::kLandmarks
                         ? "click the outline: a landmark in every pose, in order along it; drag one to move it in "
                           "this pose; shift-click to remove it from every pose"
                         : "click the mesh: a feature in every pose; drag one to move it in this pose; shift-click "
                           "to remove it from every pose");
}

bool Editor::PointsInput(const ViewMap& map, bool panning, std::string* status) {
  if (click_ == Click::kHandles || description_.empty() || !points_ || !points_->problem.empty()) return false;
  const bool landmarks = click_ == Click::kLandmarks;
  const std::uint32_t pose = std::uint32_t(edit_.pose);
  const std::vector<glm::dvec2>& at = edit_.current;
  if (at.size() != rig_->vertex_count()) return true;
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  const ImGuiIO& io = ImGui::GetIO();
  // Each part: its outline, and its points in this pose.
  struct Shown {
    std::uint32_t part;
    const DrawnPoints::Part* points;
    std::vector<std::uint32_t> loop;
  };
  std::vector<Shown> shown;
  for (std::uint32_t p = 0; p < rig_->part_count() && p < 64; ++p) {
    const StringView n = rig_->part(p).name;
    const DrawnPoints::Part* points = points_->Find(rig_->part_count() > 1 ? std::string(n.data, n.size) : "");
    if (!points || pose >= points->poses.size()) continue;
    shown.push_back({p, points, BoundaryLoop(*rig_, p, at)});
    const std::vector<std::uint32_t>& loop = shown.back().loop;
    for (std::size_t i = 0; i < loop.size(); ++i)
      draw->AddLine(map.ToScreen(at[loop[i]]), map.ToScreen(at[loop[(i + 1) % loop.size()]]),
                    IM_COL32(20, 90, 200, 220), 1.5f);
    const DrawnPoints::Pose& dp = points->poses[pose];
    const std::vector<Eigen::Vector2d>& list = landmarks ? dp.landmarks : dp.features;
    for (std::size_t k = 0; k < list.size(); ++k) {
      const bool dragged = point_drag_ == int(k) && drag_part_ == points->name;
      const ImVec2 s = dragged ? io.MousePos : map.ToScreen(InRig(list[k], dp.origin));
      draw->AddCircleFilled(s, 6, landmarks ? IM_COL32(250, 200, 30, 240) : IM_COL32(40, 200, 120, 240));
      draw->AddCircle(s, 7, IM_COL32(20, 20, 20, 255), 0, 1.5f);
      const std::string label = std::to_string(k);
      draw->AddText(ImVec2(s.x + 8, s.y - 16), IM_COL32(20, 20, 20, 255), label.c_str());
    }
  }
  if (io.WantCaptureMouse || io.MousePos.x < map.x0 || panning) return true;
  const glm::dvec2 mouse = map.ToRig(io.MousePos);
  const std::string key = landmarks ? "landmarks" : "features";
  // The lists of every pose of `part`, changed by `change`, saved.
  auto save = [&](const DrawnPoints::Part& part, const std::string& what,
                  const std::function<void(std::vector<std::vector<Eigen::Vector2d>>&)>& change) {
    std::vector<std::vector<Eigen::Vector2d>> lists;
    for (const DrawnPoints::Pose& p : part.poses) lists.push_back(landmarks ? p.landmarks : p.features);
    change(lists);
    try {
      const std::vector<unsigned char> bytes =
          bake::ReadInputFile(description_, bake::kMaxTextFileBytes, "a rig description");
      const std::string text =
          bake::SetDrawnPoints(std::string(bytes.begin(), bytes.end()), description_, part.name, key, lists);
      bake::WriteFileAtomic(description_, std::vector<unsigned char>(text.begin(), text.end()));
      *status = what + (part.name.empty() ? "" : " of part '" + part.name + "'") + " in " + description_ +
                (watched_ ? " (baked again)" : " (bake again to use it)");
    } catch (const std::exception& e) {
      *status = std::string("cannot save: ") + e.what();
    }
    std::printf("%s\n", status->c_str());
    std::fflush(stdout);
  };
  if (io.MouseClicked[0]) {
    point_drag_ = -1;
    // On an existing point: drag it, or shift-click: remove it from every pose.
    for (const Shown& s : shown) {
      const DrawnPoints::Pose& dp = s.points->poses[pose];
      const std::vector<Eigen::Vector2d>& list = landmarks ? dp.landmarks : dp.features;
      for (std::size_t k = 0; k < list.size(); ++k) {
        const ImVec2 p = map.ToScreen(InRig(list[k], dp.origin));
        if (std::hypot(p.x - io.MousePos.x, p.y - io.MousePos.y) >= 9) continue;
        if (io.KeyShift) {
          if (landmarks && k == 0) {
            *status = "landmark 0 is the start point every pose shares: move it, it cannot go";
          } else {
            save(*s.points, "removed " + key.substr(0, key.size() - 1) + " " + std::to_string(k) + " from every pose",
                 [&](auto& lists) {
                   for (auto& l : lists)
                     if (k < l.size()) l.erase(l.begin() + std::ptrdiff_t(k));
                 });
          }
          return true;
        }
        point_drag_ = int(k), drag_part_ = s.points->name;
        return true;
      }
    }
    // Elsewhere: a new point in every pose, where this pose's mesh puts it.
    if (landmarks) {
      double best = 9 / map.s();
      const Shown* on = nullptr;
      std::uint32_t vertex = 0;
      for (const Shown& s : shown)
        for (std::uint32_t v : s.loop)
          if (glm::length(at[v] - mouse) < best) best = glm::length(at[v] - mouse), on = &s, vertex = v;
      if (!on) return true;
      // Its place among the landmarks along the outline, from landmark 0.
      const DrawnPoints::Pose& dp = on->points->poses[pose];
      const double length = LoopLength(on->loop, at);
      double start = 0, arc = 0;
      if (!dp.landmarks.empty()) Nearest(on->loop, at, InRig(dp.landmarks[0], dp.origin), &start);
      Nearest(on->loop, at, at[vertex], &arc);
      auto from_start = [&](double a) { return std::fmod(a - start + 2 * length, length); };
      std::size_t index = dp.landmarks.size();
      for (std::size_t k = 1; k < dp.landmarks.size(); ++k) {
        double ak = 0;
        Nearest(on->loop, at, InRig(dp.landmarks[k], dp.origin), &ak);
        if (from_start(ak) > from_start(arc)) {
          index = k;
          break;
        }
      }
      save(*on->points, "added landmark " + std::to_string(index) + " to every pose", [&](auto& lists) {
        for (std::size_t i = 0; i < lists.size(); ++i) {
          const Span<const double> p = rig_->pose_positions(std::uint32_t(i));
          const glm::dvec2 v(p.data[2 * vertex], p.data[2 * vertex + 1]);
          auto& l = lists[i];
          l.insert(l.begin() + std::ptrdiff_t(std::min(index, l.size())), InDrawing(v, on->points->poses[i].origin));
        }
      });
    } else {
      // The triangle under the click, and the click's barycentric place in it.
      for (const Shown& s : shown) {
        const PartView part = rig_->part(s.part);
        for (std::uint32_t t = part.first_triangle; t < part.first_triangle + part.triangle_count; ++t) {
          const std::uint32_t* tri = rig_->triangles().data + 3 * std::size_t(t);
          const glm::dvec2 a = at[tri[0]], b = at[tri[1]], c = at[tri[2]];
          const double det = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
          if (det == 0) continue;
          const double u = ((mouse.x - a.x) * (c.y - a.y) - (c.x - a.x) * (mouse.y - a.y)) / det;
          const double w = ((b.x - a.x) * (mouse.y - a.y) - (mouse.x - a.x) * (b.y - a.y)) / det;
          if (u < 0 || w < 0 || u + w > 1) continue;
          save(*s.points, "added feature " + std::to_string(s.points->poses[pose].features.size()) + " to every pose",
               [&](auto& lists) {
                 for (std::size_t i = 0; i < lists.size(); ++i) {
                   const Span<const double> p = rig_->pose_positions(std::uint32_t(i));
                   auto vertex = [&](int k) { return glm::dvec2(p.data[2 * tri[k]], p.data[2 * tri[k] + 1]); };
                   const glm::dvec2 q = (1 - u - w) * vertex(0) + u * vertex(1) + w * vertex(2);
                   lists[i].push_back(InDrawing(q, s.points->poses[i].origin));
                 }
               });
          return true;
        }
      }
    }
    return true;
  }
  if (point_drag_ >= 0 && !io.MouseDown[0]) {
    // Let go: the point moves in this pose only (a landmark onto the outline).
    const std::size_t k = std::size_t(point_drag_);
    point_drag_ = -1;
    for (const Shown& s : shown) {
      if (s.points->name != drag_part_) continue;
      double arc = 0;
      const glm::dvec2 to = landmarks ? Nearest(s.loop, at, mouse, &arc) : mouse;
      const Eigen::Vector2d in_drawing = InDrawing(to, s.points->poses[pose].origin);
      save(*s.points, "moved " + key.substr(0, key.size() - 1) + " " + std::to_string(k) + " in this pose",
           [&](auto& lists) {
             if (k < lists[pose].size()) lists[pose][k] = in_drawing;
           });
    }
  }
  return true;
}

}  // namespace posemorph::viewer::window_impl
