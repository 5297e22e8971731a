// SPDX-License-Identifier: MIT
#include "preview.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>

#include "posemorph/bake/pose_colours.h"

namespace posemorph::bake {
namespace {

struct Rgb {
  double r, g, b;
};

Rgb PoseRgb(std::size_t pose) {
  const PoseColour c = PoseColourOf(std::uint32_t(pose));
  return {double(c.r), double(c.g), double(c.b)};
}

Rgb Mix(const std::vector<double>& w) {
  Rgb c{0, 0, 0};
  for (std::size_t i = 0; i < w.size(); ++i) {
    const Rgb p = PoseRgb(i);
    const double wi = std::clamp(w[i], 0.0, 1.0);
    c.r += wi * p.r, c.g += wi * p.g, c.b += wi * p.b;
  }
  return c;
}

std::string Hex(Rgb c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", int(std::clamp(c.r, 0.0, 255.0)), int(std::clamp(c.g, 0.0, 255.0)),
                int(std::clamp(c.b, 0.0, 255.0)));
  return buf;
}

std::string Escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

std::string Name(StringView v) { return std::string(v.data, v.size); }

struct Box {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  void Add(double x, double y) {
    x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
  }
  void Add(const std::vector<double>& p) {
    for (std::size_t k = 0; k + 1 < p.size(); k += 2) Add(p[k], p[k + 1]);
  }
};

// The largest width or height over frames: one scale for all of them, so
// sizes compare, while each frame is centred in its own cell.
double CommonExtent(const std::vector<const std::vector<double>*>& frames) {
  double extent = 1e-12;
  for (const auto* f : frames) {
    Box b;
    b.Add(*f);
    extent = std::max({extent, b.x1 - b.x0, b.y1 - b.y0});
  }
  return extent;
}

// One <path> with every triangle: filled with the blend colour, thin edges,
// centred on (cx, cy), `extent` mesh units to 2 half pixels, y up.
void MeshPath(std::ostringstream& svg, const Rig& rig, const std::vector<double>& p, double extent, double cx,
              double cy, double half, const std::string& fill) {
  Box box;
  box.Add(p);
  const double scale = 2 * half / extent;
  const double mx = 0.5 * (box.x0 + box.x1), my = 0.5 * (box.y0 + box.y1);
  auto X = [&](std::uint32_t v) { return cx + (p[2 * v] - mx) * scale; };
  auto Y = [&](std::uint32_t v) { return cy - (p[2 * v + 1] - my) * scale; };
  svg << "<path fill=\"" << fill
      << "\" fill-opacity=\"0.85\" stroke=\"#222\" stroke-width=\"0.3\" stroke-linejoin=\"round\" d=\"";
  svg.precision(2);
  svg << std::fixed;
  const auto tris = rig.triangles();
  for (std::uint32_t t = 0; t < rig.triangle_count(); ++t) {
    const std::uint32_t a = tris[3 * t], b = tris[3 * t + 1], c = tris[3 * t + 2];
    svg << 'M' << X(a) << ',' << Y(a) << 'L' << X(b) << ',' << Y(b) << 'L' << X(c) << ',' << Y(c) << 'Z';
  }
  svg << "\"/>\n";
  svg.unsetf(std::ios::floatfield);
  svg.precision(6);
}

void SvgHeader(std::ostringstream& svg, double w, double h, const std::string& title) {
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << w << "\" height=\"" << h << "\" viewBox=\"0 0 " << w
      << ' ' << h << "\" font-family=\"sans-serif\">\n<rect width=\"100%\" height=\"100%\" fill=\"#fafafa\"/>\n"
      << "<text x=\"12\" y=\"24\" font-size=\"16\" font-weight=\"bold\">" << Escape(title) << "</text>\n";
}

void Label(std::ostringstream& svg, double x, double y, const std::string& text, int size = 10) {
  svg << "<text x=\"" << x << "\" y=\"" << y << "\" font-size=\"" << size << "\" text-anchor=\"middle\">"
      << Escape(text) << "</text>\n";
}

}  // namespace

Frame EvaluateFrame(const Rig& rig, double x, double y, const EvalOptions& options) {
  const std::size_t N = rig.pose_count();
  Frame f;
  f.x = x, f.y = y;
  f.raw.resize(N), f.texture.resize(N);
  std::vector<double> limited(N), work(rig.morph_workspace_size());
  f.positions.resize(2 * std::size_t(rig.vertex_count()));
  WeightsJob wj;
  wj.rig = &rig;
  wj.x = x, wj.y = y;
  wj.sigma = options.sigma < 0 ? rig.default_sigma() : options.sigma;
  wj.limit_weights = options.limit_weights;
  wj.raw = MakeSpan(f.raw), wj.limited = MakeSpan(limited), wj.texture = MakeSpan(f.texture);
  wj.Run();
  MorphJob mj;
  mj.rig = &rig;
  mj.weights = MakeSpan(f.raw), mj.limited_weights = MakeSpan(limited);
  mj.interpolation = options.interpolation;
  mj.workspace = MakeSpan(work), mj.positions = MakeSpan(f.positions);
  mj.Run();
  return f;
}

