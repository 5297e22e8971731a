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
#include "rig_renderer.h"
#include "scene.h"
#include "window.h"

using namespace posemorph;
using namespace posemorph::viewer;

namespace {

const char* kUsage =
    "usage: posemorph-view RIG.pmrig [--images DIR] [--headless -o OUT.png] [--size WxH]\n"
    "         [--at X,Y | --path NAME [--time T] [--frames K]] [--crowd K] [--sigma S]\n"
    "         [--no-weight-limit] [--linear] [--compare] [--bases] [--wireframe] [--validation]\n"
    "         [--camera X,Y,ZOOM | --camera 1:1] [--transform T] [--seed S] [--drawings K] [--blend B]\n"
    "         [--filter linear|nearest] [--hide-part NAME]... [--joints] [--smoke-test SHOT.png [--frames K]]\n"
    "         [--description RIG.json] [--channel NAME=X,Y | --channel NAME=PATH]...\n"
    "         [--tint R,G,B[,A]] [--part-opacity NAME=A]...\n"
    "  --images DIR  where the rig's drawings are (default: where the bake found them, recorded in the rig\n"
    "                relative to its file; else the rig's folder)\n"
    "  --frames K    with --path: K frames over the path's duration, OUT-000.png ...\n"
    "  --crowd K     K characters on a ground line: seeded random places, sizes and facings\n"
    "  --seed S      the crowd's layout (default 1)\n"
    "  --camera      headless: world point X,Y at the centre, ZOOM pixels per world unit (a whole\n"
    "                ZOOM also aligns drawing pixels with screen pixels); 1:1 = fit's centre at zoom 1,\n"
    "                pixel-aligned. Default: fit the character (or the crowd)\n"
    "  --transform T one character's place, comma-separated: move=X:Y rotate=DEGREES scale=S|SX:SY flip\n"
    "                (applied as scale, flip, rotate, move; e.g. --transform rotate=30,scale=1.5,flip)\n"
    "  --drawings K  blend the K (1..8) most weighted drawings per character (default 8)\n"
    "  --filter F    sample the drawings linear or nearest (pixel art); default: as the rig asks\n"
    "  --blend B     exact (one pass, weighted sum; default) or over (sequential passes, approximate)\n"
    "  --hide-part NAME  a layered character: do not draw this part (repeatable)\n"
    "  --tint        multiply every character's colour by R,G,B and its opacity by A (each 0..1)\n"
    "  --part-opacity NAME=A  a layered character: draw this part at opacity A (0..1; repeatable)\n"
    "  --joints      window: mark a layered character's joints over the frame\n"
    "  --channel     a rig with control channels: channel NAME (after the first, which --at and --path\n"
    "                drive) at the point X,Y of its pose space, or along its path PATH (repeatable)\n"
    "  --compare     rigid (left) and linear (right) interpolation side by side\n"
    "  --bases       the N base poses in a row\n"
    "  --validation  enable the Vulkan validation layer; any message fails (exit 3)\n"
    "  --smoke-test  window: drag the pad along a circle for K frames (default 60), resizing the window\n"
    "                half-way, save a screenshot of the last frame, exit\n"
    "  --description window: the rig description that recorded gestures are saved into\n";

// A usage error: one line naming the option and what it wants (the whole
// usage only when nothing was given, and on --help).
int Usage(const std::string& problem) {
  std::fprintf(stderr, "posemorph-view: %s (posemorph-view --help lists the options)\n",
               Printable(problem, 1000).c_str());
  return 2;
}

// "move=X:Y,rotate=DEG,scale=S|SX:SY,flip" -> a transform. False on anything else.
bool ParseTransform(const std::string& text, Transform2D* out) {
  double x = 0, y = 0, degrees = 0, sx = 1, sy = 1;
  bool flip = false;
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t end = std::min(text.find(',', at), text.size());
    const std::string item = text.substr(at, end - at);
    const std::size_t eq = item.find('=');
    const std::string key = item.substr(0, eq), value = eq == std::string::npos ? "" : item.substr(eq + 1);
    const std::optional<std::vector<double>> v = bake::ParseNumbers(value, ':');
    if (item == "flip")
      flip = true;
    else if (key == "move" && v && v->size() == 2)
      x = (*v)[0], y = (*v)[1];
    else if (key == "rotate" && v && v->size() == 1)
      degrees = (*v)[0];
    else if (key == "scale" && v && (v->size() == 1 || v->size() == 2))
      sx = (*v)[0], sy = v->back();
    else
      return false;
    at = end + 1;
  }
  const double limit = 1e6;
  for (double value : {x, y, degrees, sx, sy})
    if (!(std::fabs(value) <= limit)) return false;
  if (sx == 0 || sy == 0) return false;
  *out = Transform2D::Make(x, y, degrees * 3.14159265358979323846 / 180, sx, sy, flip);
  return true;
}

