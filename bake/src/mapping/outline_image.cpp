// SPDX-License-Identifier: MIT
// Drawing (PNG with alpha) -> outline. The shape is the largest 4-connected
// set of pixels with alpha >= threshold, holes filled, and every diagonal
// pinch closed (two pixels touching only at a corner), so its border is one
// simple curve. That curve is traced by marching squares through the pixel
// centres, crossing each cell edge where alpha crosses the threshold.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <deque>
#include <functional>
#include <unordered_map>

#include "geometry.h"
#include "posemorph/bake/import/layered_reference.h"
#include "posemorph/bake/mapping/outline_image.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/input_file.h"

namespace posemorph::bake::mapping {
namespace {

struct Mask {
  int w = 0, h = 0;  // padded by one transparent pixel on every side
  std::vector<unsigned char> in;
  unsigned char& at(int x, int y) { return in[std::size_t(y) * w + x]; }
  unsigned char at(int x, int y) const { return in[std::size_t(y) * w + x]; }
};

// The 4-connected components of the pixels of one value, found on runs (a
// row's maximal spans of that value) joined by union-find where they overlap
// the row above: memory and time go with the number of runs, not pixels.
struct Run {
  int x0, x1;            // [x0, x1) in one row
  std::uint32_t parent;  // union-find; a root is its component's first run
};
struct RunComponents {
  std::vector<Run> runs;                 // row by row, left to right
  std::vector<std::size_t> row_start;    // row y's runs: [row_start[y], row_start[y + 1])
  std::vector<std::uint32_t> component;  // per run; components numbered in raster order of their first pixel
  std::vector<std::size_t> sizes;        // pixels per component
};

std::uint32_t Root(std::vector<Run>& runs, std::uint32_t i) {
  while (runs[i].parent != i) {
    runs[i].parent = runs[runs[i].parent].parent;  // path halving
    i = runs[i].parent;
  }
  return i;
}

RunComponents Components(const Mask& m, unsigned char value) {
  RunComponents c;
  c.row_start.reserve(std::size_t(m.h) + 1);
  for (int y = 0; y < m.h; ++y) {
    c.row_start.push_back(c.runs.size());
    const unsigned char* row = m.in.data() + std::size_t(y) * m.w;
    for (int x = 0; x < m.w;) {
      if (row[x] != value) {
        ++x;
        continue;
      }
      int end = x + 1;
      while (end < m.w && row[end] == value) ++end;
      c.runs.push_back({x, end, std::uint32_t(c.runs.size())});
      x = end;
    }
    if (y == 0) continue;
    // Join the runs that overlap a run of the row above (sharing an edge).
    std::size_t a = c.row_start[std::size_t(y) - 1], b = c.row_start[y];
    const std::size_t a_end = c.row_start[y], b_end = c.runs.size();
    while (a < a_end && b < b_end) {
      const Run &up = c.runs[a], &here = c.runs[b];
      if (up.x1 <= here.x0) {
        ++a;
        continue;
      }
      if (here.x1 <= up.x0) {
        ++b;
        continue;
      }
      const std::uint32_t ra = Root(c.runs, std::uint32_t(a)), rb = Root(c.runs, std::uint32_t(b));
      if (ra != rb) c.runs[std::max(ra, rb)].parent = std::min(ra, rb);  // the earlier run stays the root
      if (c.runs[a].x1 < c.runs[b].x1)
        ++a;
      else
        ++b;
    }
  }
  c.row_start.push_back(c.runs.size());
  c.component.resize(c.runs.size());
  for (std::size_t i = 0; i < c.runs.size(); ++i) {
    const std::uint32_t root = Root(c.runs, std::uint32_t(i));  // root <= i: already numbered
    if (root == i) {
      c.component[i] = std::uint32_t(c.sizes.size());
      c.sizes.push_back(0);
    } else {
      c.component[i] = c.component[root];
    }
    c.sizes[c.component[i]] += std::size_t(c.runs[i].x1 - c.runs[i].x0);
  }
  return c;
}

// Sets every pixel of the runs of `c` whose component is not `keep` to `to`;
// returns how many.
std::size_t SetAllBut(Mask& m, const RunComponents& c, std::uint32_t keep, unsigned char to) {
  std::size_t changed = 0;
  for (int y = 0; y < m.h; ++y)
    for (std::size_t i = c.row_start[y]; i < c.row_start[std::size_t(y) + 1]; ++i) {
      if (c.component[i] == keep) continue;
      const Run& r = c.runs[i];
      std::memset(&m.at(r.x0, y), to, std::size_t(r.x1 - r.x0));
      changed += std::size_t(r.x1 - r.x0);
    }
  return changed;
}

// Background not connected to the border becomes shape. Returns pixels filled.
std::size_t FillHoles(Mask& m) {
  const RunComponents background = Components(m, 0);
  // The padding row is background and touches everything outside.
  return SetAllBut(m, background, background.component[0], 1);
}

// Two shape pixels meeting only at a corner would make the border touch
// itself; the shape takes one of the two background pixels of that block.
std::size_t ClosePinches(Mask& m) {
  std::size_t changed = 0;
  for (int y = 0; y + 1 < m.h; ++y)
    for (int x = 0; x + 1 < m.w; ++x) {
      const unsigned char a = m.at(x, y), b = m.at(x + 1, y), c = m.at(x, y + 1), d = m.at(x + 1, y + 1);
      if (a && d && !b && !c)
        m.at(x + 1, y) = 1, ++changed;
      else if (b && c && !a && !d)
        m.at(x, y) = 1, ++changed;
    }
  return changed;
}

// Alpha at padded coordinates (a border of 0 around the image).
double PaddedAlpha(const std::vector<unsigned char>& alpha, int width, int height, int x, int y) {
  if (x <= 0 || y <= 0 || x > width || y > height) return 0;
  return alpha[std::size_t(y - 1) * width + (x - 1)];
}

// The shape: pixels at or above the threshold, the largest 4-connected part
// kept (the others counted in `result`), holes filled, pinches closed.
Mask ShapeMask(const std::vector<unsigned char>& alpha, int width, int height, double threshold,
               const ErrorSource& source, ImageOutline& result) {
  auto a = [&](int x, int y) { return PaddedAlpha(alpha, width, height, x, y); };
  Mask m;
  m.w = width + 2;
  m.h = height + 2;
  m.in.assign(std::size_t(m.w) * m.h, 0);
  const double cut = threshold * 255.0;
  for (int y = 1; y <= height; ++y)
    for (int x = 1; x <= width; ++x) m.at(x, y) = a(x, y) >= cut;

  const RunComponents shape = Components(m, 1);
  const std::vector<std::size_t>& sizes = shape.sizes;
  if (sizes.empty())
    throw source.Error(
        "image is empty or fully transparent (no pixel has alpha >= " + std::to_string(threshold).substr(0, 4) + ")");
  const int keep = int(std::max_element(sizes.begin(), sizes.end()) - sizes.begin());
  result.dropped_pixels = SetAllBut(m, shape, std::uint32_t(keep), 0);
  result.dropped_components = int(sizes.size()) - 1;
  for (std::size_t c = 0; c < sizes.size(); ++c) {
    result.shape_pixels += sizes[c];
    if (int(c) != keep) result.dropped_parts.push_back(sizes[c]);
  }
  std::sort(result.dropped_parts.begin(), result.dropped_parts.end(), std::greater<std::size_t>());
  if (sizes[keep] < 4) throw source.Error("the drawn shape is smaller than 4 pixels");
  if (sizes.size() > 1) {
    // Where the largest dropped part lies (mask coordinates are the
    // drawing's plus the padding of 1).
    std::size_t largest = keep == 0 ? 1 : 0;
    for (std::size_t c = 0; c < sizes.size(); ++c)
      if (int(c) != keep && sizes[c] > sizes[largest]) largest = c;
    result.dropped_x0 = m.w, result.dropped_y0 = m.h, result.dropped_x1 = -1, result.dropped_y1 = -1;
    for (int y = 0; y < m.h; ++y)
      for (std::size_t i = shape.row_start[y]; i < shape.row_start[std::size_t(y) + 1]; ++i) {
        if (shape.component[i] != largest) continue;
        result.dropped_x0 = std::min(result.dropped_x0, shape.runs[i].x0 - 1);
        result.dropped_x1 = std::max(result.dropped_x1, shape.runs[i].x1 - 2);
        result.dropped_y0 = std::min(result.dropped_y0, y - 1);
        result.dropped_y1 = std::max(result.dropped_y1, y - 1);
      }
  }

  for (;;) {
    result.filled_hole_pixels += FillHoles(m);
    if (ClosePinches(m) == 0) break;
  }

  return m;
}

// Where the border crosses the cell edges (marching squares through the
// pixel centres, sub-pixel), linked edge to edge with the shape on one side.
struct Border {
  std::unordered_map<std::size_t, std::size_t> next;  // edge key -> edge key
  std::unordered_map<std::size_t, Point> where;
};

Border TraceBorder(const Mask& m, const std::vector<unsigned char>& alpha, int width, int height, double threshold,
                   const ErrorSource& source) {
  auto a = [&](int x, int y) { return PaddedAlpha(alpha, width, height, x, y); };
  Border border;
  std::unordered_map<std::size_t, std::size_t>& next = border.next;
  std::unordered_map<std::size_t, Point>& where = border.where;
  // Signed field through the pixel centres: positive inside. Pixels the mask
  // overrides (filled holes, dropped specks) sit just across the threshold.
  const double delta = 1.0 / 512;
  auto f = [&](int x, int y) {
    const double v = a(x, y) / 255.0 - threshold;
    return m.at(x, y) ? std::max(v, delta) : std::min(v, -delta);
  };
  auto centre = [](int x, int y) { return Point(x - 0.5, y - 0.5); };  // padded -> image pixel centre
  // Crossing points keyed by cell edge: 2 * pixel index (+1 for the vertical edge below it).
  auto crossing = [&](int x0, int y0, int x1, int y1) {
    const double f0 = f(x0, y0), f1 = f(x1, y1);
    const double t = f0 / (f0 - f1);
    return Point(centre(x0, y0) + t * (centre(x1, y1) - centre(x0, y0)));
  };
  for (int y = 0; y + 1 < m.h; ++y)
    for (int x = 0; x + 1 < m.w; ++x) {
      const unsigned char c0 = m.at(x, y);
      if (c0 == m.at(x + 1, y) && c0 == m.at(x, y + 1) && c0 == m.at(x + 1, y + 1)) continue;  // no crossing
      // Walk the cell's corners c0 (x,y) c1 (x+1,y) c2 (x+1,y+1) c3 (x,y+1).
      const int cx[4] = {x, x + 1, x + 1, x}, cy[4] = {y, y, y + 1, y + 1};
      bool in[4];
      for (int k = 0; k < 4; ++k) in[k] = m.at(cx[k], cy[k]) != 0;
      std::size_t leave = 0, enter = 0;
      int crossings = 0;
      for (int k = 0; k < 4; ++k) {
        const int l = (k + 1) % 4;
        if (in[k] == in[l]) continue;
        ++crossings;
        // Key of the edge between corners k and l.
        const int ex = std::min(cx[k], cx[l]), ey = std::min(cy[k], cy[l]);
        const std::size_t key = 2 * (std::size_t(ey) * m.w + ex) + (cx[k] == cx[l] ? 1 : 0);
        if (!where.count(key)) where[key] = crossing(cx[k], cy[k], cx[l], cy[l]);
        (in[k] ? leave : enter) = key;
      }
      if (crossings == 0) continue;
      if (crossings != 2) throw source.Error("internal: ambiguous marching-squares cell");
      next[leave] = enter;
      if (next.size() > kMaxTracedBorder)
        throw source.Error("the shape's border crosses more than " + std::to_string(kMaxTracedBorder) +
                           " pixel edges (the limit; its outline would be too intricate to map)");
    }

  return border;
}

// Every loop of the border; the outer one is the one enclosing the most area.
Polygon OuterLoop(const Border& border) {
  const std::unordered_map<std::size_t, std::size_t>& next = border.next;
  const std::unordered_map<std::size_t, Point>& where = border.where;
  std::unordered_map<std::size_t, bool> seen;
  Polygon best;
  double best_area = 0;
  for (const auto& [start, unused] : next) {
    (void)unused;
    if (seen.count(start)) continue;
    Polygon loop;
    std::size_t k = start;
    do {
      seen[k] = true;
      loop.push_back(where.at(k));
      k = next.at(k);
    } while (k != start && loop.size() <= next.size());
    const double area = std::abs(SignedArea(loop));
    if (area > best_area) best_area = area, best = std::move(loop);
  }
  return best;
}

// A pixel just below the threshold with opaque pixels on three sides (a
// faint pixel in pixel art) makes the border dip almost to its centre: a
// notch a hundredth of a pixel wide and a pixel deep, whose edges point
// every way and whose normals no enclosing polygon can follow. Filling
// them: a concave corner whose triangle with its neighbours is thinner than
// kNotchWidth pixels (twice its area over its longest side) goes, until
// none is left. Filling only adds to the shape, so the mesh still covers
// every pixel the threshold kept.
constexpr double kNotchWidth = 1.0 / 16;
Polygon FillNotches(const Polygon& loop) {
  std::vector<Point> p = loop;
  const double orientation = SignedArea(p) > 0 ? 1.0 : -1.0;
  // Each pass fills what the last uncovered; 64 bound the work on any
  // input (a notch a pixel wide is gone in two or three).
  bool removed = true;
  for (int pass = 0; pass < 64 && removed && p.size() > 4; ++pass) {
    removed = false;
    std::vector<Point> kept;
    kept.reserve(p.size());
    const std::size_t n = p.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Point& a = kept.empty() ? p[n - 1] : kept.back();
      const Point &v = p[i], &b = p[(i + 1) % n];
      const double twice_area = orientation * ((v - a).x() * (b - v).y() - (v - a).y() * (b - v).x());
      const double longest = std::max({(v - a).norm(), (b - v).norm(), (b - a).norm()});
      const bool room = n - (i - kept.size()) > 4;  // never below four corners
      if (twice_area < 0 && -twice_area < kNotchWidth * longest && room) {
        removed = true;  // a concave corner of a thin notch: filled
        continue;
      }
      kept.push_back(v);
    }
    p = std::move(kept);
  }
  return p;
}

}  // namespace