std::string FramesSvg(const Rig& rig, const std::vector<Frame>& frames, const std::string& title) {
  const double cell = frames.size() == 1 ? 480 : 160;
  const int columns = int(std::min<std::size_t>(frames.size(), 8));
  const int rows = int((frames.size() + columns - 1) / columns);
  std::vector<const std::vector<double>*> all;
  for (const Frame& f : frames) all.push_back(&f.positions);
  const double extent = CommonExtent(all);
  std::ostringstream svg;
  SvgHeader(svg, columns * cell + 24, rows * (cell + 16) + 48, title);
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const double cx = 12 + (k % columns + 0.5) * cell, cy = 40 + (k / columns) * (cell + 16) + cell / 2;
    MeshPath(svg, rig, frames[k].positions, extent, cx, cy, cell * 0.45, Hex(Mix(frames[k].texture)));
    Label(svg, cx, cy + cell / 2 + 10, frames[k].label);
  }
  svg << "</svg>\n";
  return svg.str();
}

std::string FramesJson(const Rig& rig, const std::vector<Frame>& frames) {
  nlohmann::json out = nlohmann::json::array();
  for (const Frame& f : frames) {
    nlohmann::json j;
    j["point"] = {f.x, f.y};
    if (!f.label.empty()) j["label"] = f.label;
    j["weights"] = f.raw;
    j["texture_weights"] = f.texture;
    nlohmann::json v = nlohmann::json::array();
    for (std::size_t k = 0; k + 1 < f.positions.size(); k += 2) v.push_back({f.positions[k], f.positions[k + 1]});
    j["vertices"] = std::move(v);
    out.push_back(std::move(j));
  }
  nlohmann::json root;
  nlohmann::json tris = nlohmann::json::array();
  for (std::uint32_t t = 0; t < rig.triangle_count(); ++t)
    tris.push_back({rig.triangles()[3 * t], rig.triangles()[3 * t + 1], rig.triangles()[3 * t + 2]});
  root["triangles"] = std::move(tris);
  root["frames"] = std::move(out);
  return root.dump(1) + "\n";
}

std::string FrameObj(const Rig& rig, const Frame& f) {
  std::ostringstream obj;
  obj.precision(17);
  obj << "# posemorph frame at pose-space point (" << f.x << ", " << f.y << ")\n";
  for (std::size_t k = 0; k + 1 < f.positions.size(); k += 2)
    obj << "v " << f.positions[k] << ' ' << f.positions[k + 1] << " 0\n";
  for (std::uint32_t t = 0; t < rig.triangle_count(); ++t)
    obj << "f " << rig.triangles()[3 * t] + 1 << ' ' << rig.triangles()[3 * t + 1] + 1 << ' '
        << rig.triangles()[3 * t + 2] + 1 << '\n';
  return obj.str();
}

std::vector<std::array<double, 2>> SheetPoints(const Rig& rig, int columns, int rows, std::array<double, 4>* box) {
  const std::uint32_t N = rig.pose_count();
  const auto pts = rig.pose_points();
  Box pbox;
  for (std::uint32_t i = 0; i < N; ++i) pbox.Add(pts[2 * i], pts[2 * i + 1]);
  const double spread = std::max(pbox.x1 - pbox.x0, pbox.y1 - pbox.y0);
  // Sample the points' box plus a quarter of their spread: the outer ring is extrapolation.
  const double ex = 0.25 * spread;
  const double sx0 = pbox.x0 - ex, sx1 = pbox.x1 + ex, sy0 = pbox.y0 - ex, sy1 = pbox.y1 + ex;
  if (pbox.y1 - pbox.y0 < 1e-9 * spread) rows = 1;
  if (box) *box = {sx0, sy0, sx1, sy1};
  std::vector<std::array<double, 2>> out;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c)
      out.push_back({sx0 + (sx1 - sx0) * c / std::max(1, columns - 1),
                     rows == 1 ? 0.5 * (pbox.y0 + pbox.y1) : sy1 - (sy1 - sy0) * r / (rows - 1)});
  return out;
}

