// SPDX-License-Identifier: MIT
// The viewer's panel and the frame's characters: the ImGui panel (the pads,
// the drawing toggles, the parts, edit mode, the camera), the characters
// evaluated into the renderer, and the joint markers over them.
#include <chrono>
#include <cstdio>
#include <string>

#include "drawings.h"
#include "window_viewer.h"

namespace posemorph::viewer::window_impl {

void Viewer::BuildUi() {
  Parts& w = parts_;
  const Rig& rig = *w.rig;
  Scene& scene = w.scene;
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(ImVec2(kPanelWidth, float(w.presenter.extent().height)));
  ImGui::Begin("posemorph", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  // A rig with a state machine: its section first (while it drives the
  // characters, the pads below do not).
  if (w.machine.Ui(rig)) ImGui::Separator();
  if (w.pad.Ui(rig, &scene, &w.clock)) w.editor.SaveGesture(w.pad.gesture(), &w.status);
  PosePad::PoseMove move{0, 0, 0};
  if (w.pad.TakeMove(&move)) {
    w.editor.SavePosePoint(move.pose, move.x, move.y, &w.status);
    std::printf("%s\n", w.status.c_str());
    std::fflush(stdout);
  }

  ImGui::Separator();
  ImGui::TextUnformatted("Drawing");
  float sigma = float(scene.sigma < 0 ? rig.default_sigma() : scene.sigma);
  if (ImGui::SliderFloat("sigma", &sigma, 0, 1)) scene.sigma = sigma;
  ImGui::Checkbox("weight limiting", &scene.limit_weights);
  ImGui::Checkbox("wireframe", &scene.wireframe);
  ImGui::Checkbox("rigid | linear side by side", &scene.compare_linear);
  ImGui::Checkbox("base drawings", &scene.show_bases);
  if (rig.part_count() > 1) {
    // A layered character's parts, back to front in pose 0: each one's toggle.
    ImGui::TextUnformatted("Parts");
    const Span<const std::uint32_t> sequence = rig.draw_sequence();
    for (std::size_t s = 0; s < sequence.size && sequence[s] < 64; ++s) {
      const std::uint32_t p = sequence[s];
      const std::string name(rig.part(p).name.data, rig.part(p).name.size);
      bool shown = !((scene.hidden_parts >> p) & 1);
      if (ImGui::Checkbox((Printable(name, 40) + "##part" + std::to_string(p)).c_str(), &shown))
        scene.hidden_parts =
            shown ? scene.hidden_parts & ~(std::uint64_t(1) << p) : scene.hidden_parts | (std::uint64_t(1) << p);
      if (s + 1 < sequence.size && (s + 1) % 4 != 0) ImGui::SameLine();
    }
    // A later channel's parts (attachments) hide likewise: "part" M + a.
    for (std::uint32_t a = 0; a < rig.attachment_count() && rig.part_count() + a < 64; ++a) {
      const std::uint32_t bit = rig.part_count() + a;
      const StringView n = rig.attachment(a).rig->part(0).name;
      bool shown = !((scene.hidden_parts >> bit) & 1);
      if (a % 4 != 0) ImGui::SameLine();
      if (ImGui::Checkbox((Printable(std::string(n.data, n.size), 40) + "##attachment" + std::to_string(a)).c_str(),
                          &shown))
        scene.hidden_parts =
            shown ? scene.hidden_parts & ~(std::uint64_t(1) << bit) : scene.hidden_parts | (std::uint64_t(1) << bit);
    }
    // The glue: each joint is one vertex of its two parts, so the parts
    // cannot come apart there in any frame.
    ImGui::TextWrapped("glue: %zu joint(s), each one vertex shared by its parts: residual 0 px in every frame",
                       w.joints.size());
    if (rig.attachment_count() > 0)
      ImGui::TextWrapped("%u part(s) of later channels, each solved on its own and pinned at its joint on the body",
                         rig.attachment_count());
    if (!w.joints.empty() || rig.attachment_count() > 0) ImGui::Checkbox("mark the joints", &w.show_joints);
  }
  w.editor.Ui(scene, &w.status);
  int crowd = int(scene.crowd);
  if (ImGui::SliderInt("crowd", &crowd, 1, int(kMaxCharacters))) scene.crowd = std::uint32_t(crowd);
  w.view.Ui();
  ImGui::Text("%.1f fps, CPU %.3f ms per frame for %u character(s)", ImGui::GetIO().Framerate, w.eval_ms,
              SceneCharacters(rig, scene));
  ImGui::TextWrapped("%s", w.presenter.device_name().c_str());
  if (!w.status.empty()) ImGui::TextWrapped("%s", w.status.c_str());
  if (w.options.watch) {
    // --watch: the bake under way, else the last re-bake's outcome.
    ImGui::Separator();
    const std::string progress = w.options.watch->Progress();
    ImGui::TextWrapped("%s", progress.empty() ? (w.watch_line.empty() ? "watching the description and its drawings"
                                                                      : w.watch_line.c_str())
                                              : progress.c_str());
  }
  ImGui::End();
}

// Each drawn character's joints where this frame puts them: the positions
// its draw list holds (rig units) through its transform and the camera (in
// edit mode, the edited pose where it stands unmoved).
void Viewer::JointOverlay(std::uint32_t count) {
  Parts& w = parts_;
  const Rig& rig = *w.rig;
  const VkExtent2D extent = w.presenter.extent();
  w.joint_marks.clear();
  if (!w.show_joints || (w.joints.empty() && rig.attachment_count() == 0) || extent.width <= kPanelWidth + 8) return;
  const ViewMap map{w.view.camera(), std::int32_t(kPanelWidth), extent.width - std::uint32_t(kPanelWidth),
                    extent.height};
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  const float right = float(extent.width), bottom = float(extent.height);
  auto mark = [&](double x, double y) {
    const ImVec2 p = map.ToScreen(glm::dvec2(x, y));
    if (!(p.x >= kPanelWidth + 8 && p.y >= 8 && p.x < right - 8 && p.y < bottom - 8)) return;  // off the view
    draw->AddCircleFilled(p, 5, kJointColour);
    draw->AddCircle(p, 6, IM_COL32(20, 20, 20, 255), 0, 1.5f);
    w.joint_marks.push_back(p);
  };
  if (w.editor.on()) {
    const std::vector<glm::dvec2>& current = w.editor.state().current;
    for (std::uint32_t v : w.joints)
      if (v < current.size()) mark(current[v].x, current[v].y);
    return;
  }
  for (std::uint32_t k = 0; k < count && k < w.scratch.lists.size(); ++k) {
    const DrawList& list = w.scratch.lists[k];
    for (std::uint32_t v : w.joints) {
      if (2 * std::size_t(v) + 1 >= list.positions.size) continue;
      double x = 0, y = 0;
      list.transform.Apply(list.positions[2 * std::size_t(v)], list.positions[2 * std::size_t(v) + 1], &x, &y);
      mark(x, y);
    }
    // A later channel's attachments: each pinned at a point of a body triangle.
    for (std::uint32_t a = 0; a < rig.attachment_count(); ++a) {
      const AttachmentView view = rig.attachment(a);
      const std::uint32_t* t = rig.triangles().data + 3 * std::size_t(view.parent_triangle);
      double px = 0, py = 0, x = 0, y = 0;
      for (int c = 0; c < 3; ++c)
        if (2 * std::size_t(t[c]) + 1 < list.positions.size)
          px += view.parent_weights[c] * list.positions[2 * std::size_t(t[c])],
              py += view.parent_weights[c] * list.positions[2 * std::size_t(t[c]) + 1];
      list.transform.Apply(px, py, &x, &y);
      mark(x, y);
    }
  }
}

// Evaluates the characters into the renderer's buffers (timed) and lets the
// camera follow them; returns how many to draw.
std::uint32_t Viewer::PrepareCharacters(const Scene& shown) {
  Parts& w = parts_;
  SceneBounds bounds;
  std::uint32_t count = 0;
  std::string problem;
  const auto t0 = std::chrono::steady_clock::now();
  RigRenderer& renderer = w.presenter.renderer();
  const bool prepared = w.editor.on() ? w.editor.Prepare(renderer, &bounds, &count, &w.status)
                                      : PrepareScene(*w.rig, shown, renderer, w.scratch, &bounds, &count, &problem);
  w.eval_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (!prepared) w.status = problem, count = 0;
  const VkExtent2D extent = w.presenter.extent();
  const std::uint32_t view_w = extent.width > kPanelWidth ? extent.width - std::uint32_t(kPanelWidth) : 1;
  if (prepared) w.view.Follow(bounds, w.editor.on(), view_w, extent.height);
  return count;
}

std::vector<std::uint32_t> JointVertices(const Rig& rig) {
  std::vector<std::uint64_t> parts(rig.vertex_count(), 0);
  for (std::uint32_t p = 0; p < rig.part_count() && p < 64; ++p) {
    const PartView part = rig.part(p);
    for (std::uint32_t t = part.first_triangle; t < part.first_triangle + part.triangle_count; ++t)
      for (int k = 0; k < 3; ++k) parts[rig.triangles()[3 * t + k]] |= std::uint64_t(1) << p;
  }
  std::vector<std::uint32_t> joints;
  for (std::uint32_t v = 0; v < rig.vertex_count(); ++v)
    if ((parts[v] & (parts[v] - 1)) != 0) joints.push_back(v);
  return joints;
}

}  // namespace posemorph::viewer::window_impl
