// SPDX-License-Identifier: MIT
// posemorph-bake init DRAWING... -o RIG.json: a rig description written from
// the drawings, for the animator to edit, instead of typed from scratch.
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>

#include "command_args.h"
#include "commands.h"
#include "posemorph/bake/bake.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/input_file.h"
#include "posemorph/bake/map_drawings.h"
#include "posemorph/bake/rig_description.h"

namespace posemorph::bake::cli {
namespace {

namespace fs = std::filesystem;

std::string Quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// A pose-space coordinate, short and exact enough: 4 decimals, no "-0".
std::string Coordinate(double v) {
  double r = std::round(v * 1e4) / 1e4;
  if (r == 0) r = 0;
  std::ostringstream s;
  s << r;
  return s.str();
}

struct Drawing {
  std::string path;       // as given
  std::string reference;  // relative to the description's folder
  std::string name;       // the pose's name: the file's stem, made unique
};

// The description: pose 0 at the pad's centre, the others on the unit
// circle, clockwise from the top (four others: up, right, down, left).
std::string Description(const std::string& name, const std::vector<Drawing>& drawings,
                        const std::vector<std::vector<std::array<double, 2>>>& landmarks) {
  std::ostringstream s;
  s << "{\n  \"posemorph\": 1,\n  \"name\": " << Quoted(name) << ",\n  \"poses\": [\n";
  const std::size_t n = drawings.size();
  for (std::size_t k = 0; k < n; ++k) {
    double x = 0, y = 0;
    if (k > 0) {
      constexpr double kPi = 3.14159265358979323846;
      const double a = kPi / 2 - 2 * kPi * double(k - 1) / double(n - 1);
      x = std::cos(a), y = std::sin(a);
    }
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

// Where each drawing stands: its outline's lowest point (the largest y in
// drawing pixels; the middle of a flat bottom), a landmark that matches
// across poses of a character standing on the ground.
std::vector<std::array<double, 2>> LowestPoints(const RigDescription& rig) {
  std::vector<std::array<double, 2>> out;
  for (const DrawnPoseOutline& pose : TraceDrawings(rig).poses) {
    const std::vector<Eigen::Vector2d>& outline = pose.traced;
    double bottom = -1e300;
    for (const Eigen::Vector2d& p : outline) bottom = std::max(bottom, p.y());
    double x0 = 1e300, x1 = -1e300;
    for (const Eigen::Vector2d& p : outline)
      if (p.y() >= bottom - 0.5) x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x());
    // The outline point nearest the middle of the flat bottom.
    const double mid = (x0 + x1) / 2;
    std::array<double, 2> best{mid, bottom};
    double best_d = 1e300;
    for (const Eigen::Vector2d& p : outline)
      if (p.y() >= bottom - 0.5 && std::abs(p.x() - mid) < best_d)
        best_d = std::abs(p.x() - mid), best = {p.x(), p.y()};
    out.push_back(best);
  }
  return out;
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

}  // namespace

int InitCommand(const std::vector<std::string>& a, std::size_t from, std::ostream& out) {
  std::string output, name;
  bool overwrite = false;
  std::vector<Drawing> drawings;
  for (std::size_t i = from; i < a.size(); ++i) {
    if (a[i] == "-o" || a[i] == "--name") {
      if (i + 1 >= a.size()) throw UsageError(a[i] + " needs a value");
      (a[i] == "-o" ? output : name) = a[i + 1];
      ++i;
    } else if (a[i] == "--force") {
      overwrite = true;
    } else if (!a[i].empty() && a[i][0] == '-') {
      throw UsageError("unknown option " + a[i]);
    } else {
      drawings.push_back({a[i], "", ""});
    }
  }
  if (output.empty()) throw UsageError("init needs -o RIG.json");
  if (drawings.size() < 2) throw UsageError("init needs two drawings or more (one per pose)");
  if (drawings.size() > 64) throw UsageError("init takes at most 64 drawings");
  if (Extension(output) != "json") throw UsageError("init writes a rig description: -o must name a .json file");
  std::vector<std::string> inputs;
  for (const Drawing& d : drawings) inputs.push_back(d.path);
  CheckOutputPath(output, inputs);
  if (!overwrite && fs::exists(output))
    throw BakeError(output, "exists; init does not overwrite a description (--force does)");
  const fs::path folder = fs::absolute(output).parent_path();
  std::map<std::string, int> used;
  for (Drawing& d : drawings) {
    const std::string ext = Extension(d.path);
    if (ext == "ora" || ext == "psd")
      throw BakeError(d.path, "layered ." + ext + " files are not read yet: export each pose as PNG or SVG");
    if (ext != "png" && ext != "svg") throw BakeError(d.path, "not a drawing init reads (PNG or SVG)");
    if (!fs::is_regular_file(d.path)) throw BakeError(d.path, "cannot read the drawing (no such file)");
    d.reference = fs::absolute(d.path).lexically_relative(folder).generic_string();
    std::string stem = fs::path(d.path).stem().string();
    if (stem.empty()) stem = "pose";
    const int n = ++used[stem];
    d.name = n == 1 ? stem : stem + "-" + std::to_string(n);
  }
  if (name.empty()) name = fs::path(output).stem().string();

  // Every drawn pose needs a start landmark, a point every drawing shares:
  // where the character stands, its outline's lowest point. Traced from a
  // description whose landmarks are placeholders (the tracing reads none).
  std::vector<std::vector<std::array<double, 2>>> landmarks(drawings.size(), {{{0.0, 0.0}}});
  const std::string placeholder = Description(name, drawings, landmarks);
  std::size_t k = 0;
  for (const std::array<double, 2>& p : LowestPoints(ParseRigDescription(placeholder, output, folder.string())))
    landmarks[k++] = {p};
  const std::string text = Description(name, drawings, landmarks);
  const std::string problem = TryBake(text, output, folder.string());
  const std::string landmarks_note = "; the start landmark at each drawing's lowest point (where it stands)";
  WriteText(output, text);
  out << "wrote " << output << ": " << drawings.size() << " poses (" << drawings[0].name
      << " at the pad's centre, the others around it)" << landmarks_note << "\n";
  if (problem.empty()) {
    out << "it bakes as written: posemorph-bake " << output << "\n";
  } else {
    out << "it does not bake yet: " << Printable(problem) << "\n"
        << "place landmarks at points every drawing shares (posemorph-bake outline " << output
        << " -o DIR draws the outlines to read them from)\n";
  }
  return 0;
}

}  // namespace posemorph::bake::cli