// A number in [lo, hi] (bake::ParseNumber: finite, nothing after it).
bool ParseNumber(const char* text, double lo, double hi, double* out) {
  const std::optional<double> v = bake::ParseNumber(text);
  if (!v || !(*v >= lo && *v <= hi)) return false;
  *out = *v;
  return true;
}

// A whole number in [lo, hi].
bool ParseCount(const char* text, long lo, long hi, std::uint32_t* out) {
  const std::optional<long long> v = bake::ParseWholeNumber(text, lo, hi);
  if (!v) return false;
  *out = std::uint32_t(*v);
  return true;
}

int Fail(const std::string& problem) {
  std::fprintf(stderr, "posemorph-view: error: %s\n", Printable(problem, 1000).c_str());
  return 1;
}

}  // namespace

namespace {
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

// What the command line asks for.
struct Options {
  std::string rig_path, images, output;
  WindowOptions window;
  bool headless = false, validation = false;
  std::uint32_t width = 640, height = 640, frames = 0;
  Scene scene;
  enum class CameraMode { kFit, kOneToOne, kGiven } camera_mode = CameraMode::kFit;
  Camera given_camera;
  Blend blend = Blend::kExact;
  std::vector<std::string> hidden_parts;    // --hide-part, resolved once the rig is loaded
  std::vector<std::string> channels;        // --channel NAME=X,Y or NAME=PATH, resolved likewise
  std::vector<std::string> part_opacities;  // --part-opacity NAME=A, resolved likewise
};
using CameraMode = Options::CameraMode;

// The options without a value; false if `a` is none of them.
bool ParseSwitch(const std::string& a, Options& o) {
  if (a == "--headless")
    o.headless = true;
  else if (a == "--validation")
    o.validation = true;
  else if (a == "--no-weight-limit" || a == "--no-shear-limit")  // the second: its deprecated name
    o.scene.limit_weights = false;
  else if (a == "--linear")
    o.scene.linear = true;
  else if (a == "--wireframe")
    o.scene.wireframe = true;
  else if (a == "--compare")
    o.scene.compare_linear = true;
  else if (a == "--bases")
    o.scene.show_bases = true;
  else if (a == "--joints")
    o.window.show_joints = true;
  else
    return false;
  return true;
}

// --camera X,Y,ZOOM or 1:1.
bool ParseCamera(const char* v, Options& o) {
  const auto n = bake::ParseNumbers(v, ',');
  if (std::strcmp(v, "1:1") == 0) {
    o.camera_mode = CameraMode::kOneToOne;
  } else if (n && n->size() == 3 && (*n)[2] >= Camera::kMinZoom && (*n)[2] <= Camera::kMaxZoom) {
    o.camera_mode = CameraMode::kGiven;
    o.given_camera.centre = {(*n)[0], (*n)[1]};
    o.given_camera.zoom = (*n)[2];
  } else {
    return false;
  }
  return true;
}

// --size WxH, each 1..8192.
bool ParseSize(const char* v, Options& o) {
  const std::string size = v;
  const std::size_t x = size.find('x');
  std::uint32_t w = 0, h = 0;
  if (x == std::string::npos || !ParseCount(size.substr(0, x).c_str(), 1, 8192, &w) ||
      !ParseCount(size.substr(x + 1).c_str(), 1, 8192, &h))
    return false;
  o.width = w, o.height = h;
  return true;
}

// The options into `o`; -1 to go on, or the exit status (usage, --help).
int ParseOptions(int argc, char** argv, Options& o) {
  if (argc < 2) return std::fputs(kUsage, stderr), 2;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") return std::fputs(kUsage, stdout), 0;
    auto value = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
    const char* v = nullptr;
    if (ParseSwitch(a, o))
      continue;
    else if (a == "-o" && (v = value()))
      o.output = v;
    else if (a == "--smoke-test" && (v = value()))
      o.window.smoke_test = v;
    else if (a == "--description" && (v = value()))
      o.window.description = v;
    else if (a == "--hide-part" && (v = value()))
      o.hidden_parts.push_back(v);
    else if (a == "--channel" && (v = value()))
      o.channels.push_back(v);
    else if (a == "--part-opacity" && (v = value()))
      o.part_opacities.push_back(v);
    else if (a == "--images" && (v = value()))
      o.images = v;
    else if (a == "--path" && (v = value()))
      o.scene.path = v;
    else if (a == "--time" && (v = value())) {
      if (!ParseNumber(v, -1e9, 1e9, &o.scene.time)) return Usage("--time wants seconds, a finite number");
    } else if (a == "--sigma" && (v = value())) {
      if (!ParseNumber(v, 0, 1, &o.scene.sigma)) return Usage("--sigma wants a number in 0..1");
    } else if (a == "--frames" && (v = value())) {
      if (!ParseCount(v, 1, 100000, &o.frames)) return Usage("--frames wants a count in 1..100000");
    } else if (a == "--crowd" && (v = value())) {
      if (!ParseCount(v, 1, 100000, &o.scene.crowd)) return Usage("--crowd wants a count in 1..100000");
    } else if (a == "--seed" && (v = value())) {
      if (!ParseCount(v, 0, 0x7fffffff, &o.scene.seed)) return Usage("--seed wants a whole number >= 0");
    } else if (a == "--drawings" && (v = value())) {
      if (!ParseCount(v, 1, kDrawingsPerCharacter, &o.scene.max_drawings)) return Usage("--drawings wants 1..8");
    } else if (a == "--filter" && (v = value())) {
      if (std::strcmp(v, "linear") == 0)
        o.scene.filter = 0;
      else if (std::strcmp(v, "nearest") == 0)
        o.scene.filter = 1;
      else
        return Usage("--filter wants linear or nearest");
    } else if (a == "--blend" && (v = value())) {
      if (std::strcmp(v, "exact") == 0)
        o.blend = Blend::kExact;
      else if (std::strcmp(v, "over") == 0)
        o.blend = Blend::kSequentialOver;
      else
        return Usage("--blend wants exact or over");
    } else if (a == "--transform" && (v = value())) {
      if (!ParseTransform(v, &o.scene.transform))
        return Usage("--transform wants move=X:Y,rotate=DEGREES,scale=S|SX:SY,flip (any of them, finite, scale not 0)");
    } else if (a == "--camera" && (v = value())) {
      if (!ParseCamera(v, o)) return Usage("--camera wants X,Y,ZOOM (ZOOM pixels per world unit, 1/256..256) or 1:1");
    } else if (a == "--size" && (v = value())) {
      if (!ParseSize(v, o)) return Usage("--size wants WxH, each 1..8192");
    } else if (a == "--tint" && (v = value())) {
      const auto n = bake::ParseNumbers(v, ',');
      if (!n || n->size() < 3 || n->size() > 4 ||
          std::any_of(n->begin(), n->end(), [](double c) { return !(c >= 0 && c <= 1); }))
        return Usage("--tint wants R,G,B or R,G,B,A, each in 0..1");
      o.scene.colour = {float((*n)[0]), float((*n)[1]), float((*n)[2]), n->size() == 4 ? float((*n)[3]) : 1.0f};
    } else if (a == "--at" && (v = value())) {
      const auto n = bake::ParseNumbers(v, ',');
      if (!n || n->size() != 2) return Usage("--at wants X,Y");
      o.scene.x = (*n)[0], o.scene.y = (*n)[1];
    } else if (!a.empty() && a[0] != '-' && o.rig_path.empty())
      o.rig_path = a;
    else
      return Usage("unknown or incomplete argument \"" + a + "\"");
  }
  if (o.rig_path.empty()) return Usage("no rig given");
  return -1;
}

