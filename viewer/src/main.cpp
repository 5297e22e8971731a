// SPDX-License-Identifier: MIT
// posemorph-view: preview a baked rig. With --headless it renders offscreen
// (no window system needed) and writes PNG frames; otherwise it opens a
// window (when built with GLFW and a display is there).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sys/stat.h>

#include <new>
#include <stdexcept>
#include <string>
#include <vector>

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
    "         [--no-shear-limit] [--linear] [--compare] [--bases] [--wireframe] [--validation]\n"
    "         [--camera X,Y,ZOOM | --camera 1:1] [--transform T] [--seed S] [--drawings K] [--blend B]\n"
    "         [--filter linear|nearest] [--smoke-test SHOT.png [--frames K]] [--description RIG.json]\n"
    "  --images DIR  where the rig's drawings are (default: the rig's folder)\n"
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
    char tail = 0;
    if (item == "flip")
      flip = true;
    else if (std::sscanf(item.c_str(), "move=%lf:%lf%c", &x, &y, &tail) == 2) {
    } else if (std::sscanf(item.c_str(), "rotate=%lf%c", &degrees, &tail) == 1) {
    } else if (std::sscanf(item.c_str(), "scale=%lf:%lf%c", &sx, &sy, &tail) == 2) {
    } else if (std::sscanf(item.c_str(), "scale=%lf%c", &sx, &tail) == 1)
      sy = sx;
    else
      return false;
    at = end + 1;
  }
  const double limit = 1e6;
  for (double v : {x, y, degrees, sx, sy})
    if (!std::isfinite(v) || std::fabs(v) > limit) return false;
  if (sx == 0 || sy == 0) return false;
  *out = Transform2D::Make(x, y, degrees * 3.14159265358979323846 / 180, sx, sy, flip);
  return true;
}

// A finite number in [lo, hi], nothing after it.
bool ParseNumber(const char* text, double lo, double hi, double* out) {
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || *end != 0 || !(v >= lo && v <= hi)) return false;
  *out = v;
  return true;
}

// A whole number in [lo, hi], nothing after it.
bool ParseCount(const char* text, long lo, long hi, std::uint32_t* out) {
  char* end = nullptr;
  const long v = std::strtol(text, &end, 10);
  if (end == text || *end != 0 || v < lo || v > hi) return false;
  *out = std::uint32_t(v);
  return true;
}

int Fail(const std::string& problem) {
  std::fprintf(stderr, "posemorph-view: error: %s\n", Printable(problem, 1000).c_str());
  return 1;
}

// The rig file: a regular file (a pipe would block, a device never end) of at
// most kMaxRigFileBytes, read whole.
constexpr std::uint64_t kMaxRigFileBytes = std::uint64_t(256) << 20;
bool ReadRigFile(const std::string& path, std::vector<unsigned char>* bytes, std::string* error) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) return *error = path + ": cannot open file", false;
  if (!S_ISREG(st.st_mode)) return *error = path + ": is not a regular file (a directory, device or pipe)", false;
  if (std::uint64_t(st.st_size) > kMaxRigFileBytes)
    return *error = path + ": is " + std::to_string(st.st_size) + " bytes, more than the limit of " +
                    std::to_string(kMaxRigFileBytes) + " for a rig",
           false;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return *error = path + ": cannot open file", false;
  bytes->resize(std::size_t(st.st_size));
  const std::size_t got = bytes->empty() ? 0 : std::fread(bytes->data(), 1, bytes->size(), f);
  std::fclose(f);
  if (got != bytes->size()) return *error = path + ": cannot read the whole file", false;
  return true;
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

