// SPDX-License-Identifier: MIT
// posemorph-bake eval RIG.pmrig: frames at pose-space points or along a path.
#include "commands.h"

#include <algorithm>
#include <cstdio>

#include "command_args.h"
#include "posemorph/bake/error.h"
#include "posemorph/path.h"
#include "posemorph/rig.h"
#include "preview.h"

namespace posemorph::bake::cli {

int EvalCommand(const std::vector<std::string>& a, std::size_t from, std::ostream& out) {
  const Args args = Args::Parse(a, from, {"-o", "--at", "--path", "--time", "--frames", "--sigma"},
                                {"--no-weight-limit", "--no-shear-limit", "--linear"});
  if (args.positional.empty()) throw UsageError("no rig file given");
  const std::string* output = args.Get("-o");
  if (!output) throw UsageError("eval needs -o OUT.svg|.json|.obj");
  const std::string ext = Extension(*output);
  if (ext != "svg" && ext != "json" && ext != "obj") throw UsageError("-o " + *output + ": use .svg, .json or .obj");
  const std::string *at = args.Get("--at"), *path_name = args.Get("--path");
  if (!at == !path_name) throw UsageError("give exactly one of --at X,Y or --path NAME");
  const EvalOptions options = ReadEvalOptions(args);
  double at_x = 0, at_y = 0;
  if (at) {
    const auto comma = at->find(',');
    if (comma == std::string::npos) throw UsageError("--at: expected X,Y");
    at_x = NumberOption("--at", at->substr(0, comma));
    at_y = NumberOption("--at", at->substr(comma + 1));
  }
  const Rig rig = LoadRigFile(args.positional);

  std::vector<Frame> frames;
  char label[96];
  if (at) {
    const double x = at_x, y = at_y;
    frames.push_back(EvaluateFrame(rig, x, y, options));
    std::snprintf(label, sizeof label, "(%.3g, %.3g)", x, y);
    frames.back().label = label;
  } else {
    const int index = rig.FindPath(path_name->c_str());
    if (index < 0) throw BakeError(args.positional, "has no path named '" + *path_name + "'");
    const PathView path = rig.path(std::uint32_t(index));
    const double t0 = path.start_time(), t1 = path.end_time();
    std::vector<double> times;
    if (const std::string* t = args.Get("--time")) {
      if (args.Get("--frames")) throw UsageError("give --time or --frames, not both");
      times.push_back(NumberOption("--time", *t));
    } else {
      const int k = args.Get("--frames") ? CountOption("--frames", *args.Get("--frames"), 1, 1000) : 16;
      // A looping path's end is its start again; spread frames over one period.
      for (int i = 0; i < k; ++i) times.push_back(t0 + (t1 - t0) * i / (path.loop ? k : std::max(1, k - 1)));
    }
    for (double t : times) {
      double x, y;
      SamplePath(path, t, &x, &y);
      frames.push_back(EvaluateFrame(rig, x, y, options));
      std::snprintf(label, sizeof label, "t=%.3g (%.2f, %.2f)", t, x, y);
      frames.back().label = label;
    }
  }
  if (ext == "obj" && frames.size() != 1) throw UsageError("an OBJ file holds one frame; use --time or --at");
  const std::string title = args.positional + (at ? " at " + *at : " path " + *path_name);
  WriteText(*output, ext == "svg"    ? FramesSvg(rig, frames, title)
                     : ext == "json" ? FramesJson(rig, frames)
                                     : FrameObj(rig, frames[0]));
  out << "wrote " << *output << " (" << frames.size() << (frames.size() == 1 ? " frame)\n" : " frames)\n");
  return 0;
}

}  // namespace posemorph::bake::cli
