// The interactive viewer window (GLFW + Vulkan swapchain).
#pragma once
#include <cstdint>

#include "scene.h"

namespace posemorph::viewer {

// Runs until the window closes; returns the process exit status.
int RunWindow(const Rig& rig, const Drawings& drawings, Scene scene, std::uint32_t width, std::uint32_t height,
              bool validation);

}  // namespace posemorph::viewer