ImageOutline OutlineFromAlpha(const std::vector<unsigned char>& alpha, int width, int height, double threshold,
                              const ErrorSource& source, bool fill_notches) {
  if (!(threshold > 0 && threshold <= 1)) throw source.Error("alpha threshold must be in (0, 1]");
  if (width <= 0 || height <= 0 || alpha.size() != std::size_t(width) * std::size_t(height))
    throw source.Error("image is empty");
  ImageOutline result;
  result.width = width;
  result.height = height;
  const Mask m = ShapeMask(alpha, width, height, threshold, source, result);
  result.outline = OuterLoop(TraceBorder(m, alpha, width, height, threshold, source));
  if (fill_notches) {
    const std::size_t before = result.outline.size();
    result.outline = FillNotches(result.outline);
    result.filled_notch_corners = before - result.outline.size();
  }
  return result;
}

ImageOutline OutlineFromPng(const std::string& path, double threshold, const ErrorSource& source, bool fill_notches) {
  int width = 0, height = 0;
  const std::vector<unsigned char> alpha = ReadPngAlpha(path, &width, &height, source);
  return OutlineFromAlpha(alpha, width, height, threshold, source, fill_notches);
}

ImageOutline OutlineFromPng(const std::string& path, double threshold, const ErrorSource& source, bool fill_notches,
                            bool drop_shadows, int halvings) {
  return OutlineFromPngBytes(import::ReadDrawingBytes(path, "a PNG drawing", source), threshold, source, fill_notches,
                             drop_shadows, halvings);
}

