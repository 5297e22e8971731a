// SPDX-License-Identifier: MIT
// posemorph-bake init DRAWING... -o RIG.json: a rig description written from
// the drawings, for the animator to edit, instead of typed from scratch.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "command_args.h"
#include "commands.h"
#include "import_command.h"
#include "init_starts.h"
#include "layered_description.h"
#include "posemorph/bake/bake.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/import/layered_image.h"
#include "posemorph/bake/input_file.h"
#include "posemorph/bake/map_drawings.h"
#include "posemorph/bake/mapping/outline_image.h"
#include "posemorph/bake/mapping/outline_svg.h"
#include "posemorph/bake/rig_description.h"

namespace posemorph::bake::cli {
namespace {

namespace fs = std::filesystem;

struct Drawing {
  std::string path;       // as given
  std::string reference;  // relative to the description's folder
  std::string name;       // the pose's name: the file's stem, made unique
};

// The description `text` (as written here: its second line the name) with
// "import" after the name: the layered files its drawings came from,
// relative to the description's folder, so that posemorph-view --watch
// imports them again when one changes.
std::string WithImport(const std::string& text, const std::vector<std::string>& files, const fs::path& folder,
                       bool channels, bool flatten) {
  std::string line = "  \"import\": {\"files\": [";
  for (std::size_t k = 0; k < files.size(); ++k)
    line += (k ? ", " : "") + Quoted(fs::absolute(files[k]).lexically_relative(folder).generic_string());
  line += "]";
  if (channels) line += ", \"channels\": true";
  if (flatten) line += ", \"flatten\": true";
  line += "},\n";
  const std::size_t name = text.find("\n  \"name\": ");
  const std::size_t after = name == std::string::npos ? std::string::npos : text.find('\n', name + 1);
  return after == std::string::npos ? text : text.substr(0, after + 1) + line + text.substr(after + 1);
}

// The description of one drawing per pose.
std::string Description(const std::string& name, const std::vector<Drawing>& drawings,
                        const std::vector<std::vector<std::array<double, 2>>>& landmarks) {
  std::ostringstream s;
  s << "{\n  \"posemorph\": 1,\n  \"name\": " << Quoted(name) << ",\n  \"poses\": [\n";
  const std::size_t n = drawings.size();
  for (std::size_t k = 0; k < n; ++k) {
    const auto [x, y] = PadPoint(k, n);
    s << "    {\"name\": " << Quoted(drawings[k].name) << ", \"point\": [" << Coordinate(x) << ", " << Coordinate(y)
      << "], \"drawing\": " << Quoted(drawings[k].reference);
    if (!landmarks.empty()) {
      s << ", \"landmarks\": [";
      for (std::size_t j = 0; j < landmarks[k].size(); ++j)
        s << (j ? ", " : "") << "[" << Coordinate(landmarks[k][j][0]) << ", " << Coordinate(landmarks[k][j][1]) << "]";
      s << "]";
    }
    s << "}" << (k + 1 < n ? "," : "") << "\n";
  }
  s << "  ]\n}\n";
  return s.str();
}

// Bakes the description in memory (exact, nothing written): "" if it
// bakes, else the bake's message.
std::string TryBake(const std::string& text, const std::string& file, const std::string& folder) {
  try {
    RigDescription rig = ParseRigDescription(text, file, folder);
    rig.parameters.compact = false;
    BakeRig(rig);
    return "";
  } catch (const BakeError& e) {
    return e.what();
  }
}

// A layered character drawn as PNGs of one canvas named POSE-PART.png
// (split at the first '-': "rest-arm-left.png" is part "arm-left" of pose
// "rest"), every part in every pose: the poses in the order their files
// first come, the parts likewise.
struct Layered {
  std::vector<std::string> poses, parts;
  std::vector<std::vector<std::size_t>> drawing;  // [pose][part]: index into the drawings
};
bool AsLayered(const std::vector<Drawing>& drawings, Layered* out) {
  std::map<std::pair<std::string, std::string>, std::size_t> cells;
  for (std::size_t k = 0; k < drawings.size(); ++k) {
    const std::string stem = fs::path(drawings[k].path).stem().string();
    const std::size_t dash = stem.find('-');
    if (Extension(drawings[k].path) != "png" || dash == std::string::npos || dash == 0 || dash + 1 == stem.size())
      return false;
    const std::string pose = stem.substr(0, dash), part = stem.substr(dash + 1);
    if (std::find(out->poses.begin(), out->poses.end(), pose) == out->poses.end()) out->poses.push_back(pose);
    if (std::find(out->parts.begin(), out->parts.end(), part) == out->parts.end()) out->parts.push_back(part);
    if (!cells.emplace(std::make_pair(pose, part), k).second) return false;
  }
  if (out->poses.size() < 2 || out->parts.size() < 2 || out->parts.size() > 64 ||
      cells.size() != out->poses.size() * out->parts.size())
    return false;
  for (const std::string& pose : out->poses) {
    out->drawing.emplace_back();
    for (const std::string& part : out->parts) out->drawing.back().push_back(cells.at({pose, part}));
  }
  return true;
}

// A layered character drawn as one SVG per pose whose top-level groups
// (Inkscape layers by label, plain groups by id; hidden ones left out) are
// the parts, the same names in every drawing: the parts in the first
// drawing's order, `drawing[pose][part]` the pose's drawing. False when a
// drawing is no SVG or has fewer than two such groups; drawings that all
// have groups, but not the same, are refused.
bool AsLayeredSvg(const std::vector<Drawing>& drawings, Layered* out) {
  std::vector<std::vector<std::string>> names;
  for (const Drawing& d : drawings) {
    if (Extension(d.path) != "svg") return false;
    names.push_back(mapping::SvgLayerNames(d.path, ErrorSource(d.path)));
    if (names.back().size() < 2) return false;
  }
  auto listed = [](std::vector<std::string> v) {
    std::string s;
    for (std::size_t k = 0; k < v.size() && k < 16; ++k) s += (k ? ", '" : "'") + v[k] + "'";
    return s + (v.size() > 16 ? ", ..." : "");
  };
  std::vector<std::string> first = names[0];
  std::sort(first.begin(), first.end());
  for (std::size_t k = 0; k < drawings.size(); ++k) {
    std::vector<std::string> sorted = names[k];
    std::sort(sorted.begin(), sorted.end());
    if (const auto twice = std::adjacent_find(sorted.begin(), sorted.end()); twice != sorted.end())
      throw BakeError(drawings[k].path,
                      "two top-level groups are named '" + *twice + "': each part is one layer or group, named apart");
    if (sorted.size() > 64) throw BakeError(drawings[k].path, "has more than 64 layers (parts); a rig has at most 64");
    if (sorted != first)
      throw BakeError(drawings[k].path, "its layers (" + listed(names[k]) + ") are not " + drawings[0].path + "'s (" +
                                            listed(names[0]) +
                                            "): each pose's SVG holds every part, a top-level layer or group each "
                                            "(hide a layer that is no part)");
  }
  out->parts = names[0];
  for (std::size_t k = 0; k < drawings.size(); ++k) {
    out->poses.push_back(drawings[k].name);
    out->drawing.emplace_back(out->parts.size(), k);
  }
  return true;
}

}  // namespace

int InitCommand(const std::vector<std::string>& a, std::size_t from, std::ostream& out, std::ostream& err) {
  std::string output, name;
  bool overwrite = false, flatten = false, channels = false;
  std::vector<Drawing> drawings;
  for (std::size_t i = from; i < a.size(); ++i) {
    if (a[i] == "-o" || a[i] == "--name") {
      if (i + 1 >= a.size()) throw UsageError(a[i] + " needs a value");
      (a[i] == "-o" ? output : name) = a[i + 1];
      ++i;
    } else if (a[i] == "--force") {
      overwrite = true;
    } else if (a[i] == "--flatten") {
      flatten = true;
    } else if (a[i] == "--channels") {
      channels = true;
    } else if (!a[i].empty() && a[i][0] == '-') {
      throw UsageError("unknown option " + a[i]);
    } else {
      drawings.push_back({a[i], "", ""});
    }
  }
  if (output.empty()) throw UsageError("init needs -o RIG.json");
  std::size_t layered_files = 0;
  for (const Drawing& d : drawings) layered_files += import::IsLayeredImagePath(d.path);
  if (layered_files != 0 && layered_files != drawings.size())
    throw UsageError("init takes layered files (.ora, .psd) or flat drawings (PNG, SVG), not both");
  if (flatten && layered_files == 0) throw UsageError("--flatten is for layered files (.ora, .psd)");
  if (channels && (layered_files == 0 || flatten))
    throw UsageError("--channels takes layered files (.ora, .psd), one per channel, each with a group per pose");
  if (channels && (drawings.size() < 2 || drawings.size() > 8))
    throw UsageError("--channels takes 2 to 8 layered files, one per channel (the first drives the body)");
  if (layered_files == 0 && drawings.size() < 2) throw UsageError("init needs two drawings or more (one per pose)");
  if (drawings.empty()) throw UsageError("init needs a layered file with a group per pose, or one file per pose");
  if (drawings.size() > 4096) throw UsageError("init takes at most 4096 drawings (64 parts in 64 poses)");
  if (Extension(output) != "json") throw UsageError("init writes a rig description: -o must name a .json file");
  std::vector<std::string> inputs;
  for (const Drawing& d : drawings) inputs.push_back(d.path);
  CheckOutputPath(output, inputs);
  if (!overwrite && fs::exists(output))
    throw BakeError(output, "exists; init does not overwrite a description (--force does)");
  const fs::path folder = fs::absolute(output).parent_path();
  std::string imported;
  std::vector<std::string> import_files;  // the layered files imported, for the description's "import"
  if (channels) {
    // One file of poses per channel, named by the file's stem: its drawings
    // beside the description, the first channel's parts glued into the
    // body, the later channels' each to the body part it is drawn over.
    std::vector<import::LayeredCharacter> imports;
    std::vector<std::string> files;
    for (const Drawing& d : drawings) files.push_back(d.path);
    for (const std::string& file : files) {
      imports.push_back(import::ImportLayeredCharacter({file}, false));
      const import::LayeredCharacter& c = imports.back();
      if (c.poses.size() < 2)
        throw BakeError(file, "gives one pose: a channel's file holds two poses or more, one top-level group each");
      if (c.parts.empty())
        throw BakeError(file, "each pose is one layer: a channel's poses hold its parts, a layer or group each");
      if (c.width != imports[0].width || c.height != imports[0].height)
        throw BakeError(file, "a canvas of " + std::to_string(c.width) + " x " + std::to_string(c.height) + ", but " +
                                  files[0] + "'s is " + std::to_string(imports[0].width) + " x " +
                                  std::to_string(imports[0].height) + ": the channels share one canvas");
      for (std::size_t k = 0; k + 1 < imports.size(); ++k)
        for (const std::string& part : c.parts)
          if (std::find(imports[k].parts.begin(), imports[k].parts.end(), part) != imports[k].parts.end())
            throw BakeError(file, "part '" + part + "' is also a part of " + files[k] +
                                      ": a part belongs to one channel (leave it out of, or hide it in, the other)");
      for (std::size_t k = 0; k + 1 < imports.size(); ++k)
        for (const std::string& pose : c.poses)
          if (std::find(imports[k].poses.begin(), imports[k].poses.end(), pose) != imports[k].poses.end())
            throw BakeError(file, "pose '" + pose + "' is also a pose of " + files[k] +
                                      ": name the channels' poses apart (their drawings are POSE-PART.png)");
    }
    std::vector<ChannelDrawings> described;
    std::size_t written = 0;
    for (std::size_t k = 0; k < imports.size(); ++k) {
      const import::LayeredCharacter& c = imports[k];
      ChannelDrawings ch;
      ch.name = fs::path(files[k]).stem().string();
      ch.poses = c.poses, ch.parts = c.parts;
      const std::vector<std::string> paths = WriteLayeredCharacter(c, folder.string(), overwrite, err);
      written += paths.size();
      for (std::size_t i = 0; i < c.poses.size(); ++i) {
        ch.path.emplace_back(), ch.reference.emplace_back();
        for (std::size_t q = 0; q < c.parts.size(); ++q) {
          const std::string& path = paths[i * c.parts.size() + q];
          ch.path.back().push_back(path);
          ch.reference.back().push_back(fs::absolute(path).lexically_relative(folder).generic_string());
        }
      }
      described.push_back(std::move(ch));
    }
    if (name.empty()) name = fs::path(output).stem().string();
    const std::string text = WithImport(LayeredDescription(name, described), files, folder, true, false);
    std::string summary = std::to_string(described.size()) + " channels (";
    for (std::size_t k = 0; k < described.size(); ++k)
      summary += (k ? ", " : "") + described[k].name + ": " + std::to_string(described[k].poses.size()) + " poses of " +
                 std::to_string(described[k].parts.size()) + " parts";
    summary += "; the later channels' parts glued where drawn over the first's)";
    const std::string problem = TryBake(text, output, folder.string());
    WriteText(output, text);
    out << "wrote " << output << ": imported " << written << " drawings from " << files.size()
        << " layered files beside it; " << summary << "\n";
    if (problem.empty())
      out << "it bakes as written: posemorph-bake " << output << "\n";
    else
      out << "it does not bake yet: " << Printable(problem) << "\n";
    return 0;
  }
  if (layered_files != 0) {
    // The layered files' drawings become PNGs beside the description (as
    // `import` writes them), which it then names like any other drawings.
    std::vector<std::string> files;
    for (const Drawing& d : drawings) files.push_back(d.path);
    const import::LayeredCharacter c = import::ImportLayeredCharacter(files, flatten);
    if (c.poses.size() < 2)
      throw BakeError(files[0],
                      "gives one pose: init needs two poses or more (one file per pose, or one file "
                      "whose top-level groups are the poses)");
    drawings.clear();
    for (const std::string& path : WriteLayeredCharacter(c, folder.string(), overwrite, err))
      drawings.push_back({path, "", ""});
    import_files = files;
    imported = "imported " + std::to_string(drawings.size()) + " drawings from " + std::to_string(files.size()) +
               (files.size() == 1 ? " layered file" : " layered files") + " beside it; ";
  }
  std::map<std::string, int> used;
  for (Drawing& d : drawings) {
    const std::string ext = Extension(d.path);
    if (ext != "png" && ext != "svg") throw BakeError(d.path, "not a drawing init reads (PNG or SVG)");
    if (!fs::is_regular_file(d.path)) throw BakeError(d.path, "cannot read the drawing (no such file)");
    d.reference = fs::absolute(d.path).lexically_relative(folder).generic_string();
    std::string stem = fs::path(d.path).stem().string();
    if (stem.empty()) stem = "pose";
    const int n = ++used[stem];
    d.name = n == 1 ? stem : stem + "-" + std::to_string(n);
  }
  if (name.empty()) name = fs::path(output).stem().string();

  std::string text, summary, advice;
  std::optional<std::string> tried;  // the trial bake of `text`, when made already
  Layered layered;
  const bool svg_layers = AsLayeredSvg(drawings, &layered);
  if (svg_layers || AsLayered(drawings, &layered)) {
    ChannelDrawings only;
    only.poses = layered.poses, only.parts = layered.parts, only.svg_layers = svg_layers;
    for (const std::vector<std::size_t>& row : layered.drawing) {
      only.path.emplace_back(), only.reference.emplace_back();
      for (std::size_t k : row)
        only.path.back().push_back(drawings[k].path), only.reference.back().push_back(drawings[k].reference);
    }
    text = LayeredDescription(name, {only});
    summary = std::to_string(layered.poses.size()) + " poses (" + layered.poses[0] +
              " at the pad's centre, the others around it) of " + std::to_string(layered.parts.size()) + " parts (" +
              (svg_layers ? "each SVG's top-level layers" : "from POSE-PART.png names") +
              "; the larger behind, glued where drawn over each other)";
  } else {
    // Every drawn pose needs a start landmark, a point every drawing shares:
    // where the character stands, its outline's lowest point. Traced from a
    // description whose landmarks are placeholders (the tracing reads none).
    std::vector<std::vector<std::array<double, 2>>> landmarks(drawings.size(), {{{0.0, 0.0}}});
    const std::string placeholder = Description(name, drawings, landmarks);
    std::vector<std::array<double, 2>> suggested;
    std::vector<std::string> moved;
    const DrawnOutlines traced = TraceDrawings(ParseRigDescription(placeholder, output, folder.string()));
    const std::vector<std::array<double, 2>> lowest = StartPoints(traced, &suggested, &moved);
    for (std::size_t k = 0; k < lowest.size(); ++k) landmarks[k] = {lowest[k]};
    text = Description(name, drawings, landmarks);
    const std::string poses = std::to_string(drawings.size()) + " poses (" + drawings[0].name +
                              " at the pad's centre, the others around it); the start landmark at each drawing's ";
    summary = poses + "lowest point (where it stands)";
    // Where the matching is unsure of a start and the description does not
    // bake with the lowest points, the starts the outlines' bends suggest
    // are tried; kept when they bake, else said.
    if (!suggested.empty()) {
      tried = TryBake(text, output, folder.string());
      if (!tried->empty()) {
        std::vector<std::vector<std::array<double, 2>>> aligned(drawings.size());
        for (std::size_t k = 0; k < suggested.size(); ++k) aligned[k] = {suggested[k]};
        const std::string other = Description(name, drawings, aligned);
        std::string list;
        for (const std::string& m : moved) list += (list.empty() ? " " : "; ") + m;
        const std::string other_problem = TryBake(other, output, folder.string());
        if (other_problem.empty()) {
          text = other, tried = std::string();
          summary += ", except where the outlines' bends place it elsewhere (the lowest points do not bake):" + list;
        } else {
          advice = "the outlines' bends suggest other starts (neither bakes as written):" + list +
                   "; with them: " + other_problem;
        }
      }
    }
    // Where that does not bake, the outline's other extremes (a head, a
    // nose, a tail), the side the outlines' bends agree with best first;
    // the first that bakes is kept (one drawing has no start to match).
    if (!tried) tried = TryBake(text, output, folder.string());
    if (!tried->empty() && drawings.size() > 1) {
      std::string failed;
      for (const OutlineSide side : OtherSidesByAgreement(traced)) {
        const std::vector<std::array<double, 2>> at = SidePoints(traced, side);
        std::vector<std::vector<std::array<double, 2>>> starts(drawings.size());
        for (std::size_t k = 0; k < at.size() && k < starts.size(); ++k) starts[k] = {at[k]};
        const std::string other = Description(name, drawings, starts);
        if (TryBake(other, output, folder.string()).empty()) {
          text = other, tried = std::string(), advice.clear();
          summary = poses + SideName(side) + " point (the lowest points do not bake" +
                    (suggested.empty() ? "" : ", nor the starts the outlines' bends suggest") + ")";
          break;
        }
        failed += (failed.empty() ? "" : ", ") + std::string(SideName(side));
      }
      if (!tried->empty())
        advice += (advice.empty() ? "" : "; ") + std::string("the outlines' ") + failed +
                  " points do not bake as starts either";
    }
  }
  if (!import_files.empty()) text = WithImport(text, import_files, folder, false, flatten), tried.reset();
  const std::string problem = tried ? *tried : TryBake(text, output, folder.string());
  WriteText(output, text);
  out << "wrote " << output << ": " << imported << summary << "\n";
  if (problem.empty()) {
    out << "it bakes as written: posemorph-bake " << output << "\n";
  } else {
    out << "it does not bake yet: " << Printable(problem) << "\n";
    if (!advice.empty()) out << Printable(advice) << "\n";
    out << "place landmarks at points every drawing shares (posemorph-bake outline " << output
        << " -o DIR draws the outlines to read them from)\n";
  }
  return 0;
}

}  // namespace posemorph::bake::cli
