// SPDX-License-Identifier: MIT
// The interactive viewer: a GLFW window with a Vulkan swapchain. The rig is
// drawn with dynamic rendering, then Dear ImGui (its 1.86 Vulkan backend
// wants a render pass) draws the panel on top: the pose-space pad, gestures,
// stored paths, and the controls.
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "posemorph/bake/arap_deformer.h"
#include "posemorph/bake/bake.h"
#include "posemorph/bake/pose_colours.h"
#include "posemorph/bake/error.h"
#include "posemorph/jobs.h"
#include "posemorph/path.h"
#include "window.h"

namespace posemorph::viewer {
namespace {

constexpr float kPanelWidth = 320;
constexpr std::uint32_t kMaxCharacters = 400;
const float kBackground[4] = {0.93f, 0.94f, 0.95f, 1.0f};

struct Swapchain {
  VkSwapchainKHR handle = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent2D extent{0, 0};
  std::vector<VkImage> images;
  std::vector<VkImageView> views;
  std::vector<VkFramebuffer> framebuffers;
  std::vector<VkSemaphore> rendered;  // one per image: presentation waits on it
};

// Edit mode: handles dragged on one base pose's mesh make a new pose
// (as-rigid-as-possible shape manipulation, the bake's ArapDeformer).
struct Edit {
  bool on = false;
  int pose = 0;
  std::vector<std::uint32_t> handles;
  std::vector<Eigen::Vector2d> targets;
  std::unique_ptr<bake::ArapDeformer> deformer;  // for this handle set
  bake::Points rest, current;
  int dragging = -1;
  int saved = 0;
};

struct Gesture {
  std::vector<std::array<double, 3>> keys;  // t, x, y
  bool recording = false, playing = false;
  double start = 0;
};

// Colours of the poses in the pad (dominant pose of the weight field): the
// contact sheet's (pose_colours.h).
ImU32 PoseColour(std::uint32_t i, int alpha) {
  const bake::PoseColour c = bake::PoseColourOf(i);
  return IM_COL32(c.r, c.g, c.b, alpha);
}

class Viewer {
 public:
  Viewer(const Rig& rig, const Drawings& drawings, Scene scene, const WindowOptions& options)
      : rig_(rig), drawings_(drawings), scene_(scene), options_(options) {}
  int Run();

 private:
  bool CreateSwapchain();
  void DestroySwapchain();
  void BuildUi();
  void Pad();
  void Frame(bool screenshot);
  void SaveGesture();
  void EditUi();
  void EditInput(std::int32_t x0, std::uint32_t w, std::uint32_t h);
  bool EditScene(SceneBounds* bounds, std::uint32_t* count);
  void CameraUi();
  void CameraInput(std::int32_t x0, std::uint32_t w, std::uint32_t h);
  void SavePose();
  void ChangeDescription(const char* what, const std::function<std::string(nlohmann::json&)>& change);