namespace {

// The shape of `alpha` traced on pyramid level `halvings`, in the drawing's
// pixels, with the drop shadow `found` recorded.
ImageOutline OutlineFromAlphaAtLevel(std::vector<unsigned char> alpha, int width, int height, double threshold,
                                     const ErrorSource& source, bool fill_notches, int halvings,
                                     const ImageOutline& found) {
  ImageOutline result;
  if (halvings == 0) {
    result = OutlineFromAlpha(alpha, width, height, threshold, source, fill_notches);
  } else {
    int level_width = 0, level_height = 0;
    const std::vector<unsigned char> level = AlphaAtLevel(alpha, width, height, halvings, &level_width, &level_height);
    alpha = {};
    result = OutlineFromAlpha(level, level_width, level_height, threshold, source, fill_notches);
    const double scale = std::ldexp(1.0, halvings);  // exact: a power of two
    for (Point& p : result.outline) p *= scale;
    const std::size_t area = std::size_t(1) << (2 * halvings);
    result.width = width;
    result.height = height;
    result.dropped_pixels *= area;
    for (std::size_t& part : result.dropped_parts) part *= area;
    // A working pixel covers 2^halvings drawing pixels each way.
    const int side = 1 << halvings;
    result.dropped_x0 *= side, result.dropped_y0 *= side;
    result.dropped_x1 = (result.dropped_x1 + 1) * side - 1, result.dropped_y1 = (result.dropped_y1 + 1) * side - 1;
    result.shape_pixels *= area;
    result.filled_hole_pixels *= area;
  }
  result.shadow_pixels = found.shadow_pixels;
  result.shadow_x0 = found.shadow_x0, result.shadow_y0 = found.shadow_y0;
  result.shadow_x1 = found.shadow_x1, result.shadow_y1 = found.shadow_y1;
  result.shadow_alpha = found.shadow_alpha;
  return result;
}

}  // namespace