// --headless: each frame's file and the time it shows (--frames K along the
// path: OUT-000.png ...).
void HeadlessFrames(const Rig& rig, const Options& o, std::vector<std::string>* outputs, std::vector<double>* times) {
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
  if (o.frames > 0 && (o.scene.path.empty() || rig.FindPath(o.scene.path.c_str()) < 0))
    return Fail("--frames needs a --path the rig has");
  std::string problem;
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
  for (std::size_t f = 0; f < outputs.size(); ++f) {
    o.scene.time = times[f];
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
  std::vector<unsigned char> bytes;
  try {
    bytes = bake::ReadInputFile(o.rig_path, bake::kMaxRigFileBytes, "a rig");
  } catch (const bake::BakeError& e) {
    return Fail(e.what());
  }
  Rig rig;
  Error err;
  if (!LoadRig(bytes.data(), bytes.size(), &rig, &err)) return Fail(o.rig_path + ": " + err.message);
  if (!o.scene.path.empty() && rig.FindPath(o.scene.path.c_str()) < 0)
    return Fail(o.rig_path + ": has no path named \"" + o.scene.path + "\"");
  if (o.frames > 0 && o.headless && o.scene.path.empty()) return Usage("--frames needs --path NAME");
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
  if (o.images.empty()) o.images = bake::DefaultDrawingFolder(o.rig_path, rig);
  Drawings drawings;
  std::string problem;
  if (!LoadDrawings(rig, o.images, &drawings, &problem)) return Fail(o.rig_path + ": " + problem);
  if (o.headless) return RunHeadless(rig, drawings, o);
  o.window.validation = o.validation;
  if (o.width != 640 || o.height != 640) o.window.width = o.width, o.window.height = o.height;
  if (o.frames > 0) o.window.smoke_frames = o.frames;
  return RunWindow(rig, drawings, o.scene, o.window);
}

}  // namespace
