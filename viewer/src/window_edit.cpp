// SPDX-License-Identifier: MIT
// Edit mode: handles dragged on a base pose's mesh (as-rigid-as-possible, the bake's ArapDeformer) make a new pose.
// Part of the edit component (with window_description.cpp): it links the bake.
#include "posemorph/bake/arap_deformer.h"
#include "posemorph/bake/error.h"
#include "window_editor.h"

#include <algorithm>
#include <cmath>

namespace posemorph::viewer::window_impl {
namespace {

bake::Triangles RigTriangles(const Rig& rig) {
  bake::Triangles tris;
  for (std::uint32_t t = 0; t < rig.triangle_count(); ++t)
    tris.push_back({rig.triangles().data[3 * t], rig.triangles().data[3 * t + 1], rig.triangles().data[3 * t + 2]});
  return tris;
}

bake::Points ToPoints(const std::vector<glm::dvec2>& points) {
  bake::Points out;
  out.reserve(points.size());
  for (const glm::dvec2& p : points) out.emplace_back(p.x, p.y);
  return out;
}

}  // namespace

class EditDeformer {
 public:
  EditDeformer(const std::vector<glm::dvec2>& rest, const Rig& rig, const std::vector<std::uint32_t>& handles)
      : deformer_(ToPoints(rest), RigTriangles(rig), handles) {}
  // The mesh with its handles at `targets`.
  void Deform(const std::vector<glm::dvec2>& targets, std::vector<glm::dvec2>* current) {
    deformer_.Deform(ToPoints(targets), &points_);
    current->resize(points_.size());
    for (std::size_t v = 0; v < points_.size(); ++v) (*current)[v] = glm::dvec2(points_[v].x(), points_[v].y());
  }

 private:
  bake::ArapDeformer deformer_;
  bake::Points points_;
};

void EditDeformerDelete::operator()(EditDeformer* d) const { delete d; }

void Editor::Ui(const Scene& scene, std::string* status) {
  ImGui::Separator();
  ImGui::TextUnformatted("Edit (drag handles on a base pose)");
  if (ImGui::Checkbox("edit mode", &edit_.on)) edit_.dragging = -1;
  if (!edit_.on) return;
  const StringView current = rig_->pose_name(std::uint32_t(edit_.pose));
  if (ImGui::BeginCombo("from", std::string(current.data, current.size).c_str())) {
    for (std::uint32_t i = 0; i < rig_->pose_count(); ++i) {
      const StringView n = rig_->pose_name(i);
      if (ImGui::Selectable(std::string(n.data, n.size).c_str(), int(i) == edit_.pose) && int(i) != edit_.pose) {
        edit_.pose = int(i);
        edit_.handles.clear(), edit_.targets.clear(), edit_.deformer.reset();
      }
    }
    ImGui::EndCombo();
  }
  PointsUi();
  if (click_ != Click::kHandles) return;
  if (ImGui::Button("clear handles")) edit_.handles.clear(), edit_.targets.clear(), edit_.deformer.reset();
  ImGui::SameLine();
  if (ImGui::Button("save pose") && edit_.handles.size() >= 2) SavePose(scene, status);
  ImGui::Text("%zu handle(s): click the mesh to add, drag to move", edit_.handles.size());
}

void Editor::Input(const ViewMap& map, bool panning, std::string* status) {
  if (PointsInput(map, panning, status)) return;
  const ImGuiIO& io = ImGui::GetIO();
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  for (std::size_t k = 0; k < edit_.handles.size(); ++k) {
    const ImVec2 p = map.ToScreen(edit_.targets[k]);
    draw->AddCircleFilled(p, 6, IM_COL32(230, 60, 40, 230));
    draw->AddCircle(p, 7, IM_COL32(20, 20, 20, 255), 0, 1.5f);
  }
  if (io.WantCaptureMouse || io.MousePos.x < map.x0 || panning) return;
  if (io.MouseClicked[0]) {
    edit_.dragging = -1;
    for (std::size_t k = 0; k < edit_.handles.size(); ++k) {
      const ImVec2 p = map.ToScreen(edit_.targets[k]);
      if (std::hypot(p.x - io.MousePos.x, p.y - io.MousePos.y) < 9) edit_.dragging = int(k);
    }
    if (edit_.dragging < 0) {
      // A new handle on the vertex under the click (as the description's "at" handles pick it).
      std::uint32_t vertex = 0;
      const glm::dvec2 at = map.ToRig(io.MousePos);
      if (bake::HandleVertex(ToPoints(edit_.current), RigTriangles(*rig_), Eigen::Vector2d(at.x, at.y), 6 / map.s(),
                             &vertex) &&
          std::find(edit_.handles.begin(), edit_.handles.end(), vertex) == edit_.handles.end()) {
        edit_.handles.push_back(vertex);
        edit_.targets.push_back(edit_.current[vertex]);
        edit_.deformer.reset();
        edit_.dragging = int(edit_.handles.size()) - 1;
      }
    }
  }
  if (!io.MouseDown[0]) edit_.dragging = -1;
  if (edit_.dragging >= 0) edit_.targets[std::size_t(edit_.dragging)] = map.ToRig(io.MousePos);
}

bool Editor::Prepare(RigRenderer& renderer, SceneBounds* bounds, std::uint32_t* count, std::string* status) {
  const std::uint32_t V = rig_->vertex_count();
  const Span<const double> p = rig_->pose_positions(std::uint32_t(edit_.pose));
  edit_.rest.resize(V);
  for (std::uint32_t v = 0; v < V; ++v) edit_.rest[v] = glm::dvec2(p.data[2 * v], p.data[2 * v + 1]);
  edit_.current = edit_.rest;
  if (edit_.handles.size() >= 2) {
    try {
      if (!edit_.deformer) edit_.deformer.reset(new EditDeformer(edit_.rest, *rig_, edit_.handles));
      edit_.deformer->Deform(edit_.targets, &edit_.current);
    } catch (const bake::BakeError& e) {
      *status = e.what();
      edit_.current = edit_.rest;
    }
  }
  float* out = renderer.positions();
  for (std::uint32_t v = 0; v < V; ++v)
    out[2 * v] = float(edit_.current[v].x), out[2 * v + 1] = float(edit_.current[v].y);
  DrawList list;  // the edited pose's own drawing, where the character stands unmoved
  list.drawing_count = 1;
  list.drawings[0].pose = std::uint32_t(edit_.pose);
  list.drawings[0].weight = 1;
  list.parts = rig_->draw_sequence(std::uint32_t(edit_.pose));
  renderer.SetCharacter(0, list);
  bounds->all = bounds->first = CharacterBounds(*rig_);
  *count = 1;
  return true;
}

}  // namespace posemorph::viewer::window_impl

namespace posemorph::viewer {
bool EditModeBuilt() { return true; }
}  // namespace posemorph::viewer
