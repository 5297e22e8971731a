// SPDX-License-Identifier: MIT
// The layered description `posemorph-bake init` writes (layered_description.h).
#include "layered_description.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <nlohmann/json.hpp>

#include "posemorph/bake/error.h"
#include "posemorph/bake/mapping/boundary_matching.h"
#include "posemorph/bake/mapping/outline_image.h"
#include "posemorph/bake/mapping/outline_svg.h"
#include "posemorph/bake/rig_description.h"

namespace posemorph::bake::cli {

std::string Quoted(const std::string& s) {
  return nlohmann::json(s).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::string Coordinate(double v) {
  double r = std::round(v * 1e4) / 1e4;
  if (r == 0) r = 0;
  std::ostringstream s;
  s << r;
  return s.str();
}

std::array<double, 2> PadPoint(std::size_t k, std::size_t n) {
  if (k == 0) return {0, 0};
  constexpr double kPi = 3.14159265358979323846;
  const double a = kPi / 2 - 2 * kPi * double(k - 1) / double(n - 1);
  return {std::cos(a), std::sin(a)};
}

namespace {

struct Mask {
  int width = 0, height = 0;
  std::vector<char> in;      // alpha above the bake's default threshold
  mapping::Polygon outline;  // an SVG layer's: its outline in mask pixels
  bool At(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height && in[std::size_t(y) * width + x]; }
};
// An SVG layer's outline, filled at `scale` pixels per user unit on the
// viewBox's canvas (pixel centres inside the polygon).
Mask SvgLayerMask(const std::string& path, const std::string& layer, double* scale, mapping::Point* origin) {
  const mapping::SvgOutline o = mapping::OutlineFromSvg(path, 0.25, ErrorSource(path), {layer, true});
  // At least 256 pixels along the longer side, at most 2048.
  const double longer = std::max(o.canvas_size.x(), o.canvas_size.y());
  *scale = std::clamp(256.0 / longer, std::min(1.0, 2048.0 / longer), 2048.0 / longer);
  *origin = o.canvas_origin;
  Mask m;
  m.width = int(std::ceil(o.canvas_size.x() * *scale)), m.height = int(std::ceil(o.canvas_size.y() * *scale));
  m.in.assign(std::size_t(m.width) * std::size_t(m.height), 0);
  mapping::Polygon& scaled = m.outline;
  for (const mapping::Point& p : o.outline) scaled.emplace_back((p - o.canvas_origin) * *scale);
  // Even-odd scanline fill at each row's pixel centres.
  for (int y = 0; y < m.height; ++y) {
    const double cy = y + 0.5;
    std::vector<double> xs;
    for (std::size_t k = 0; k < scaled.size(); ++k) {
      const mapping::Point& a = scaled[k];
      const mapping::Point& b = scaled[(k + 1) % scaled.size()];
      if ((a.y() <= cy) != (b.y() <= cy)) xs.push_back(a.x() + (cy - a.y()) / (b.y() - a.y()) * (b.x() - a.x()));
    }
    std::sort(xs.begin(), xs.end());
    for (std::size_t k = 0; k + 1 < xs.size(); k += 2)
      for (int x = std::max(0, int(std::ceil(xs[k] - 0.5))); x < m.width && x + 0.5 < xs[k + 1]; ++x)
        m.in[std::size_t(y) * m.width + x] = 1;
  }
  return m;
}

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

// The outline point of a mask nearest `target`: on an SVG layer's outline,
// else the edge between an inside pixel and an outside one, where the
// traced outline runs.
std::array<double, 2> EdgeNearest(const Mask& m, std::array<double, 2> target) {
  if (!m.outline.empty()) {
    double distance = 0;
    const mapping::Point t(target[0], target[1]);
    const mapping::Point p = mapping::PointAtArcLength(m.outline, mapping::NearestArcLength(m.outline, t, &distance));
    return {p.x(), p.y()};
  }
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

}  // namespace

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
  // A mask pixel's corner (x, y) is the drawing's point `origin` + (x, y) /
  // `scale` (SVG user units); a PNG's pixels are its own.
  std::vector<std::vector<double>> scale(channels.size());
  std::vector<std::vector<mapping::Point>> origin(channels.size());
  for (std::size_t c = 0; c < channels.size(); ++c)
    for (std::size_t i = 0; i < channels[c].poses.size(); ++i) {
      masks[c].emplace_back();
      scale[c].push_back(1), origin[c].emplace_back(0, 0);
      for (std::size_t q = 0; q < channels[c].parts.size(); ++q)
        masks[c][i].push_back(channels[c].svg_layers ? SvgLayerMask(channels[c].path[i][q], channels[c].parts[q],
                                                                    &scale[c][i], &origin[c][i])
                                                     : ReadMask(channels[c].path[i][q]));
    }
  // Pose i's mask point as the drawing's coordinates.
  auto drawn = [&](std::size_t c, std::size_t i, std::array<double, 2> at) {
    return std::array<double, 2>{origin[c][i].x() + at[0] / scale[c][i], origin[c][i].y() + at[1] / scale[c][i]};
  };
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
        const std::array<double, 2> at = drawn(c, i, lm);
        s << "      {\"drawing\": " << Quoted(ch.reference[i][q]) << ", \"landmarks\": [[" << Coordinate(at[0]) << ", "
          << Coordinate(at[1]) << "]]}" << (i + 1 < ch.poses.size() ? "," : "") << "\n";
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
      for (std::size_t i = 0; i < joint[c][q].size(); ++i) {
        const std::array<double, 2> at = drawn(c, i, joint[c][q][i]);
        s << (i ? ", " : "") << "[" << Coordinate(at[0]) << ", " << Coordinate(at[1]) << "]";
      }
      s << "]}";
      first = false;
    }
  s << "\n  ]\n}\n";
  return s.str();
}

}  // namespace posemorph::bake::cli
