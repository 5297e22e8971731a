// SPDX-License-Identifier: MIT
// The interactive viewer's window class, shared by its files (window*.cpp,
// one job each): the swapchain, the pad, edit mode, the camera controls,
// saving into the description, the frame, and the main loop (window.cpp).
// Nothing here needs the bake: edit mode and saving into the description
// (window_edit.cpp, window_description.cpp) are the one component that
// links it, and a build with POSEMORPH_VIEWER_EDIT=OFF takes
// window_edit_off.cpp in their place.
#pragma once
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
#include <memory>

#include <glm/vec2.hpp>

#include "posemorph/jobs.h"
#include "posemorph/path.h"
#include "window.h"

namespace posemorph::viewer::window_impl {

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

// The deformer behind edit mode (the bake's ArapDeformer, window_edit.cpp).
class EditDeformer;
struct EditDeformerDelete {
  void operator()(EditDeformer* d) const;
};

// Edit mode: handles dragged on one base pose's mesh make a new pose
// (as-rigid-as-possible shape manipulation, the bake's ArapDeformer).
struct Edit {
  bool on = false;
  int pose = 0;
  std::vector<std::uint32_t> handles;
  std::vector<glm::dvec2> targets;
  std::unique_ptr<EditDeformer, EditDeformerDelete> deformer;  // for this handle set
  std::vector<glm::dvec2> rest, current;
  int dragging = -1;
};

// True when this build has edit mode and saving into the description.
bool EditModeBuilt();

struct Gesture {
  std::vector<std::array<double, 3>> keys;  // t, x, y
  bool recording = false, playing = false;
  double start = 0;
};

ImU32 PoseColour(std::uint32_t i, int alpha);  // the pad's colour of pose i (pose_colours.h)

// The vertices used by triangles of two parts or more: a layered
// character's joints, in index order.
std::vector<std::uint32_t> JointVertices(const Rig& rig);

// The joint markers' fill: a colour no sample draws, found again in screenshots.
constexpr ImU32 kJointColour = IM_COL32(255, 0, 255, 255);

class Viewer {
 public:
  Viewer(const Rig& rig, const Drawings& drawings, Scene scene, const WindowOptions& options)
      : rig_(rig),
        drawings_(drawings),
        scene_(scene),
        options_(options),
        joints_(JointVertices(rig)),
        show_joints_(options.show_joints) {}
  int Run();

 private:
  bool Open();
  void InitUi();
  void BuildPadField();
  // One channel's pad: its weight field as colours over its domain.
  struct PadField {
    std::vector<ImU32> colours;
    double x0 = 0, y0 = 0, span = 1;
  };
  PadField PadFieldOf(const Rig& rig) const;
  // Draws a pad of `rig`'s pose space with the point (x, y); true while it
  // is dragged (then (x, y) follows the mouse).
  bool DrawPad(const Rig& rig, const PadField& field, const char* id, double* x, double* y);
  void ChannelPads();  // a pad per control channel after the first
  int Close();
  void SmokeInput();
  void SmokeAfterFrame();
  int WriteSmokeShot();
  bool CreateSwapchain();
  void CreateUiPass();
  void CreateImageViews();
  void DestroySwapchain();
  void BuildUi();
  void Pad();
  // A frame in two steps around ImGui::Render: BeginFrame waits for the GPU,
  // acquires an image and evaluates the characters (false when the
  // swapchain is out of date: nothing to draw this time), so that the
  // overlays drawn before Render follow this frame's characters; EndFrame
  // records, submits and presents.
  bool BeginFrame(std::uint32_t* index, std::uint32_t* count, Scene* shown);
  void EndFrame(std::uint32_t index, std::uint32_t count, const Scene& shown, bool screenshot);
  // A marker on every joint of the characters drawn (when shown_joints_ is on).
  void JointOverlay(std::uint32_t count);
  // Frame's steps.
  Scene ShownScene();
  std::uint32_t PrepareCharacters(const Scene& shown);
  void RecordFrame(std::uint32_t index, std::uint32_t count, const Scene& shown, bool screenshot);
  void SubmitAndPresent(std::uint32_t index);
  void SaveGesture();
  void EditUi();
  void EditInput(std::int32_t x0, std::uint32_t w, std::uint32_t h);
  bool EditScene(SceneBounds* bounds, std::uint32_t* count);
  void CameraUi();
  void CameraInput(std::int32_t x0, std::uint32_t w, std::uint32_t h);
  // The gesture as a path and the edited pose as a deformation, added to the
  // rig description (bake::AddToRigDescription; the names are stems) and
  // written back atomically; the status line says what.
  void SavePose();

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
  std::vector<PadField> channel_fields_;  // channels 1 .. C-1 (index c - 1)
  std::vector<char> play_channel_;        // channel c - 1 follows its first path
  Gesture gesture_;
  std::string status_;
  bool play_path_ = false;
  int path_index_ = 0;
  double clock_ = 0;
  double eval_ms_ = 0;
  std::uint32_t smoke_frame_ = 0;
  std::chrono::steady_clock::time_point smoke_timing_start_{};
  double smoke_fps_ = 0;  // frames 10 .. half-way (before the resize)
  Edit edit_;
  // The camera: fitted to the scene every frame until the user zooms or pans.
  enum class Fit { kAll, kCharacter, kNone } fit_ = Fit::kAll;
  Camera camera_;
  bool one_to_one_ = false;  // applied once the next frame's bounds are known
  bool panning_ = false;
  std::vector<std::uint32_t> joints_;  // a layered character's joint vertices (JointVertices)
  bool show_joints_ = false;           // markers on the joints (--joints, or the panel's toggle)
  // The last overlay's markers in window pixels (the smoke test finds them in its shot).
  std::vector<ImVec2> joint_marks_;
};

// The same mapping as RigRenderer::Record: world <-> window pixels, for a
// viewport at x0 (the edited character stands at the identity transform).
struct ViewMap {
  Camera camera;
  std::int32_t x0;
  std::uint32_t w, h;
  double s() const { return camera.zoom; }
  ImVec2 ToScreen(const glm::dvec2& p) const {
    const glm::dvec2 q = viewer::ToScreen(camera, p, w, h);
    return ImVec2(float(q.x + x0), float(q.y));
  }
  glm::dvec2 ToRig(const ImVec2& q) const { return ToWorld(camera, {q.x - x0, q.y}, w, h); }
};

}  // namespace posemorph::viewer::window_impl
