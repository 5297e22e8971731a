// SPDX-License-Identifier: MIT
// posemorph-view: preview a baked rig. With --headless it renders offscreen
// (no window system needed) and writes PNG frames; otherwise it opens a
// window (when built with GLFW and a display is there).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include <memory>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "posemorph/bake/command_line.h"
#include "posemorph/bake/drawing_folder.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/input_file.h"
#include "posemorph/rig.h"
#include "machine_driver.h"
#include "options.h"
#include "rig_renderer.h"
#include "watch_bake.h"

using namespace posemorph;
using namespace posemorph::viewer;

namespace {

int Fail(const std::string& problem) {
  std::fprintf(stderr, "posemorph-view: error: %s\n", Printable(problem, 1000).c_str());
  return 1;
}

int Run(int argc, char** argv, std::string* rig_path_out);
}  // namespace

// Every failure ends in one line naming the rig and the problem, exit status 1:
// a Vulkan call that failed (out of GPU memory, say) or host memory running out.
int main(int argc, char** argv) {
  std::string rig_path;
  try {
    return Run(argc, argv, &rig_path);
  } catch (const std::bad_alloc&) {
    return Fail((rig_path.empty() ? std::string("posemorph-view") : rig_path) + ": out of memory");
  } catch (const std::exception& e) {
    return Fail((rig_path.empty() ? std::string("posemorph-view") : rig_path) + ": " + e.what());
  }
}

