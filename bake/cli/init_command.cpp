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
#include "posemorph/bake/bake.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/import/layered_image.h"
#include "posemorph/bake/input_file.h"
#include "posemorph/bake/map_drawings.h"
#include "posemorph/bake/mapping/boundary_matching.h"
#include "posemorph/bake/mapping/outline_image.h"
#include "posemorph/bake/rig_description.h"

namespace posemorph::bake::cli {
namespace {

namespace fs = std::filesystem;

// A JSON string literal, escaped by nlohmann-json.
std::string Quoted(const std::string& s) {
  return nlohmann::json(s).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
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

// Pose k of n on the pad: pose 0 at the centre, the others on the unit
// circle, clockwise from the top (four others: up, right, down, left).
std::array<double, 2> PadPoint(std::size_t k, std::size_t n) {
  if (k == 0) return {0, 0};
  constexpr double kPi = 3.14159265358979323846;
  const double a = kPi / 2 - 2 * kPi * double(k - 1) / double(n - 1);
  return {std::cos(a), std::sin(a)};
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

// Where each drawing stands: its outline's lowest point (the largest y in
// drawing pixels; the middle of a flat bottom), a landmark that matches
// across poses of a character standing on the ground. Where the matching
// is unsure of it (the outline's bends agree clearly better with another
// start, more than an eighth of the way round from it: a character that
// stands on the other foot, or does not stand), `suggested` gets the start
// where they agree best with the first pose's, and `moved` says which poses
// (empty when none is unsure).
std::vector<std::array<double, 2>> StartPoints(const RigDescription& rig, std::vector<std::array<double, 2>>* suggested,
                                               std::vector<std::string>* moved) {
  std::vector<std::array<double, 2>> out;
  const DrawnOutlines traced = TraceDrawings(rig);
  // In rig orientation (y up) the traced outlines, counter-clockwise as
  // seen, are counter-clockwise as AlignStart takes them.
  auto flipped = [](const std::vector<Eigen::Vector2d>& points) {
    mapping::Polygon p;
    for (const Eigen::Vector2d& q : points) p.emplace_back(q.x(), -q.y());
    return p;
  };
  for (const DrawnPoseOutline& pose : traced.poses) {
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
  *suggested = out;
  for (std::size_t k = 1; k < out.size() && k < traced.poses.size(); ++k) {
    const mapping::Polygon o0 = flipped(traced.poses[0].traced), ok = flipped(traced.poses[k].traced);
    const mapping::StartAlignment a = mapping::AlignStart(o0, {out[0][0], -out[0][1]}, ok, {out[k][0], -out[k][1]});
    if (!a.Misplaced()) continue;
    const mapping::Point at = mapping::PointAtArcLength(ok, a.best_start);
    moved->push_back(traced.poses[k].label + ": from its lowest point (" + Coordinate(out[k][0]) + ", " +
                     Coordinate(out[k][1]) + ") to (" + Coordinate(at.x()) + ", " + Coordinate(-at.y()) +
                     "), where its outline's bends agree with the first pose's");
    (*suggested)[k] = {at.x(), -at.y()};
  }
  if (moved->empty()) suggested->clear();
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

struct Mask {
  int width = 0, height = 0;
  std::vector<char> in;  // alpha above the bake's default threshold
  bool At(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height && in[std::size_t(y) * width + x]; }
};
Mask ReadMask(const std::string& path) {
  Mask m;
  const std::vector<unsigned char> alpha = mapping::ReadPngAlpha(path, &m.width, &m.height);
  const RigDescription defaults;
  for (unsigned char a : alpha) m.in.push_back(a > defaults.mapping.alpha_threshold * 255);
  return m;
}

// Where two parts are drawn over each other: the overlap's pixel nearest its
// centroid among those whose neighbours within 2 px overlap too (the joint
// lies well inside both outlines), else the nearest at all; false if none.
std::size_t Overlap(const Mask& a, const Mask& b) {
  std::size_t n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) n += a.At(x, y) && b.At(x, y);
  return n;
}
bool JointOf(const Mask& a, const Mask& b, std::array<double, 2>* at) {
  double sx = 0, sy = 0;
  std::vector<std::array<int, 2>> both;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      if (a.At(x, y) && b.At(x, y)) both.push_back({x, y}), sx += x, sy += y;
  if (both.empty()) return false;
  const double cx = sx / double(both.size()), cy = sy / double(both.size());
  double best = 1e300, best_inner = 1e300;
  std::array<int, 2> pick = both[0], pick_inner = both[0];
  for (const auto& p : both) {
    const double d = (p[0] - cx) * (p[0] - cx) + (p[1] - cy) * (p[1] - cy);
    if (d < best) best = d, pick = p;
    bool inner = true;
    for (int dy = -2; dy <= 2 && inner; ++dy)
      for (int dx = -2; dx <= 2 && inner; ++dx) inner = a.At(p[0] + dx, p[1] + dy) && b.At(p[0] + dx, p[1] + dy);
    if (inner && d < best_inner) best_inner = d, pick_inner = p;
  }
  const auto& p = best_inner < 1e300 ? pick_inner : pick;
  *at = {p[0] + 0.5, p[1] + 0.5};
  return true;
}

// The outline point of a mask nearest `target`: the edge between an inside
// pixel and an outside one, where the traced outline runs.
std::array<double, 2> EdgeNearest(const Mask& m, std::array<double, 2> target) {
  double best = 1e300;
  std::array<double, 2> out = target;
  const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x) {
      if (!m.At(x, y)) continue;
      for (int k = 0; k < 4; ++k) {
        if (m.At(x + dx[k], y + dy[k])) continue;
        const double ex = x + 0.5 + 0.5 * dx[k], ey = y + 0.5 + 0.5 * dy[k];
        const double d = (ex - target[0]) * (ex - target[0]) + (ey - target[1]) * (ey - target[1]);
        if (d < best) best = d, out = {ex, ey};
      }
    }
  return out;
}

// A layered character's drawings for the description: per channel (the
// first drives the body; a rig without channels has one, unnamed), its
// poses and parts and each part's drawing in each pose.
struct ChannelDrawings {
  std::string name;  // "": a rig without channels
  std::vector<std::string> poses, parts;
  std::vector<std::vector<std::string>> path, reference;  // [pose][part]: to read, and as the description names it
};

// The layered description: the first channel's parts back to front by size
// (the largest part, the root of the glue, behind: a smaller part drawn
// over a larger one is usually in front of it, like eyes on a head), glued
// in the tree of their largest overlaps in the first pose, each joint where
// the two are drawn over each other in every pose, each part's start
// landmark on its outline nearest its joint (the root's: its lowest point).
// A later channel's parts (a face's eyes and mouth) in front of them all,
// each glued to the first channel's part it overlaps most in both
// channels' first poses (which share one canvas), its joint in each of its
// drawings where it is drawn over that part's first drawing.
std::string LayeredDescription(const std::string& name, const std::vector<ChannelDrawings>& channels) {
  const ChannelDrawings& body = channels[0];
  const std::size_t P = body.poses.size(), Q = body.parts.size();
  std::vector<std::vector<std::vector<Mask>>> masks(channels.size());  // [channel][pose][part]
  for (std::size_t c = 0; c < channels.size(); ++c)
    for (std::size_t i = 0; i < channels[c].poses.size(); ++i) {
      masks[c].emplace_back();
      for (std::size_t q = 0; q < channels[c].parts.size(); ++q)
        masks[c][i].push_back(ReadMask(channels[c].path[i][q]));
    }
  auto area_of = [](const Mask& m) {
    std::size_t n = 0;
    for (char c : m.in) n += c != 0;
    return n;
  };
  std::vector<std::size_t> area(Q, 0);
  for (std::size_t q = 0; q < Q; ++q) area[q] = area_of(masks[0][0][q]);
  std::vector<std::size_t> by_size(Q);
  for (std::size_t q = 0; q < Q; ++q) by_size[q] = q;
  std::stable_sort(by_size.begin(), by_size.end(), [&](std::size_t x, std::size_t y) { return area[x] > area[y]; });
  std::vector<int> order(Q);
  for (std::size_t r = 0; r < Q; ++r) order[by_size[r]] = int(r);
  // Prim's tree of the largest overlaps, from the largest part.
  std::vector<std::vector<std::size_t>> overlap(Q, std::vector<std::size_t>(Q, 0));
  for (std::size_t a = 0; a < Q; ++a)
    for (std::size_t b = a + 1; b < Q; ++b) overlap[a][b] = overlap[b][a] = Overlap(masks[0][0][a], masks[0][0][b]);
  const std::size_t root = by_size[0];
  std::vector<int> parent(Q, -1);
  std::vector<bool> joined(Q, false);
  joined[root] = true;
  for (std::size_t added = 1; added < Q; ++added) {
    std::size_t best = 0, from = 0, to = 0;
    for (std::size_t a = 0; a < Q; ++a)
      for (std::size_t b = 0; b < Q; ++b)
        if (joined[a] && !joined[b] && overlap[a][b] > best) best = overlap[a][b], from = a, to = b;
    if (best == 0) {
      for (std::size_t b = 0; b < Q; ++b)
        if (!joined[b])
          throw BakeError(body.path[0][b], "part '" + body.parts[b] + "' is drawn over no other part in pose '" +
                                               body.poses[0] +
                                               "': glue needs a point where two parts are drawn over each other");
    }
    joined[to] = true, parent[to] = int(from);
  }
  // The glue, per channel and part: the part it hangs from (the first
  // channel's) and its joint in each of its channel's poses.
  std::vector<std::vector<int>> glued_to(channels.size());
  std::vector<std::vector<std::vector<std::array<double, 2>>>> joint(channels.size());  // [channel][part][pose]
  glued_to[0] = parent;
  joint[0].resize(Q);
  for (std::size_t q = 0; q < Q; ++q) {
    if (parent[q] < 0) continue;
    for (std::size_t i = 0; i < P; ++i) {
      std::array<double, 2> at;
      if (!JointOf(masks[0][i][q], masks[0][i][std::size_t(parent[q])], &at))
        throw BakeError(body.path[i][q], "part '" + body.parts[q] + "' is not drawn over part '" +
                                             body.parts[std::size_t(parent[q])] + "' in pose '" + body.poses[i] +
                                             "': glue needs a point over both");
      joint[0][q].push_back(at);
    }
  }
  for (std::size_t c = 1; c < channels.size(); ++c) {
    const ChannelDrawings& ch = channels[c];
    joint[c].resize(ch.parts.size());
    for (std::size_t q = 0; q < ch.parts.size(); ++q) {
      std::size_t best = 0;
      int to = -1;
      for (std::size_t b = 0; b < Q; ++b)
        if (const std::size_t n = Overlap(masks[c][0][q], masks[0][0][b]); n > best) best = n, to = int(b);
      if (to < 0)
        throw BakeError(ch.path[0][q], "part '" + ch.parts[q] + "' of channel '" + ch.name +
                                           "' is drawn over no part of channel '" + body.name + "' (pose '" +
                                           body.poses[0] + "'): glue needs a point over both");
      glued_to[c].push_back(to);
      for (std::size_t i = 0; i < ch.poses.size(); ++i) {
        std::array<double, 2> at;
        if (!JointOf(masks[c][i][q], masks[0][0][std::size_t(to)], &at))
          throw BakeError(ch.path[i][q], "part '" + ch.parts[q] + "' is not drawn over part '" +
                                             body.parts[std::size_t(to)] + "' in pose '" + ch.poses[i] +
                                             "': glue needs a point over both");
        joint[c][q].push_back(at);
      }
    }
  }
  auto pose_list = [&](const ChannelDrawings& ch, const char* indent) {
    std::ostringstream s;
    for (std::size_t i = 0; i < ch.poses.size(); ++i) {
      const std::array<double, 2> point = PadPoint(i, ch.poses.size());
      s << indent << "{\"name\": " << Quoted(ch.poses[i]) << ", \"point\": [" << Coordinate(point[0]) << ", "
        << Coordinate(point[1]) << "]}" << (i + 1 < ch.poses.size() ? "," : "") << "\n";
    }
    return s.str();
  };
  std::ostringstream s;
  s << "{\n  \"posemorph\": 1,\n  \"name\": " << Quoted(name) << ",\n";
  if (channels.size() == 1) {
    s << "  \"poses\": [\n" << pose_list(body, "    ") << "  ],\n";
  } else {
    s << "  \"channels\": [\n";
    for (std::size_t c = 0; c < channels.size(); ++c)
      s << "    {\"name\": " << Quoted(channels[c].name) << ", \"poses\": [\n"
        << pose_list(channels[c], "      ") << "    ]}" << (c + 1 < channels.size() ? "," : "") << "\n";
    s << "  ],\n";
  }
  s << "  \"parts\": [\n";
  int front = int(Q);
  for (std::size_t c = 0; c < channels.size(); ++c) {
    const ChannelDrawings& ch = channels[c];
    for (std::size_t q = 0; q < ch.parts.size(); ++q) {
      s << "    {\"name\": " << Quoted(ch.parts[q]);
      if (c > 0) s << ", \"channel\": " << Quoted(ch.name);
      s << ", \"order\": " << (c == 0 ? order[q] : front++) << ", \"poses\": [\n";
      for (std::size_t i = 0; i < ch.poses.size(); ++i) {
        const Mask& m = masks[c][i][q];
        std::array<double, 2> target;
        if (c > 0 || glued_to[0][q] >= 0) {
          target = joint[c][q][i];
        } else {  // the root: the middle of its lowest row
          int bottom = -1;
          for (int y = 0; y < m.height; ++y)
            for (int x = 0; x < m.width; ++x)
              if (m.At(x, y)) bottom = y;
          double sum = 0, n = 0;
          for (int x = 0; x < m.width; ++x)
            if (m.At(x, bottom)) sum += x + 0.5, n += 1;
          target = {n > 0 ? sum / n : 0, bottom + 1.0};
        }
        const std::array<double, 2> lm = EdgeNearest(m, target);
        s << "      {\"drawing\": " << Quoted(ch.reference[i][q]) << ", \"landmarks\": [[" << Coordinate(lm[0]) << ", "
          << Coordinate(lm[1]) << "]]}" << (i + 1 < ch.poses.size() ? "," : "") << "\n";
      }
      const bool last = c + 1 == channels.size() && q + 1 == ch.parts.size();
      s << "    ]}" << (last ? "" : ",") << "\n";
    }
  }
  s << "  ],\n  \"glue\": [\n";
  bool first = true;
  for (std::size_t c = 0; c < channels.size(); ++c)
    for (std::size_t q = 0; q < channels[c].parts.size(); ++q) {
      if (glued_to[c][q] < 0) continue;
      s << (first ? "" : ",\n") << "    {\"part\": " << Quoted(channels[c].parts[q])
        << ", \"to\": " << Quoted(body.parts[std::size_t(glued_to[c][q])]) << ", \"at\": [";
      for (std::size_t i = 0; i < joint[c][q].size(); ++i)
        s << (i ? ", " : "") << "[" << Coordinate(joint[c][q][i][0]) << ", " << Coordinate(joint[c][q][i][1]) << "]";
      s << "]}";
      first = false;
    }
  s << "\n  ]\n}\n";
  return s.str();
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
  if (AsLayered(drawings, &layered)) {
    ChannelDrawings only;
    only.poses = layered.poses, only.parts = layered.parts;
    for (const std::vector<std::size_t>& row : layered.drawing) {
      only.path.emplace_back(), only.reference.emplace_back();
      for (std::size_t k : row)
        only.path.back().push_back(drawings[k].path), only.reference.back().push_back(drawings[k].reference);
    }
    text = LayeredDescription(name, {only});
    summary = std::to_string(layered.poses.size()) + " poses (" + layered.poses[0] +
              " at the pad's centre, the others around it) of " + std::to_string(layered.parts.size()) +
              " parts (from POSE-PART.png names; the larger behind, glued where drawn over each other)";
  } else {
    // Every drawn pose needs a start landmark, a point every drawing shares:
    // where the character stands, its outline's lowest point. Traced from a
    // description whose landmarks are placeholders (the tracing reads none).
    std::vector<std::vector<std::array<double, 2>>> landmarks(drawings.size(), {{{0.0, 0.0}}});
    const std::string placeholder = Description(name, drawings, landmarks);
    std::vector<std::array<double, 2>> suggested;
    std::vector<std::string> moved;
    const std::vector<std::array<double, 2>> lowest =
        StartPoints(ParseRigDescription(placeholder, output, folder.string()), &suggested, &moved);
    for (std::size_t k = 0; k < lowest.size(); ++k) landmarks[k] = {lowest[k]};
    text = Description(name, drawings, landmarks);
    summary = std::to_string(drawings.size()) + " poses (" + drawings[0].name +
              " at the pad's centre, the others around it); the start landmark at each drawing's lowest point "
              "(where it stands)";
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
        if (TryBake(other, output, folder.string()).empty()) {
          text = other, tried = std::string();
          summary += ", except where the outlines' bends place it elsewhere (the lowest points do not bake):" + list;
        } else {
          advice = "the outlines' bends suggest other starts (neither bakes as written):" + list;
        }
      }
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