std::string ContactSheetSvg(const Rig& rig, const std::string& title, int columns, int rows,
                            const EvalOptions& options) {
  const std::uint32_t N = rig.pose_count();
  const auto pts = rig.pose_points();
  std::array<double, 4> sampled{};
  const std::vector<std::array<double, 2>> points = SheetPoints(rig, columns, rows, &sampled);
  rows = int(points.size()) / columns;
  const double sx0 = sampled[0], sy0 = sampled[1], sx1 = sampled[2], sy1 = sampled[3];

  std::vector<Frame> samples, bases;
  std::vector<const std::vector<double>*> all;
  for (const auto& p : points) samples.push_back(EvaluateFrame(rig, p[0], p[1], options));
  for (std::uint32_t i = 0; i < N; ++i) {
    bases.push_back(EvaluateFrame(rig, pts[2 * i], pts[2 * i + 1], options));
    bases.back().label = Name(rig.pose_name(i));
  }
  for (const Frame& f : samples) all.push_back(&f.positions);
  for (const Frame& f : bases) all.push_back(&f.positions);
  const double extent = CommonExtent(all);

  const double cell = 110, map = 320, top = 40;
  const double base_row = cell + 24;
  const double width = 24 + map + 24 + columns * cell;
  const double height = top + base_row + std::max(map + 40, rows * cell + 20);
  std::ostringstream svg;
  SvgHeader(svg, width, height, title);

  // Base poses in a row, each in its own colour.
  for (std::uint32_t i = 0; i < N; ++i) {
    const double cx = 12 + (i + 0.5) * cell, cy = top + cell / 2;
    MeshPath(svg, rig, bases[i].positions, extent, cx, cy, cell * 0.42, Hex(PoseRgb(i)));
    Label(svg, cx, cy + cell / 2 + 12, bases[i].label);
  }

  // Pose-space map: the grid's weight field coloured by the raw weights.
  const PoseSpaceGrid& g = rig.grid();
  const double gx1 = g.origin_x + g.cell * g.cells_x, gy1 = g.origin_y + g.cell * g.cells_y;
  const double mscale = map / std::max(gx1 - g.origin_x, gy1 - g.origin_y);
  const double mx0 = 12, my0 = top + base_row;
  auto MX = [&](double x) { return mx0 + (x - g.origin_x) * mscale; };
  auto MY = [&](double y) { return my0 + (gy1 - y) * mscale; };
  const int res = 48;
  const double step = std::max(gx1 - g.origin_x, gy1 - g.origin_y) / res;
  std::vector<double> raw(N);
  for (int j = 0; j < res; ++j)
    for (int i = 0; i < res; ++i) {
      const double x = g.origin_x + (i + 0.5) * step, y = g.origin_y + (j + 0.5) * step;
      if (x > gx1 || y > gy1) continue;
      WeightsJob wj;
      wj.rig = &rig, wj.x = x, wj.y = y, wj.raw = MakeSpan(raw);
      wj.Run();
      svg << "<rect x=\"" << MX(x - step / 2) << "\" y=\"" << MY(y + step / 2) << "\" width=\"" << step * mscale + 0.3
          << "\" height=\"" << step * mscale + 0.3 << "\" fill=\"" << Hex(Mix(raw)) << "\"/>\n";
    }
  svg << "<rect x=\"" << MX(sx0) << "\" y=\"" << MY(sy1) << "\" width=\"" << (sx1 - sx0) * mscale << "\" height=\""
      << std::max(2.0, (sy1 - sy0) * mscale) << "\" fill=\"none\" stroke=\"#000\" stroke-dasharray=\"4 3\"/>\n";
  for (const Frame& f : samples)
    svg << "<circle cx=\"" << MX(f.x) << "\" cy=\"" << MY(f.y) << "\" r=\"1.5\" fill=\"#000\"/>\n";
  for (std::uint32_t i = 0; i < N; ++i) {
    svg << "<circle cx=\"" << MX(pts[2 * i]) << "\" cy=\"" << MY(pts[2 * i + 1]) << "\" r=\"5\" fill=\"#fff\" stroke=\""
        << Hex(PoseRgb(i)) << "\" stroke-width=\"3\"/>\n";
    Label(svg, MX(pts[2 * i]), MY(pts[2 * i + 1]) - 8, bases[i].label);
  }
  Label(svg, mx0 + map / 2, my0 + map + 16, "pose space: colour = weights, dashed = sampled area", 10);

  // The sampled morphs, laid out as they sit in pose space.
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) {
      const Frame& f = samples[r * columns + c];
      const double cx = 12 + map + 24 + (c + 0.5) * cell, cy = my0 + (r + 0.5) * cell;
      MeshPath(svg, rig, f.positions, extent, cx, cy, cell * 0.42, Hex(Mix(f.texture)));
    }
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace posemorph::bake
