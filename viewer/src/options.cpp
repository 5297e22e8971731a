// SPDX-License-Identifier: MIT
// posemorph-view's command line (options.h).
#include "options.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>

#include "drawings.h"
#include "posemorph/bake/command_line.h"

namespace posemorph::viewer {
namespace {

const char* kUsage =
    "usage: posemorph-view RIG.pmrig [--images DIR] [--headless -o OUT.png] [--size WxH]\n"
    "       posemorph-view --watch RIG.json [window options]\n"
    "         [--at X,Y | --path NAME [--time T] [--frames K]] [--crowd K] [--sigma S]\n"
    "         [--no-weight-limit] [--linear] [--compare] [--bases] [--wireframe] [--validation]\n"
    "         [--camera X,Y,ZOOM | --camera 1:1] [--transform T] [--seed S] [--drawings K] [--blend B]\n"
    "         [--filter linear|nearest] [--hide-part NAME]... [--joints] [--smoke-test SHOT.png [--frames K]]\n"
    "         [--description RIG.json] [--channel NAME=X,Y | --channel NAME=PATH]...\n"
    "         [--tint R,G,B[,A]] [--part-opacity NAME=A]... [--inputs TIMELINE [--fps F]]\n"
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
    "  --description window: the rig description that recorded gestures are saved into\n"
    "  --watch       window: RIG.json is a rig description: baked in memory, and baked again whenever it\n"
    "                or a drawing it names changes on disk; each new rig is swapped in without closing the\n"
    "                window, a failed bake's message shown in the panel (the last rig stays); recorded\n"
    "                gestures and edited poses are saved into it (a re-bake follows)\n"
    "  --rebakes K   with --watch and --smoke-test: end after K re-bakes (swapped in or failed), not before\n"
    "  --inputs T    a rig with a state machine: it drives the characters, its inputs set at times,\n"
    "                \"TIME:NAME[=VALUE];...\" (a bool: NAME, !NAME or NAME=true|false; a number: NAME=V;\n"
    "                a point: NAME=X,Y; a trigger: NAME or NAME=true), e.g. \"0:talking;1:wave;2.5:sway=0.4\"; "
    "headless,\n"
    "                --frames K frames (default 1) at --fps F (default 30), the states and events logged\n";

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

// A whole number in [lo, hi].
bool ParseCount(const char* text, long lo, long hi, std::uint32_t* out) {
  const std::optional<long long> v = bake::ParseWholeNumber(text, lo, hi);
  if (!v) return false;
  *out = std::uint32_t(*v);
  return true;
}
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
  else if (a == "--watch")
    o.watch = true;
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

}  // namespace

// The whole usage only when nothing was given, and on --help.
int Usage(const std::string& problem) {
  std::fprintf(stderr, "posemorph-view: %s (posemorph-view --help lists the options)\n",
               Printable(problem, 1000).c_str());
  return 2;
}

bool ParseNumber(const char* text, double lo, double hi, double* out) {
  const std::optional<double> v = bake::ParseNumber(text);
  if (!v || !(*v >= lo && *v <= hi)) return false;
  *out = *v;
  return true;
}

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
    else if (a == "--inputs" && (v = value()))
      o.inputs = v, o.has_inputs = true;
    else if (a == "--images" && (v = value()))
      o.images = v;
    else if (a == "--path" && (v = value()))
      o.scene.path = v;
    else if (a == "--time" && (v = value())) {
      if (!ParseNumber(v, -1e9, 1e9, &o.scene.time)) return Usage("--time wants seconds, a finite number");
    } else if (a == "--sigma" && (v = value())) {
      if (!ParseNumber(v, 0, 1, &o.scene.sigma)) return Usage("--sigma wants a number in 0..1");
    } else if (a == "--fps" && (v = value())) {
      if (!ParseNumber(v, 1, 1000, &o.fps)) return Usage("--fps wants updates per second, 1..1000");
    } else if (a == "--frames" && (v = value())) {
      if (!ParseCount(v, 1, 100000, &o.frames)) return Usage("--frames wants a count in 1..100000");
    } else if (a == "--rebakes" && (v = value())) {
      if (!ParseCount(v, 1, 1000, &o.window.smoke_rebakes)) return Usage("--rebakes wants a count in 1..1000");
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

}  // namespace posemorph::viewer