ImageOutline OutlineFromPngBytes(const std::vector<unsigned char>& png, double threshold, const ErrorSource& source,
                                 bool fill_notches, bool drop_shadows, int halvings) {
  int width = 0, height = 0;
  if (drop_shadows) {
    const std::vector<unsigned char> rgba = DecodePngRgba(png, &width, &height, source);
    return OutlineFromRgba(rgba, width, height, threshold, source, fill_notches, true, halvings);
  }
  std::vector<unsigned char> alpha = DecodePngAlpha(png, &width, &height, source);  // sets width, height first
  return OutlineFromAlphaAtLevel(std::move(alpha), width, height, threshold, source, fill_notches, halvings,
                                 ImageOutline{});
}

ImageOutline OutlineFromRgba(const std::vector<unsigned char>& rgba, int width, int height, double threshold,
                             const ErrorSource& source, bool fill_notches, bool drop_shadows, int halvings) {
  const std::size_t n = std::size_t(width) * std::size_t(height);
  std::vector<unsigned char> alpha(n);
  for (std::size_t i = 0; i < n; ++i) alpha[i] = rgba[4 * i + 3];
  ImageOutline found;
  std::vector<unsigned char> shadow;
  if (drop_shadows && FindDropShadow(rgba.data(), width, height, threshold, shadow, found) > 0)
    for (std::size_t i = 0; i < n; ++i)
      if (shadow[i]) alpha[i] = 0;  // transparent to the tracing; the drawing keeps it
  return OutlineFromAlphaAtLevel(std::move(alpha), width, height, threshold, source, fill_notches, halvings, found);
}

ImageOutline OutlineFromPng(const std::string& path, double threshold) {
  return OutlineFromPng(path, threshold, ErrorSource(path));
}

ImageOutline OutlineFromPngBytes(const std::vector<unsigned char>& png, double threshold, const ErrorSource& source) {
  return OutlineFromPngBytes(png, threshold, source, false, false, 0);
}

}  // namespace posemorph::bake::mapping