int Run(int argc, char** argv, std::string* rig_path_out) {
  std::string& rig_path = *rig_path_out;
  std::string images, output;
  WindowOptions window;
  bool headless = false, validation = false;
  std::uint32_t width = 640, height = 640, frames = 0;
  Scene scene;
  enum class CameraMode { kFit, kOneToOne, kGiven } camera_mode = CameraMode::kFit;
  Camera given_camera;
  Blend blend = Blend::kExact;
  if (argc < 2) return std::fputs(kUsage, stderr), 2;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") return std::fputs(kUsage, stdout), 0;
    auto value = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
    const char* v = nullptr;
    if (a == "--headless")
      headless = true;
    else if (a == "--validation")
      validation = true;
    else if (a == "--no-shear-limit")
      scene.shear_limit = false;
    else if (a == "--linear")
      scene.linear = true;
    else if (a == "--wireframe")
      scene.wireframe = true;
    else if (a == "--compare")
      scene.compare_linear = true;
    else if (a == "--bases")
      scene.show_bases = true;
    else if (a == "-o" && (v = value()))
      output = v;
    else if (a == "--smoke-test" && (v = value()))
      window.smoke_test = v;
    else if (a == "--description" && (v = value()))
      window.description = v;
    else if (a == "--images" && (v = value()))
      images = v;
    else if (a == "--path" && (v = value()))
      scene.path = v;
    else if (a == "--time" && (v = value())) {
      if (!ParseNumber(v, -1e9, 1e9, &scene.time)) return Usage("--time wants seconds, a finite number");
    } else if (a == "--sigma" && (v = value())) {
      if (!ParseNumber(v, 0, 1, &scene.sigma)) return Usage("--sigma wants a number in 0..1");
    } else if (a == "--frames" && (v = value())) {
      if (!ParseCount(v, 1, 100000, &frames)) return Usage("--frames wants a count in 1..100000");
    } else if (a == "--crowd" && (v = value())) {
      if (!ParseCount(v, 1, 100000, &scene.crowd)) return Usage("--crowd wants a count in 1..100000");
    } else if (a == "--seed" && (v = value())) {
      if (!ParseCount(v, 0, 0x7fffffff, &scene.seed)) return Usage("--seed wants a whole number >= 0");
    } else if (a == "--drawings" && (v = value())) {
      if (!ParseCount(v, 1, kDrawingsPerCharacter, &scene.max_drawings)) return Usage("--drawings wants 1..8");
    } else if (a == "--filter" && (v = value())) {
      if (std::strcmp(v, "linear") == 0)
        scene.filter = 0;
      else if (std::strcmp(v, "nearest") == 0)
        scene.filter = 1;
      else
        return Usage("--filter wants linear or nearest");
    } else if (a == "--blend" && (v = value())) {
      if (std::strcmp(v, "exact") == 0)
        blend = Blend::kExact;
      else if (std::strcmp(v, "over") == 0)
        blend = Blend::kSequentialOver;
      else
        return Usage("--blend wants exact or over");
    } else if (a == "--transform" && (v = value())) {
      if (!ParseTransform(v, &scene.transform))
        return Usage("--transform wants move=X:Y,rotate=DEGREES,scale=S|SX:SY,flip (any of them, finite, scale not 0)");
    } else if (a == "--camera" && (v = value())) {
      char tail = 0;
      if (std::strcmp(v, "1:1") == 0)
        camera_mode = CameraMode::kOneToOne;
      else if (std::sscanf(v, "%lf,%lf,%lf%c", &given_camera.centre.x, &given_camera.centre.y, &given_camera.zoom,
                           &tail) == 3 &&
               std::isfinite(given_camera.centre.x) && std::isfinite(given_camera.centre.y) &&
               given_camera.zoom >= Camera::kMinZoom && given_camera.zoom <= Camera::kMaxZoom)
        camera_mode = CameraMode::kGiven;
      else
        return Usage("--camera wants X,Y,ZOOM (ZOOM pixels per world unit, 1/256..256) or 1:1");
    } else if (a == "--size" && (v = value())) {
      if (std::sscanf(v, "%ux%u", &width, &height) != 2 || width == 0 || height == 0 || width > 8192 || height > 8192)
        return Usage("--size wants WxH, each 1..8192");
    } else if (a == "--at" && (v = value())) {
      if (std::sscanf(v, "%lf,%lf", &scene.x, &scene.y) != 2) return Usage("--at wants X,Y");
    } else if (!a.empty() && a[0] != '-' && rig_path.empty())
      rig_path = a;
    else
      return Usage("unknown or incomplete argument \"" + a + "\"");
  }
  if (rig_path.empty()) return Usage("no rig given");
  if (images.empty()) {
    const auto slash = rig_path.rfind('/');
    images = slash == std::string::npos ? "." : rig_path.substr(0, slash);
  }

  std::vector<unsigned char> bytes;
  std::string problem;
  if (!ReadRigFile(rig_path, &bytes, &problem)) return Fail(problem);
  Rig rig;
  Error err;
  if (!LoadRig(bytes.data(), bytes.size(), &rig, &err)) return Fail(rig_path + ": " + err.message);
  if (!scene.path.empty() && rig.FindPath(scene.path.c_str()) < 0)
    return Fail(rig_path + ": has no path named \"" + scene.path + "\"");
  if (frames > 0 && headless && scene.path.empty()) return Usage("--frames needs --path NAME");
  Drawings drawings;
  if (!LoadDrawings(rig, images, &drawings, &problem)) return Fail(rig_path + ": " + problem);

  if (!headless) {
    window.validation = validation;
    if (width != 640 || height != 640) window.width = width, window.height = height;
    if (frames > 0) window.smoke_frames = frames;
    return RunWindow(rig, drawings, scene, window);
  }
  if (output.empty()) return Usage("--headless needs -o OUT.png");

  Gpu gpu;
  GpuOptions options;
  options.validation = validation;
  if (!gpu.Init(options, &problem)) return Fail(problem);
  RigRenderer renderer;
  if (!renderer.Init(gpu, rig, drawings, OffscreenTarget::kFormat, SceneCharacters(rig, scene), SceneFilter(rig, scene),
                     &problem))
    return Fail(problem);
  OffscreenTarget target;
  target.Init(gpu, width, height);
  const float background[4] = {0.93f, 0.94f, 0.95f, 1.0f};

  SceneScratch scratch;
  std::vector<std::string> outputs;
  std::vector<double> times;
  if (frames > 0) {
    const int p = rig.FindPath(scene.path.c_str());
    if (scene.path.empty() || p < 0) return Fail("--frames needs a --path the rig has");
    const PathView path = rig.path(std::uint32_t(p));
    const double t0 = path.start_time(), t1 = path.end_time();
    std::string stem = output;
    if (stem.size() > 4 && stem.compare(stem.size() - 4, 4, ".png") == 0) stem.resize(stem.size() - 4);
    for (std::uint32_t f = 0; f < frames; ++f) {
      char name[32];
      std::snprintf(name, sizeof name, "-%03u.png", f);
      outputs.push_back(stem + name);
      times.push_back(t0 + (t1 - t0) * f / frames);
    }
  } else {
    outputs.push_back(output);
    times.push_back(scene.time);
  }
  for (std::size_t f = 0; f < outputs.size(); ++f) {
    scene.time = times[f];
    SceneBounds bounds;
    std::uint32_t count = 0;
    if (!PrepareScene(rig, scene, renderer, scratch, &bounds, &count, &problem)) return Fail(problem);
    Camera camera = FitCamera(bounds.all, width, height);
    if (camera_mode == CameraMode::kOneToOne) camera.zoom = 1, camera = PixelExact(camera, width, height);
    if (camera_mode == CameraMode::kGiven) {
      camera = given_camera;
      if (camera.zoom == std::round(camera.zoom)) camera = PixelExact(camera, width, height);
    }
    target.Render(
        [&](VkCommandBuffer cmd) { renderer.Record(cmd, count, camera, width, height, scene.wireframe, 0, 0, blend); },
        background);
    if (!WritePng(outputs[f], target.pixels(), width, height, &problem)) return Fail(problem);
  }
  std::printf("wrote %s%s (%ux%u, %s)\n", outputs[0].c_str(), outputs.size() > 1 ? " ..." : "", width, height,
              gpu.device_name().c_str());
  if (gpu.validation_messages() > 0)
    return std::fprintf(stderr, "posemorph-view: %d validation message(s)\n", gpu.validation_messages()), 3;
  return 0;
}

}  // namespace
