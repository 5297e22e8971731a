// SPDX-License-Identifier: MIT
// One frame of the window: the ImGui panel, the characters, the pad and edit overlays, presentation.
#include "window_impl.h"

namespace posemorph::viewer::window_impl {

void Viewer::BuildUi() {
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(ImVec2(kPanelWidth, float(sc_.extent.height)));
  ImGui::Begin("posemorph", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  Pad();
  ImGui::Text("point (%.3f, %.3f)", scene_.x, scene_.y);
  ChannelPads();

  ImGui::Separator();
  ImGui::TextUnformatted("Gesture");
  if (!gesture_.recording && ImGui::Button("Record")) {
    gesture_ = Gesture{};
    gesture_.recording = true;
    gesture_.start = clock_;
  } else if (gesture_.recording && ImGui::Button("Stop")) {
    gesture_.recording = false;
  }
  ImGui::SameLine();
  if (ImGui::Button(gesture_.playing ? "Pause" : "Play") && gesture_.keys.size() > 1) {
    gesture_.playing = !gesture_.playing;
    gesture_.start = clock_;
    play_path_ = false;
  }
  ImGui::SameLine();
  if (ImGui::Button("Save") && gesture_.keys.size() > 1) SaveGesture();
  ImGui::Text("%zu keys%s", gesture_.keys.size(), gesture_.recording ? ", recording" : "");

  if (rig_.path_count() > 0) {
    ImGui::Separator();
    ImGui::TextUnformatted("Stored paths");
    std::vector<std::string> names;
    for (std::uint32_t i = 0; i < rig_.path_count(); ++i)
      names.emplace_back(rig_.path(i).name.data, rig_.path(i).name.size);
    if (ImGui::BeginCombo("path", names[std::size_t(path_index_)].c_str())) {
      for (std::size_t i = 0; i < names.size(); ++i)
        if (ImGui::Selectable(names[i].c_str(), int(i) == path_index_)) path_index_ = int(i);
      ImGui::EndCombo();
    }
    ImGui::SameLine();
    if (ImGui::Checkbox("play", &play_path_) && play_path_) gesture_.playing = false, clock_ = 0;
  }

  ImGui::Separator();
  ImGui::TextUnformatted("Drawing");
  float sigma = float(scene_.sigma < 0 ? rig_.default_sigma() : scene_.sigma);
  if (ImGui::SliderFloat("sigma", &sigma, 0, 1)) scene_.sigma = sigma;
  ImGui::Checkbox("weight limiting", &scene_.limit_weights);
  ImGui::Checkbox("wireframe", &scene_.wireframe);
  ImGui::Checkbox("rigid | linear side by side", &scene_.compare_linear);
  ImGui::Checkbox("base drawings", &scene_.show_bases);
  if (rig_.part_count() > 1) {
    // A layered character's parts, back to front in pose 0: each one's toggle.
    ImGui::TextUnformatted("Parts");
    const Span<const std::uint32_t> sequence = rig_.draw_sequence();
    for (std::size_t s = 0; s < sequence.size && sequence[s] < 64; ++s) {
      const std::uint32_t p = sequence[s];
      const std::string name(rig_.part(p).name.data, rig_.part(p).name.size);
      bool shown = !((scene_.hidden_parts >> p) & 1);
      if (ImGui::Checkbox((Printable(name, 40) + "##part" + std::to_string(p)).c_str(), &shown))
        scene_.hidden_parts =
            shown ? scene_.hidden_parts & ~(std::uint64_t(1) << p) : scene_.hidden_parts | (std::uint64_t(1) << p);
      if (s + 1 < sequence.size && (s + 1) % 4 != 0) ImGui::SameLine();
    }
    // A later channel's parts (attachments) hide likewise: "part" M + a.
    for (std::uint32_t a = 0; a < rig_.attachment_count() && rig_.part_count() + a < 64; ++a) {
      const std::uint32_t bit = rig_.part_count() + a;
      const StringView n = rig_.attachment(a).rig->part(0).name;
      bool shown = !((scene_.hidden_parts >> bit) & 1);
      if (a % 4 != 0) ImGui::SameLine();
      if (ImGui::Checkbox((Printable(std::string(n.data, n.size), 40) + "##attachment" + std::to_string(a)).c_str(),
                          &shown))
        scene_.hidden_parts =
            shown ? scene_.hidden_parts & ~(std::uint64_t(1) << bit) : scene_.hidden_parts | (std::uint64_t(1) << bit);
    }
    // The glue: each joint is one vertex of its two parts, so the parts
    // cannot come apart there in any frame.
    ImGui::TextWrapped("glue: %zu joint(s), each one vertex shared by its parts: residual 0 px in every frame",
                       joints_.size());
    if (rig_.attachment_count() > 0)
      ImGui::TextWrapped("%u part(s) of later channels, each solved on its own and pinned at its joint on the body",
                         rig_.attachment_count());
    if (!joints_.empty() || rig_.attachment_count() > 0) ImGui::Checkbox("mark the joints", &show_joints_);
  }
  EditUi();
  int crowd = int(scene_.crowd);
  if (ImGui::SliderInt("crowd", &crowd, 1, int(kMaxCharacters))) scene_.crowd = std::uint32_t(crowd);
  CameraUi();
  ImGui::Text("%.1f fps, CPU %.3f ms per frame for %u character(s)", ImGui::GetIO().Framerate, eval_ms_,
              SceneCharacters(rig_, scene_));
  ImGui::TextWrapped("%s", gpu_.device_name().c_str());
  if (!status_.empty()) ImGui::TextWrapped("%s", status_.c_str());
  ImGui::End();
}

bool Viewer::BeginFrame(std::uint32_t* index, std::uint32_t* count, Scene* shown) {
  VkDevice dev = gpu_.device();
  VkCheck(vkWaitForFences(dev, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  if (resized_ || sc_.handle == VK_NULL_HANDLE) {
    resized_ = false;
    if (!CreateSwapchain()) return false;
    ImGui_ImplVulkan_SetMinImageCount(std::uint32_t(sc_.images.size()));
  }
  const VkResult acquired = vkAcquireNextImageKHR(dev, sc_.handle, UINT64_MAX, acquired_, VK_NULL_HANDLE, index);
  if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
    resized_ = true;
    return false;
  }
  VkCheck(vkResetFences(dev, 1, &fence_), "vkResetFences");
  // The characters: the runtime, timed, then into the GPU buffers.
  *shown = ShownScene();
  *count = PrepareCharacters(*shown);
  return true;
}

void Viewer::EndFrame(std::uint32_t index, std::uint32_t count, const Scene& shown, bool screenshot) {
  RecordFrame(index, count, shown, screenshot);
  SubmitAndPresent(index);
}

// Each drawn character's joints where this frame puts them: the positions
// its draw list holds (rig units) through its transform and the camera (in
// edit mode, the edited pose where it stands unmoved).
void Viewer::JointOverlay(std::uint32_t count) {
  joint_marks_.clear();
  if (!show_joints_ || (joints_.empty() && rig_.attachment_count() == 0) || sc_.extent.width <= kPanelWidth + 8) return;
  const ViewMap map{camera_, std::int32_t(kPanelWidth), sc_.extent.width - std::uint32_t(kPanelWidth),
                    sc_.extent.height};
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  const float right = float(sc_.extent.width), bottom = float(sc_.extent.height);
  auto mark = [&](double x, double y) {
    const ImVec2 p = map.ToScreen(glm::dvec2(x, y));
    if (!(p.x >= kPanelWidth + 8 && p.y >= 8 && p.x < right - 8 && p.y < bottom - 8)) return;  // off the view
    draw->AddCircleFilled(p, 5, kJointColour);
    draw->AddCircle(p, 6, IM_COL32(20, 20, 20, 255), 0, 1.5f);
    joint_marks_.push_back(p);
  };
  if (edit_.on) {
    for (std::uint32_t v : joints_)
      if (v < edit_.current.size()) mark(edit_.current[v].x, edit_.current[v].y);
    return;
  }
  for (std::uint32_t k = 0; k < count && k < scratch_.lists.size(); ++k) {
    const DrawList& list = scratch_.lists[k];
    for (std::uint32_t v : joints_) {
      if (2 * std::size_t(v) + 1 >= list.positions.size) continue;
      double x = 0, y = 0;
      list.transform.Apply(list.positions[2 * std::size_t(v)], list.positions[2 * std::size_t(v) + 1], &x, &y);
      mark(x, y);
    }
    // A later channel's attachments: each pinned at a point of a body triangle.
    for (std::uint32_t a = 0; a < rig_.attachment_count(); ++a) {
      const AttachmentView view = rig_.attachment(a);
      const std::uint32_t* t = rig_.triangles().data + 3 * std::size_t(view.parent_triangle);
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

// The scene as this frame shows it: along the playing path or gesture, the
// pad's point moving with it.
Scene Viewer::ShownScene() {
  Scene shown = scene_;
  if (play_path_ && rig_.path_count() > 0) {
    shown.path =
        std::string(rig_.path(std::uint32_t(path_index_)).name.data, rig_.path(std::uint32_t(path_index_)).name.size);
    shown.time = clock_;
    SamplePath(rig_, std::uint32_t(path_index_), clock_, &scene_.x, &scene_.y);
  } else if (gesture_.playing && gesture_.keys.size() > 1) {
    const double length = gesture_.keys.back()[0];
    const double t = length > 0 ? std::fmod(clock_ - gesture_.start, length) : 0;
    std::size_t k = 1;
    while (k + 1 < gesture_.keys.size() && gesture_.keys[k][0] < t) ++k;
    const auto& a = gesture_.keys[k - 1];
    const auto& b = gesture_.keys[k];
    const double u = b[0] > a[0] ? std::clamp((t - a[0]) / (b[0] - a[0]), 0.0, 1.0) : 1.0;
    scene_.x = shown.x = a[1] + u * (b[1] - a[1]);
    scene_.y = shown.y = a[2] + u * (b[2] - a[2]);
  }
  // Later channels on their first path: each pad's point moves with it.
  for (std::size_t c = 0; c < scene_.channels.size() && c < play_channel_.size(); ++c) {
    shown.channels[c].path.clear();
    if (!play_channel_[c]) continue;
    const Rig& channel = *rig_.channel_rig(std::uint32_t(c + 1));
    if (channel.path_count() == 0) continue;
    const StringView name = channel.path(0).name;
    shown.channels[c].path = std::string(name.data, name.size);
    if (!play_path_) shown.time = clock_;
    SamplePath(channel, 0, shown.time, &scene_.channels[c].x, &scene_.channels[c].y);
    shown.channels[c].x = scene_.channels[c].x, shown.channels[c].y = scene_.channels[c].y;
    if (shown.crowd <= 1) shown.channels[c].path.clear();
  }
  if (!shown.path.empty() && shown.crowd <= 1) shown.path.clear();  // one character sits at the sampled point
  return shown;
}

// Evaluates the characters into the renderer's buffers (timed) and fits the
// camera; returns how many to draw.
std::uint32_t Viewer::PrepareCharacters(const Scene& shown) {
  SceneBounds bounds;
  std::uint32_t count = 0;
  std::string problem;
  const auto t0 = std::chrono::steady_clock::now();
  const bool prepared = edit_.on ? EditScene(&bounds, &count)
                                 : PrepareScene(rig_, shown, *renderer_, scratch_, &bounds, &count, &problem);
  eval_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (!prepared) status_ = problem, count = 0;
  const std::uint32_t view_w = sc_.extent.width > kPanelWidth ? sc_.extent.width - std::uint32_t(kPanelWidth) : 1;
  if (prepared && (fit_ != Fit::kNone || one_to_one_)) {
    camera_ = FitCamera(fit_ == Fit::kCharacter || edit_.on ? bounds.first : bounds.all, view_w, sc_.extent.height);
    if (one_to_one_) camera_.zoom = 1, camera_ = PixelExact(camera_, view_w, sc_.extent.height), one_to_one_ = false;
  }

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

// The characters, then the panel; and a copy of the image for a screenshot.
void Viewer::RecordFrame(std::uint32_t index, std::uint32_t count, const Scene& shown, bool screenshot) {
  const std::uint32_t view_w = sc_.extent.width > kPanelWidth ? sc_.extent.width - std::uint32_t(kPanelWidth) : 1;
  VkCheck(vkResetCommandBuffer(cmd_, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VkCheck(vkBeginCommandBuffer(cmd_, &bi), "vkBeginCommandBuffer");
  const VkImage image = sc_.images[index];
  Transition(cmd_, image, 1, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  VkRenderingAttachmentInfo colour{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  colour.imageView = sc_.views[index];
  colour.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  colour.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  colour.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  std::memcpy(colour.clearValue.color.float32, kBackground, sizeof kBackground);
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, sc_.extent};
  ri.layerCount = 1;
  ri.colorAttachmentCount = 1;
  ri.pColorAttachments = &colour;
  vkCmdBeginRendering(cmd_, &ri);
  const std::int32_t x0 = std::int32_t(kPanelWidth);
  if (count > 0 && sc_.extent.width > kPanelWidth + 8)
    renderer_->Record(cmd_, count, camera_, view_w, sc_.extent.height, shown.wireframe, x0, 0);
  vkCmdEndRendering(cmd_);
  VkRenderPassBeginInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  rp.renderPass = ui_pass_;
  rp.framebuffer = sc_.framebuffers[index];
  rp.renderArea = {{0, 0}, sc_.extent};
  vkCmdBeginRenderPass(cmd_, &rp, VK_SUBPASS_CONTENTS_INLINE);
  ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd_);
  vkCmdEndRenderPass(cmd_);
  if (screenshot) {
    if (shot_.buffer) gpu_.Destroy(shot_);
    shot_ = gpu_.CreateBuffer(4ull * sc_.extent.width * sc_.extent.height, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    Transition(cmd_, image, 1, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {sc_.extent.width, sc_.extent.height, 1};
    vkCmdCopyImageToBuffer(cmd_, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, shot_.buffer, 1, &copy);
    Transition(cmd_, image, 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
  }
  VkCheck(vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");
}

void Viewer::SubmitAndPresent(std::uint32_t index) {
  const VkPipelineStageFlags wait_stage = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.waitSemaphoreCount = 1;
  si.pWaitSemaphores = &acquired_;
  si.pWaitDstStageMask = &wait_stage;
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd_;
  si.signalSemaphoreCount = 1;
  si.pSignalSemaphores = &sc_.rendered[index];
  VkCheck(vkQueueSubmit(gpu_.queue(), 1, &si, fence_), "vkQueueSubmit");
  VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  pi.waitSemaphoreCount = 1;
  pi.pWaitSemaphores = &sc_.rendered[index];
  pi.swapchainCount = 1;
  pi.pSwapchains = &sc_.handle;
  pi.pImageIndices = &index;
  const VkResult presented = vkQueuePresentKHR(gpu_.queue(), &pi);
  if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR) resized_ = true;
}

}  // namespace posemorph::viewer::window_impl