  const Rig& rig_;
  const Drawings& drawings_;
  Scene scene_;
  WindowOptions options_;
  GLFWwindow* window_ = nullptr;
  Gpu gpu_;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  Swapchain sc_;
  VkRenderPass ui_pass_ = VK_NULL_HANDLE;
  VkDescriptorPool ui_pool_ = VK_NULL_HANDLE;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkSemaphore acquired_ = VK_NULL_HANDLE;
  std::unique_ptr<RigRenderer> renderer_;  // released before the device goes
  SceneScratch scratch_;
  Buffer shot_;
  bool resized_ = false;
  // Pad and playback state.
  std::vector<ImU32> field_;  // dominant-pose colour per pad cell
  int field_cells_ = 48;
  double pad_x0_ = 0, pad_y0_ = 0, pad_span_ = 1;
  Gesture gesture_;
  int saved_gestures_ = 0;
  std::string status_;
  bool play_path_ = false;
  int path_index_ = 0;
  double clock_ = 0;
  double eval_ms_ = 0;
  std::uint32_t smoke_frame_ = 0;
  Edit edit_;
  // The camera: fitted to the scene every frame until the user zooms or pans.
  enum class Fit { kAll, kCharacter, kNone } fit_ = Fit::kAll;
  Camera camera_;
  bool one_to_one_ = false;  // applied once the next frame's bounds are known
  bool panning_ = false;
};

bake::Triangles RigTriangles(const Rig& rig) {
  bake::Triangles tris;
  for (std::uint32_t t = 0; t < rig.triangle_count(); ++t)
    tris.push_back({rig.triangles().data[3 * t], rig.triangles().data[3 * t + 1], rig.triangles().data[3 * t + 2]});
  return tris;
}

// The same mapping as RigRenderer::Record: world <-> window pixels, for a
// viewport at x0 (the edited character stands at the identity transform).
struct ViewMap {
  Camera camera;
  std::int32_t x0;
  std::uint32_t w, h;
  double s() const { return camera.zoom; }
  ImVec2 ToScreen(const Eigen::Vector2d& p) const {
    const glm::dvec2 q = viewer::ToScreen(camera, {p.x(), p.y()}, w, h);
    return ImVec2(float(q.x + x0), float(q.y));
  }
  Eigen::Vector2d ToRig(const ImVec2& q) const {
    const glm::dvec2 p = ToWorld(camera, {q.x - x0, q.y}, w, h);
    return {p.x, p.y};
  }
};

bool Viewer::CreateSwapchain() {
  VkSurfaceCapabilitiesKHR caps;
  vkGetPhysicalDeviceSurfaceCapabilitiesKHR(gpu_.physical(), surface_, &caps);
  int fw = 0, fh = 0;
  glfwGetFramebufferSize(window_, &fw, &fh);
  if (fw == 0 || fh == 0) return false;  // minimised
  VkExtent2D extent =
      caps.currentExtent.width != 0xFFFFFFFFu ? caps.currentExtent : VkExtent2D{std::uint32_t(fw), std::uint32_t(fh)};
  if (extent.width == 0 || extent.height == 0) return false;
  std::uint32_t n = 0;
  vkGetPhysicalDeviceSurfaceFormatsKHR(gpu_.physical(), surface_, &n, nullptr);
  std::vector<VkSurfaceFormatKHR> formats(n);
  vkGetPhysicalDeviceSurfaceFormatsKHR(gpu_.physical(), surface_, &n, formats.data());
  VkSurfaceFormatKHR chosen = formats[0];
  for (const auto& f : formats)  // UNORM like the headless frames, so both look the same
    if (f.format == VK_FORMAT_B8G8R8A8_UNORM || f.format == VK_FORMAT_R8G8B8A8_UNORM) chosen = f;
  const std::uint32_t count =
      std::min(caps.maxImageCount ? caps.maxImageCount : 8u, std::max(caps.minImageCount + 1, 2u));
  VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  ci.surface = surface_;
  ci.minImageCount = count;
  ci.imageFormat = chosen.format;
  ci.imageColorSpace = chosen.colorSpace;
  ci.imageExtent = extent;
  ci.imageArrayLayers = 1;
  ci.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.preTransform = caps.currentTransform;
  ci.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  ci.presentMode = VK_PRESENT_MODE_FIFO_KHR;
  ci.clipped = VK_TRUE;
  ci.oldSwapchain = sc_.handle;
  VkSwapchainKHR fresh = VK_NULL_HANDLE;
  if (vkCreateSwapchainKHR(gpu_.device(), &ci, nullptr, &fresh) != VK_SUCCESS) return false;
  DestroySwapchain();
  sc_.handle = fresh;
  sc_.extent = extent;
  const bool format_changed = sc_.format != chosen.format;
  sc_.format = chosen.format;
  vkGetSwapchainImagesKHR(gpu_.device(), sc_.handle, &n, nullptr);
  sc_.images.resize(n);
  vkGetSwapchainImagesKHR(gpu_.device(), sc_.handle, &n, sc_.images.data());

  if (format_changed || !ui_pass_) {
    if (ui_pass_) vkDestroyRenderPass(gpu_.device(), ui_pass_, nullptr);
    VkAttachmentDescription at{};
    at.format = sc_.format;
    at.samples = VK_SAMPLE_COUNT_1_BIT;
    at.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;  // the rig is already there
    at.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    at.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    at.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    at.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    at.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.colorAttachmentCount = 1;
    sub.pColorAttachments = &ref;
    VkSubpassDependency dep{};
    dep.srcSubpass = VK_SUBPASS_EXTERNAL;
    dep.dstSubpass = 0;
    dep.srcStageMask = dep.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dep.srcAccessMask = dep.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_COLOR_ATTACHMENT_READ_BIT;
    VkRenderPassCreateInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    rp.attachmentCount = 1;
    rp.pAttachments = &at;
    rp.subpassCount = 1;
    rp.pSubpasses = &sub;
    rp.dependencyCount = 1;
    rp.pDependencies = &dep;
    VkCheck(vkCreateRenderPass(gpu_.device(), &rp, nullptr, &ui_pass_), "vkCreateRenderPass");
  }
  for (VkImage image : sc_.images) {
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = image;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = sc_.format;
    vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView view;
    VkCheck(vkCreateImageView(gpu_.device(), &vi, nullptr, &view), "vkCreateImageView");
    sc_.views.push_back(view);
    VkFramebufferCreateInfo fi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fi.renderPass = ui_pass_;
    fi.attachmentCount = 1;
    fi.pAttachments = &view;
    fi.width = extent.width;
    fi.height = extent.height;
    fi.layers = 1;
    VkFramebuffer fb;
    VkCheck(vkCreateFramebuffer(gpu_.device(), &fi, nullptr, &fb), "vkCreateFramebuffer");
    sc_.framebuffers.push_back(fb);
    VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore s;
    VkCheck(vkCreateSemaphore(gpu_.device(), &si, nullptr, &s), "vkCreateSemaphore");
    sc_.rendered.push_back(s);
  }
  return true;
}

void Viewer::DestroySwapchain() {
  VkDevice dev = gpu_.device();
  VkCheck(vkDeviceWaitIdle(dev), "vkDeviceWaitIdle");
  for (VkFramebuffer f : sc_.framebuffers) vkDestroyFramebuffer(dev, f, nullptr);
  for (VkImageView v : sc_.views) vkDestroyImageView(dev, v, nullptr);
  for (VkSemaphore s : sc_.rendered) vkDestroySemaphore(dev, s, nullptr);
  if (sc_.handle) vkDestroySwapchainKHR(dev, sc_.handle, nullptr);
  sc_.framebuffers.clear(), sc_.views.clear(), sc_.rendered.clear(), sc_.images.clear();
  sc_.handle = VK_NULL_HANDLE;
}

void Viewer::Pad() {
  const PoseSpaceGrid& g = rig_.grid();
  const float size = kPanelWidth - 24;
  ImGui::TextUnformatted("Pose space (drag; beyond the points extrapolates)");
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("pad", ImVec2(size, size));
  const bool active = ImGui::IsItemActive();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  auto to_screen = [&](double x, double y) {
    return ImVec2(origin.x + float((x - pad_x0_) / pad_span_ * size),
                  origin.y + float((1 - (y - pad_y0_) / pad_span_) * size));
  };
  // The weight field: each cell coloured by its dominant pose, stronger where it dominates more.
  const float cell = size / float(field_cells_);
  for (int j = 0; j < field_cells_; ++j)
    for (int i = 0; i < field_cells_; ++i) {
      const ImVec2 a(origin.x + i * cell, origin.y + (field_cells_ - 1 - j) * cell);
      draw->AddRectFilled(a, ImVec2(a.x + cell + 1, a.y + cell + 1), field_[std::size_t(j) * field_cells_ + i]);
    }
  draw->AddRect(to_screen(g.origin_x, g.origin_y + g.cell * g.cells_y),
                to_screen(g.origin_x + g.cell * g.cells_x, g.origin_y), IM_COL32(60, 60, 60, 160));
  for (std::uint32_t i = 0; i < rig_.pose_count(); ++i) {
    const ImVec2 p = to_screen(rig_.pose_points().data[2 * i], rig_.pose_points().data[2 * i + 1]);
    draw->AddCircleFilled(p, 6, PoseColour(i, 255));
    draw->AddCircle(p, 6, IM_COL32(30, 30, 30, 255));
    const StringView name = rig_.pose_name(i);
    draw->AddText(ImVec2(p.x + 8, p.y - 7), IM_COL32(20, 20, 20, 255), name.data, name.data + name.size);
  }
  if (gesture_.keys.size() > 1)
    for (std::size_t k = 1; k < gesture_.keys.size(); ++k)
      draw->AddLine(to_screen(gesture_.keys[k - 1][1], gesture_.keys[k - 1][2]),
                    to_screen(gesture_.keys[k][1], gesture_.keys[k][2]), IM_COL32(40, 40, 40, 200), 2);
  const ImVec2 cur = to_screen(scene_.x, scene_.y);
  draw->AddCircle(cur, 9, IM_COL32(255, 255, 255, 255), 0, 3);
  draw->AddCircle(cur, 11, IM_COL32(20, 20, 20, 255), 0, 1.5f);
  if (active) {
    const ImVec2 m = ImGui::GetIO().MousePos;
    scene_.x = pad_x0_ + (m.x - origin.x) / size * pad_span_;
    scene_.y = pad_y0_ + (1 - (m.y - origin.y) / size) * pad_span_;
    scene_.path.clear();
    play_path_ = false;
    gesture_.playing = false;
    if (gesture_.recording) gesture_.keys.push_back({clock_ - gesture_.start, scene_.x, scene_.y});
  }
}

// Reads the rig description, lets `change` add to it (returning what it
// added), and writes it back atomically (bake::WriteFileAtomic: a unique
// temporary beside it, then a rename).
void Viewer::ChangeDescription(const char* what, const std::function<std::string(nlohmann::json&)>& change) {
  if (options_.description.empty()) {
    status_ = std::string("start with --description RIG.json to save ") + what;
    return;
  }
  try {
    std::ifstream in(options_.description);
    if (!in) throw std::runtime_error("cannot open " + options_.description);
    nlohmann::json d = nlohmann::json::parse(in);
    const std::string added = change(d);
    const std::string text = d.dump(2) + "\n";
    bake::WriteFileAtomic(options_.description, std::vector<unsigned char>(text.begin(), text.end()));
    status_ = "saved " + added + " into " + options_.description + " (bake again to use it)";
  } catch (const std::exception& e) {
    status_ = std::string("cannot save: ") + e.what();
  }
}

// A name "<stem>-K" that no entry of d[list] has yet.
std::string FreshName(const nlohmann::json& d, const char* list, const std::string& stem, int* counter) {
  std::string name;
  do name = stem + "-" + std::to_string(++*counter);
  while (d.contains(list) && std::any_of(d[list].begin(), d[list].end(),
                                         [&](const nlohmann::json& e) { return e.value("name", "") == name; }));
  return name;
}

void Viewer::SaveGesture() {
  ChangeDescription("gestures", [&](nlohmann::json& d) {
    const std::string name = FreshName(d, "paths", "gesture", &saved_gestures_);
    nlohmann::json keys = nlohmann::json::array();
    double last = -1;
    for (const auto& k : gesture_.keys)
      if (k[0] > last + 1e-3) keys.push_back({k[0], k[1], k[2]}), last = k[0];
    d["paths"].push_back({{"name", name}, {"loop", true}, {"interpolation", "linear"}, {"keys", keys}});
    return "path \"" + name + "\"";
  });
}

void Viewer::EditUi() {
  ImGui::Separator();
  ImGui::TextUnformatted("Edit (drag handles on a base pose)");
  if (ImGui::Checkbox("edit mode", &edit_.on)) edit_.dragging = -1;
  if (!edit_.on) return;
  const StringView current = rig_.pose_name(std::uint32_t(edit_.pose));
  if (ImGui::BeginCombo("from", std::string(current.data, current.size).c_str())) {
    for (std::uint32_t i = 0; i < rig_.pose_count(); ++i) {
      const StringView n = rig_.pose_name(i);
      if (ImGui::Selectable(std::string(n.data, n.size).c_str(), int(i) == edit_.pose) && int(i) != edit_.pose) {
        edit_.pose = int(i);
        edit_.handles.clear(), edit_.targets.clear(), edit_.deformer.reset();
      }
    }
    ImGui::EndCombo();
  }
  if (ImGui::Button("clear handles")) edit_.handles.clear(), edit_.targets.clear(), edit_.deformer.reset();
  ImGui::SameLine();
  if (ImGui::Button("save pose") && edit_.handles.size() >= 2) SavePose();
  ImGui::Text("%zu handle(s): click the mesh to add, drag to move", edit_.handles.size());
}

void Viewer::EditInput(std::int32_t x0, std::uint32_t w, std::uint32_t h) {
  const ImGuiIO& io = ImGui::GetIO();
  const ViewMap map{camera_, x0, w, h};
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  for (std::size_t k = 0; k < edit_.handles.size(); ++k) {
    const ImVec2 p = map.ToScreen(edit_.targets[k]);
    draw->AddCircleFilled(p, 6, IM_COL32(230, 60, 40, 230));
    draw->AddCircle(p, 7, IM_COL32(20, 20, 20, 255), 0, 1.5f);
  }
  if (io.WantCaptureMouse || io.MousePos.x < x0 || panning_) return;
  if (io.MouseClicked[0]) {
    edit_.dragging = -1;
    for (std::size_t k = 0; k < edit_.handles.size(); ++k) {
      const ImVec2 p = map.ToScreen(edit_.targets[k]);
      if (std::hypot(p.x - io.MousePos.x, p.y - io.MousePos.y) < 9) edit_.dragging = int(k);
    }
    if (edit_.dragging < 0) {
      // A new handle on the vertex under the click (as the description's "at" handles pick it).
      std::uint32_t vertex = 0;
      if (bake::HandleVertex(edit_.current, RigTriangles(rig_), map.ToRig(io.MousePos), 6 / map.s(), &vertex) &&
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

bool Viewer::EditScene(SceneBounds* bounds, std::uint32_t* count) {
  const std::uint32_t V = rig_.vertex_count();
  const Span<const double> p = rig_.pose_positions(std::uint32_t(edit_.pose));
  edit_.rest.resize(V);
  for (std::uint32_t v = 0; v < V; ++v) edit_.rest[v] = Eigen::Vector2d(p.data[2 * v], p.data[2 * v + 1]);
  edit_.current = edit_.rest;
  if (edit_.handles.size() >= 2) {
    try {
      if (!edit_.deformer)
        edit_.deformer = std::make_unique<bake::ArapDeformer>(edit_.rest, RigTriangles(rig_), edit_.handles);
      edit_.deformer->Deform(edit_.targets, &edit_.current);
    } catch (const bake::BakeError& e) {
      status_ = e.what();
      edit_.current = edit_.rest;
    }
  }
  float* out = renderer_->positions();
  for (std::uint32_t v = 0; v < V; ++v)
    out[2 * v] = float(edit_.current[v].x()), out[2 * v + 1] = float(edit_.current[v].y());
  DrawList list;  // the edited pose's own drawing, where the character stands unmoved
  list.drawing_count = 1;
  list.drawings[0].pose = std::uint32_t(edit_.pose);
  list.drawings[0].weight = 1;
  renderer_->instances()[0] = ToInstance(list);
  bounds->all = bounds->first = CharacterBounds(rig_);
  *count = 1;
  return true;
}

void Viewer::SavePose() {
  ChangeDescription("poses", [&](nlohmann::json& d) {
    const std::string name = FreshName(d, "poses", "edit", &edit_.saved);
    const StringView from = rig_.pose_name(std::uint32_t(edit_.pose));
    nlohmann::json handles = nlohmann::json::array();
    for (std::size_t k = 0; k < edit_.handles.size(); ++k)
      handles.push_back({{"vertex", edit_.handles[k]}, {"to", {edit_.targets[k].x(), edit_.targets[k].y()}}});
    d["poses"].push_back({{"name", name},
                          {"point", {scene_.x, scene_.y}},
                          {"deform", {{"from", std::string(from.data, from.size)}, {"handles", handles}}}});
    return "pose \"" + name + "\" at the pad's point";
  });
}

void Viewer::CameraUi() {
  ImGui::Separator();
  ImGui::TextUnformatted("Camera (wheel: zoom; middle/right or space + drag: pan)");
  if (ImGui::Button("fit character")) fit_ = Fit::kCharacter;
  ImGui::SameLine();
  if (ImGui::Button("fit crowd")) fit_ = Fit::kAll;
  ImGui::SameLine();
  if (ImGui::Button("1:1")) fit_ = Fit::kNone, one_to_one_ = true;
  ImGui::Text("zoom %.3g px per unit", camera_.zoom);
}

void Viewer::CameraInput(std::int32_t x0, std::uint32_t w, std::uint32_t h) {
  const ImGuiIO& io = ImGui::GetIO();
  const glm::dvec2 cursor(io.MousePos.x - x0, io.MousePos.y);
  const bool inside = io.MousePos.x >= float(x0) && cursor.y >= 0 && cursor.y < h && !io.WantCaptureMouse;
  if (inside && io.MouseWheel != 0) {
    camera_ = ZoomAbout(camera_, cursor, std::pow(1.15, double(io.MouseWheel)), w, h);
    fit_ = Fit::kNone;
  }
  const bool space = window_ && glfwGetKey(window_, GLFW_KEY_SPACE) == GLFW_PRESS;
  const bool pan_button = io.MouseDown[1] || io.MouseDown[2] || (space && io.MouseDown[0]);
  if (!pan_button)
    panning_ = false;
  else if (inside && !panning_ && (io.MouseClicked[1] || io.MouseClicked[2] || io.MouseClicked[0]))
    panning_ = true;
  if (panning_ && (io.MouseDelta.x != 0 || io.MouseDelta.y != 0)) {
    camera_ = Pan(camera_, {io.MouseDelta.x, io.MouseDelta.y});
    fit_ = Fit::kNone;
  }
  if (!io.WantCaptureKeyboard) {
    if (ImGui::IsKeyPressed(GLFW_KEY_F)) fit_ = Fit::kCharacter;
    if (ImGui::IsKeyPressed(GLFW_KEY_A)) fit_ = Fit::kAll;
    if (ImGui::IsKeyPressed(GLFW_KEY_1)) fit_ = Fit::kNone, one_to_one_ = true;
  }
}

void Viewer::BuildUi() {
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(ImVec2(kPanelWidth, float(sc_.extent.height)));
  ImGui::Begin("posemorph", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  Pad();
  ImGui::Text("point (%.3f, %.3f)", scene_.x, scene_.y);

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
  ImGui::Checkbox("shear limiting", &scene_.shear_limit);
  ImGui::Checkbox("wireframe", &scene_.wireframe);
  ImGui::Checkbox("rigid | linear side by side", &scene_.compare_linear);
  ImGui::Checkbox("base drawings", &scene_.show_bases);
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

void Viewer::Frame(bool screenshot) {
  VkDevice dev = gpu_.device();
  VkCheck(vkWaitForFences(dev, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  if (resized_ || sc_.handle == VK_NULL_HANDLE) {
    resized_ = false;
    if (!CreateSwapchain()) return;
    ImGui_ImplVulkan_SetMinImageCount(std::uint32_t(sc_.images.size()));
  }
  std::uint32_t index = 0;
  const VkResult acquired = vkAcquireNextImageKHR(dev, sc_.handle, UINT64_MAX, acquired_, VK_NULL_HANDLE, &index);
  if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
    resized_ = true;
    return;
  }
  VkCheck(vkResetFences(dev, 1, &fence_), "vkResetFences");

  // The characters: the runtime, timed, then into the GPU buffers.
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
  if (!shown.path.empty() && shown.crowd <= 1) shown.path.clear();  // one character sits at the sampled point
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

int Viewer::Run() {
  glfwSetErrorCallback([](int, const char* text) { std::fprintf(stderr, "posemorph-view: GLFW: %s\n", text); });
  if (!glfwInit()) {
    std::fprintf(stderr, "posemorph-view: error: no display to open a window on (use --headless -o OUT.png)\n");
    return 1;
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  window_ = glfwCreateWindow(int(options_.width), int(options_.height), "posemorph", nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    std::fprintf(stderr, "posemorph-view: error: cannot open a window\n");
    return 1;
  }
  glfwSetWindowUserPointer(window_, this);
  glfwSetFramebufferSizeCallback(
      window_, [](GLFWwindow* w, int, int) { static_cast<Viewer*>(glfwGetWindowUserPointer(w))->resized_ = true; });
  GpuOptions go;
  go.validation = options_.validation;
  go.swapchain = true;
  std::uint32_t n = 0;
  const char** needed = glfwGetRequiredInstanceExtensions(&n);
  go.instance_extensions.assign(needed, needed + n);
  std::string problem;
  int status = 0;
  if (!gpu_.Init(go, &problem) || glfwCreateWindowSurface(gpu_.instance(), window_, nullptr, &surface_) != VK_SUCCESS) {
    std::fprintf(stderr, "posemorph-view: error: %s\n",
                 problem.empty() ? "cannot create a window surface" : problem.c_str());
    glfwDestroyWindow(window_);
    glfwTerminate();
    return 1;
  }
  VkBool32 present = VK_FALSE;
  vkGetPhysicalDeviceSurfaceSupportKHR(gpu_.physical(), gpu_.queue_family(), surface_, &present);
  if (!present || !CreateSwapchain()) {
    std::fprintf(stderr, "posemorph-view: error: the device cannot present to this window\n");
    return 1;
  }
  renderer_ = std::make_unique<RigRenderer>();
  if (!renderer_->Init(gpu_, rig_, drawings_, sc_.format, kMaxCharacters, SceneFilter(rig_, scene_), &problem)) {
    std::fprintf(stderr, "posemorph-view: error: %s\n", problem.c_str());
    return 1;
  }
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = gpu_.command_pool();
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCheck(vkAllocateCommandBuffers(gpu_.device(), &ai, &cmd_), "vkAllocateCommandBuffers");
  VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  fi.flags = VK_FENCE_CREATE_SIGNALED_BIT;
  VkCheck(vkCreateFence(gpu_.device(), &fi, nullptr, &fence_), "vkCreateFence");
  VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  VkCheck(vkCreateSemaphore(gpu_.device(), &si, nullptr, &acquired_), "vkCreateSemaphore");

  // Dear ImGui on the window and the swapchain's render pass.
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  ImGui::StyleColorsLight();
  ImGui_ImplGlfw_InitForVulkan(window_, true);
  VkDescriptorPoolSize ps{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16};
  VkDescriptorPoolCreateInfo dp{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  dp.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  dp.maxSets = 16;
  dp.poolSizeCount = 1;
  dp.pPoolSizes = &ps;
  VkCheck(vkCreateDescriptorPool(gpu_.device(), &dp, nullptr, &ui_pool_), "vkCreateDescriptorPool");
  ImGui_ImplVulkan_InitInfo ii{};
  ii.Instance = gpu_.instance();
  ii.PhysicalDevice = gpu_.physical();
  ii.Device = gpu_.device();
  ii.QueueFamily = gpu_.queue_family();
  ii.Queue = gpu_.queue();
  ii.DescriptorPool = ui_pool_;
  ii.MinImageCount = ii.ImageCount = std::uint32_t(sc_.images.size());
  ii.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  ImGui_ImplVulkan_Init(&ii, ui_pass_);
  gpu_.RunOnce([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();

  // The pad's domain: the baked grid, a square around it; its weight-field colours.
  const PoseSpaceGrid& g = rig_.grid();
  const double gw = g.cell * g.cells_x, gh = g.cell * g.cells_y;
  pad_span_ = std::max(gw, gh) * 1.1;
  pad_x0_ = g.origin_x + gw / 2 - pad_span_ / 2;
  pad_y0_ = g.origin_y + gh / 2 - pad_span_ / 2;
  const std::uint32_t N = rig_.pose_count();
  std::vector<double> w(N);
  field_.resize(std::size_t(field_cells_) * field_cells_);
  for (int j = 0; j < field_cells_; ++j)
    for (int i = 0; i < field_cells_; ++i) {
      WeightsJob wj;
      wj.rig = &rig_;
      wj.x = pad_x0_ + (i + 0.5) / field_cells_ * pad_span_;
      wj.y = pad_y0_ + (j + 0.5) / field_cells_ * pad_span_;
      wj.raw = {w.data(), N};
      wj.Run();
      const std::uint32_t top = std::uint32_t(std::max_element(w.begin(), w.end()) - w.begin());
      field_[std::size_t(j) * field_cells_ + i] = PoseColour(top, int(60 + 120 * std::clamp(w[top], 0.0, 1.0)));
    }

  const bool smoke = !options_.smoke_test.empty();
  auto last = std::chrono::steady_clock::now();
  auto timing_start = last;  // frames 10 .. half-way (before the resize), for the smoke test's fps
  double fps = 0;
  while (!glfwWindowShouldClose(window_)) {
    glfwPollEvents();
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window_, &fw, &fh);
    if (fw == 0 || fh == 0) {  // minimised: wait for the window to come back
      glfwWaitEvents();
      continue;
    }
    const auto now = std::chrono::steady_clock::now();
    clock_ += smoke ? 1.0 / 60 : std::chrono::duration<double>(now - last).count();
    last = now;
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    if (smoke) {
      // Drag the pad programmatically: press on it and move around a circle.
      ImGuiIO& io = ImGui::GetIO();
      const float size = kPanelWidth - 24, cx = 8 + 12 + size / 2, cy = 40 + size / 2;
      const float a = float(smoke_frame_) / float(options_.smoke_frames) * 6.2831853f;
      io.MousePos = ImVec2(cx + 0.3f * size * std::cos(a), cy + 0.3f * size * std::sin(a));
      io.MouseDown[0] = smoke_frame_ > 0 && smoke_frame_ < options_.smoke_frames / 2;
      // The camera: three wheel steps in at the middle of the view, then a right drag of 4 x 10 px.
      if (smoke_frame_ == options_.smoke_frames / 2 + 2)
        io.MousePos = ImVec2(kPanelWidth + (sc_.extent.width - kPanelWidth) / 2.0f, sc_.extent.height / 2.0f);
      const std::uint32_t drag = smoke_frame_ - options_.smoke_frames / 2;
      if (smoke_frame_ >= options_.smoke_frames / 2 + 3 && drag <= 7) {
        io.MousePos = ImVec2(kPanelWidth + 100.0f + 10.0f * float(drag - 3), 300.0f);
        io.MouseDown[1] = drag < 7;
      }
      // The drag is recorded as a gesture for the first half.
      if (smoke_frame_ == 1) gesture_ = Gesture{}, gesture_.recording = true, gesture_.start = clock_;
      if (smoke_frame_ == options_.smoke_frames / 2) gesture_.recording = false;
      if (smoke_frame_ == options_.smoke_frames * 3 / 4 && rig_.vertex_count() > 2) {
        // Then edit mode: pin vertex 0, drag the vertex farthest from it.
        edit_.on = true;
        const Span<const double> p = rig_.pose_positions(0);
        std::uint32_t far = 1;
        double best = 0;
        for (std::uint32_t v = 1; v < rig_.vertex_count(); ++v) {
          const double d = std::hypot(p.data[2 * v] - p.data[0], p.data[2 * v + 1] - p.data[1]);
          if (d > best) best = d, far = v;
        }
        edit_.handles = {0, far};
        edit_.targets = {Eigen::Vector2d(p.data[0], p.data[1]), Eigen::Vector2d(p.data[2 * far], p.data[2 * far + 1])};
      }
      if (edit_.on && edit_.targets.size() == 2)
        edit_.targets[1].x() += 0.2 * rig_.bounding_box_diagonal() / options_.smoke_frames;
    }
    ImGui::NewFrame();
    BuildUi();
    if (smoke && smoke_frame_ == options_.smoke_frames / 2 + 2) {
      ImGui::GetIO().MouseWheel = 3;  // the cursor was put in the view before NewFrame
    }
    if (sc_.extent.width > kPanelWidth + 8) {
      CameraInput(std::int32_t(kPanelWidth), sc_.extent.width - std::uint32_t(kPanelWidth), sc_.extent.height);
      if (edit_.on)
        EditInput(std::int32_t(kPanelWidth), sc_.extent.width - std::uint32_t(kPanelWidth), sc_.extent.height);
    }
    ImGui::Render();
    const bool last_frame = smoke && smoke_frame_ + 1 >= options_.smoke_frames;
    if (last_frame && !options_.description.empty()) {
      // The smoke test saves what it authored: the gesture and the edited pose.
      SaveGesture();
      std::printf("%s\n", status_.c_str());
      SavePose();
      std::printf("%s\n", status_.c_str());
    }
    Frame(last_frame);
    if (smoke && smoke_frame_ == 10) timing_start = std::chrono::steady_clock::now();
    // Half-way, the smoke test resizes the window: the swapchain is rebuilt under validation.
    if (smoke && smoke_frame_ == options_.smoke_frames / 2) {
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - timing_start).count();
      if (smoke_frame_ > 10) fps = (smoke_frame_ - 10) / seconds;
      glfwSetWindowSize(window_, int(options_.width) - 100, int(options_.height) - 60);
    }
    if (smoke && ++smoke_frame_ >= options_.smoke_frames) {
      VkCheck(vkWaitForFences(gpu_.device(), 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
      if (!shot_.buffer) {
        std::fprintf(stderr, "posemorph-view: error: no frame was drawn\n");
        status = 1;
      } else {
        // Swapchain images are BGRA or RGBA; the PNG wants RGBA.
        std::vector<unsigned char> rgba(static_cast<unsigned char*>(shot_.mapped),
                                        static_cast<unsigned char*>(shot_.mapped) + shot_.size);
        if (sc_.format == VK_FORMAT_B8G8R8A8_UNORM || sc_.format == VK_FORMAT_B8G8R8A8_SRGB)
          for (std::size_t p = 0; p < rgba.size(); p += 4) std::swap(rgba[p], rgba[p + 2]);
        if (!WritePng(options_.smoke_test, rgba.data(), sc_.extent.width, sc_.extent.height, &problem)) {
          std::fprintf(stderr, "posemorph-view: error: %s\n", problem.c_str());
          status = 1;
        } else {
          std::printf(
              "wrote %s (%ux%u window, %u frames, pad dragged to (%.3f, %.3f), %u character(s), %.1f fps at %ux%u, "
              "%s)\n",
              options_.smoke_test.c_str(), sc_.extent.width, sc_.extent.height, smoke_frame_, scene_.x, scene_.y,
              SceneCharacters(rig_, scene_), fps, options_.width, options_.height, gpu_.device_name().c_str());
          std::printf("camera: zoom %.4g pixels per unit at (%.2f, %.2f), %s\n", camera_.zoom, camera_.centre.x,
                      camera_.centre.y, fit_ == Fit::kNone ? "zoomed and panned by the user" : "fitted");
        }
      }
      break;
    }
  }

  VkCheck(vkDeviceWaitIdle(gpu_.device()), "vkDeviceWaitIdle");
  ImGui_ImplVulkan_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  if (shot_.buffer) gpu_.Destroy(shot_);
  vkDestroyDescriptorPool(gpu_.device(), ui_pool_, nullptr);
  vkDestroySemaphore(gpu_.device(), acquired_, nullptr);
  vkDestroyFence(gpu_.device(), fence_, nullptr);
  DestroySwapchain();
  vkDestroyRenderPass(gpu_.device(), ui_pass_, nullptr);
  renderer_.reset();
  vkDestroySurfaceKHR(gpu_.instance(), surface_, nullptr);
  glfwDestroyWindow(window_);
  glfwTerminate();
  if (gpu_.validation_messages() > 0) {
    std::fprintf(stderr, "posemorph-view: %d validation message(s)\n", gpu_.validation_messages());
    return 3;
  }
  return status;
}

}  // namespace

int RunWindow(const Rig& rig, const Drawings& drawings, Scene scene, const WindowOptions& options) {
  Viewer viewer(rig, drawings, scene, options);
  return viewer.Run();
}

}  // namespace posemorph::viewer