namespace {

using CameraMode = Options::CameraMode;

// --headless: each frame's file and the time it shows (--frames K along the
// path: OUT-000.png ...).
void HeadlessFrames(const Rig& rig, const Options& o, std::vector<std::string>* outputs, std::vector<double>* times) {
  if (o.has_inputs) {  // frame f at f / fps, the state machine stepped to it
    std::string stem = o.output;
    if (stem.size() > 4 && stem.compare(stem.size() - 4, 4, ".png") == 0) stem.resize(stem.size() - 4);
    const std::uint32_t frames = std::max<std::uint32_t>(o.frames, 1);
    for (std::uint32_t f = 0; f < frames; ++f) {
      char name[32];
      std::snprintf(name, sizeof name, "-%03u.png", f);
      outputs->push_back(o.frames == 0 ? o.output : stem + name);
      times->push_back(f / o.fps);
    }
    return;
  }
  if (o.frames == 0) {
    outputs->push_back(o.output);
    times->push_back(o.scene.time);
    return;
  }
  const PathView path = rig.path(std::uint32_t(rig.FindPath(o.scene.path.c_str())));
  const double t0 = path.start_time(), t1 = path.end_time();
  std::string stem = o.output;
  if (stem.size() > 4 && stem.compare(stem.size() - 4, 4, ".png") == 0) stem.resize(stem.size() - 4);
  for (std::uint32_t f = 0; f < o.frames; ++f) {
    char name[32];
    std::snprintf(name, sizeof name, "-%03u.png", f);
    outputs->push_back(stem + name);
    times->push_back(t0 + (t1 - t0) * f / o.frames);
  }
}

// Renders the frames offscreen and writes them as PNG files.
int RunHeadless(const Rig& rig, const Drawings& drawings, Options& o) {
  if (o.output.empty()) return Usage("--headless needs -o OUT.png");
  if (o.frames > 0 && !o.has_inputs && (o.scene.path.empty() || rig.FindPath(o.scene.path.c_str()) < 0))
    return Fail("--frames needs a --path the rig has (or --inputs)");
  MachineDriver machine;
  const std::vector<InputCommand>& timeline = o.window.timeline;  // parsed once, in Run
  std::string problem;
  if (o.window.machine) {
    if (!machine.Init(rig, SceneCharacters(rig, o.scene), &problem)) return Fail(o.rig_path + ": " + problem);
    o.scene.machine = &machine;
  }
  Gpu gpu;
  GpuOptions gpu_options;
  gpu_options.validation = o.validation;
  if (!gpu.Init(gpu_options, &problem)) return Fail(problem);
  RigRenderer renderer;
  if (!renderer.Init(gpu, rig, drawings, OffscreenTarget::kFormat, SceneCharacters(rig, o.scene),
                     SceneFilter(rig, o.scene), &problem))
    return Fail(problem);
  OffscreenTarget target;
  target.Init(gpu, o.width, o.height);
  const float background[4] = {0.93f, 0.94f, 0.95f, 1.0f};
  SceneScratch scratch;
  std::vector<std::string> outputs;
  std::vector<double> times;
  HeadlessFrames(rig, o, &outputs, &times);
  const std::uint32_t width = o.width, height = o.height;
  std::size_t logged = 0;
  for (std::size_t f = 0; f < outputs.size(); ++f) {
    o.scene.time = times[f];
    if (machine.active()) {  // one update per frame: the first enters the initial states
      if (!machine.Advance(f == 0 ? 0 : 1 / o.fps, timeline)) return Fail("the state machine's step failed");
      for (; logged < machine.log().size(); ++logged) std::printf("%s\n", machine.log()[logged].c_str());
    }
    SceneBounds bounds;
    std::uint32_t count = 0;
    if (!PrepareScene(rig, o.scene, renderer, scratch, &bounds, &count, &problem)) return Fail(problem);
    Camera camera = FitCamera(bounds.all, width, height);
    if (o.camera_mode == CameraMode::kOneToOne) camera.zoom = 1, camera = PixelExact(camera, width, height);
    if (o.camera_mode == CameraMode::kGiven) {
      camera = o.given_camera;
      if (camera.zoom == std::round(camera.zoom)) camera = PixelExact(camera, width, height);
    }
    target.Render(
        [&](VkCommandBuffer cmd) {
          renderer.Record(cmd, count, camera, width, height, o.scene.wireframe, 0, 0, o.blend);
        },
        background);
    if (!WritePng(outputs[f], target.pixels(), width, height, &problem)) return Fail(problem);
  }
  std::printf("wrote %s%s (%ux%u, %s)\n", outputs[0].c_str(), outputs.size() > 1 ? " ..." : "", width, height,
              gpu.device_name().c_str());
  if (gpu.validation_messages() > 0)
    return std::fprintf(stderr, "posemorph-view: %d validation message(s)\n", gpu.validation_messages()), 3;
  return 0;
}

int Run(int argc, char** argv, std::string* rig_path_out) {
  Options o;
  if (const int status = ParseOptions(argc, argv, o); status >= 0) return status;
  *rig_path_out = o.rig_path;
  // --watch: the description is baked here, and watched from the window.
  std::unique_ptr<BakedRig> first;
  std::unique_ptr<WatchedBake> watch;
  Rig loaded;
  if (o.watch) {
    if (o.headless) return Usage("--watch is for the window (not --headless)");
    if (!o.images.empty()) return Usage("--watch reads the drawings from the description's folder (not --images)");
    if (!EditModeBuilt()) return Usage("--watch needs a posemorph-view built with the bake (POSEMORPH_VIEWER_EDIT=ON)");
    if (o.rig_path.size() < 5 || o.rig_path.compare(o.rig_path.size() - 5, 5, ".json") != 0)
      return Usage("--watch takes a rig description (RIG.json), not a baked rig");
    std::string problem;
    watch = WatchDescription(o.rig_path, &first, &problem);
    if (!watch) return Fail(problem);
    std::printf("posemorph-view: %s; watching it and its drawings\n", Printable(first->summary, 2000).c_str());
    std::fflush(stdout);
    if (o.window.description.empty()) o.window.description = o.rig_path;
    o.window.watch = watch.get();
  } else {
    std::vector<unsigned char> bytes;
    try {
      bytes = bake::ReadInputFile(o.rig_path, bake::kMaxRigFileBytes, "a rig");
    } catch (const bake::BakeError& e) {
      return Fail(e.what());
    }
    Error err;
    if (!LoadRig(bytes.data(), bytes.size(), &loaded, &err)) return Fail(o.rig_path + ": " + err.message);
  }
  if (o.window.smoke_rebakes > 0 && (!o.watch || o.window.smoke_test.empty()))
    return Usage("--rebakes goes with --watch and --smoke-test");
  const Rig& rig = o.watch ? first->rig : loaded;
  if (!o.scene.path.empty() && rig.FindPath(o.scene.path.c_str()) < 0)
    return Fail(o.rig_path + ": has no path named \"" + o.scene.path + "\"");
  if (o.frames > 0 && o.headless && o.scene.path.empty() && !o.has_inputs)
    return Usage("--frames needs --path NAME (or --inputs)");
  if (o.has_inputs && (o.scene.show_bases || o.scene.compare_linear || !o.scene.path.empty() || !o.channels.empty()))
    return Usage("--inputs drives the characters: not with --path, --channel, --bases or --compare");
  if (o.has_inputs) {  // the timeline, for the headless frames and the window alike
    std::string problem;
    if (!ParseInputTimeline(rig, o.inputs, &o.window.timeline, &problem)) return Fail(o.rig_path + ": " + problem);
    o.window.machine = true;
  }
  if (!EditModeBuilt() && !o.window.description.empty())
    return Usage("--description needs a posemorph-view built with edit mode (POSEMORPH_VIEWER_EDIT=ON)");
  for (const std::string& name : o.hidden_parts) {
    std::string names;
    bool found = false;
    for (std::uint32_t p = 0; p < rig.part_count() && p < 64; ++p) {
      const std::string part(rig.part(p).name.data, rig.part(p).name.size);
      if (part == name && rig.part_count() > 1) o.scene.hidden_parts |= std::uint64_t(1) << p, found = true;
      names += (names.empty() ? "'" : ", '") + part + "'";
    }
    for (std::uint32_t a = 0; a < rig.attachment_count() && rig.part_count() + a < 64; ++a) {
      const StringView n = rig.attachment(a).rig->part(0).name;
      const std::string part(n.data, n.size);
      if (part == name) o.scene.hidden_parts |= std::uint64_t(1) << (rig.part_count() + a), found = true;
      names += (names.empty() ? "'" : ", '") + part + "'";
    }
    if (!found)
      return Fail(o.rig_path + ": " +
                  (rig.part_count() > 1 ? "has no part '" + name + "' (" + names + ")"
                                        : std::string("has no parts, so --hide-part has nothing to hide")));
  }
  for (const std::string& entry : o.part_opacities) {
    const std::size_t eq = entry.find('=');
    double opacity = 0;
    if (eq == std::string::npos || !ParseNumber(entry.c_str() + eq + 1, 0, 1, &opacity))
      return Usage("--part-opacity wants NAME=A, A in 0..1");
    int p = -1;
    for (std::uint32_t q = 0; q < rig.part_count() && rig.part_count() > 1; ++q)
      if (std::string(rig.part(q).name.data, rig.part(q).name.size) == entry.substr(0, eq)) p = int(q);
    if (p < 0)
      return Fail(o.rig_path + ": " +
                  (rig.part_count() > 1 ? "has no part '" + entry.substr(0, eq) + "'"
                                        : std::string("has no parts (--part-opacity)")));
    o.scene.part_opacities.resize(rig.part_count(), 1.0f);
    o.scene.part_opacities[std::size_t(p)] = float(opacity);
  }
  for (const std::string& entry : o.channels) {
    const std::size_t eq = entry.find('=');
    const std::string name = entry.substr(0, eq);
    const int c = eq == std::string::npos ? -1 : rig.FindChannel(name.c_str());
    if (eq == std::string::npos) return Usage("--channel wants NAME=X,Y or NAME=PATH");
    if (c <= 0)
      return Fail(o.rig_path + ": " +
                  (rig.channel_count() < 2 ? std::string("has one control channel; --channel names a later one")
                                           : "has no channel '" + name + "' after the first"));
    o.scene.channels.resize(rig.channel_count() - 1);
    const Rig& channel = *rig.channel_rig(std::uint32_t(c));
    ChannelInput& in = o.scene.channels[std::size_t(c) - 1];
    in.x = channel.pose_points()[0], in.y = channel.pose_points()[1];
    const std::string value = entry.substr(eq + 1);
    const auto point = bake::ParseNumbers(value, ',');
    if (point && point->size() == 2) {
      in.x = (*point)[0], in.y = (*point)[1];
    } else if (channel.FindPath(value.c_str()) >= 0) {
      in.path = value;
    } else {
      return Fail(o.rig_path + ": channel '" + name + "' has no path named \"" + value + "\" (give X,Y or a path)");
    }
  }
  Drawings loaded_drawings;
  if (!o.watch) {
    if (o.images.empty()) o.images = bake::DefaultDrawingFolder(o.rig_path, rig);
    std::string problem;
    const std::string rig_dir = std::filesystem::path(o.rig_path).parent_path().string();
    if (!LoadDrawings(rig, o.images, &loaded_drawings, &problem, rig_dir)) return Fail(o.rig_path + ": " + problem);
  }
  const Drawings& drawings = o.watch ? first->drawings : loaded_drawings;
  if (o.headless) return RunHeadless(rig, drawings, o);
  o.window.validation = o.validation;
  if (o.width != 640 || o.height != 640) o.window.width = o.width, o.window.height = o.height;
  if (o.frames > 0) o.window.smoke_frames = o.frames;
  return RunWindow(rig, drawings, o.scene, o.window);
}

}  // namespace
