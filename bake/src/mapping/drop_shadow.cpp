// SPDX-License-Identifier: MIT
// A drawing's drop shadow (outline_image.h, FindDropShadow): dark,
// semi-transparent pixels beyond the anti-aliased fringe of the solid ones,
// which the tracing then takes as transparent.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "posemorph/bake/mapping/outline_image.h"

namespace posemorph::bake::mapping {

std::size_t FindDropShadow(const unsigned char* rgba, int width, int height, double threshold,
                           std::vector<unsigned char>& shadow, ImageOutline& report) {
  const std::size_t n = std::size_t(width) * std::size_t(height);
  shadow.assign(n, 0);
  const int solid_cut = 179, band = 2;  // alpha 0.7; the fringe's width in pixels
  const double cut = threshold * 255.0;
  auto soft_dark = [&](std::size_t i) {
    const unsigned char* p = rgba + 4 * i;
    if (p[3] < cut || p[3] >= solid_cut) return false;
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2] <= 0.3 * 255;  // straight colour
  };
  std::size_t solid = 0, soft = 0;
  for (std::size_t i = 0; i < n; ++i) solid += rgba[4 * i + 3] >= solid_cut, soft += soft_dark(i);
  if (solid < 16 || soft < std::max<std::size_t>(12, solid * 3 / 100)) return 0;  // no region could be large enough
  // Within `band` pixels (a square) of a solid pixel: two separable passes.
  std::vector<unsigned char> rows(n, 0), near(n, 0);
  for (int y = 0; y < height; ++y) {
    int last = -1000000;  // the last solid column seen, from the left, then from the right
    for (int x = 0; x < width; ++x) {
      if (rgba[4 * (std::size_t(y) * width + x) + 3] >= solid_cut) last = x;
      rows[std::size_t(y) * width + x] = x - last <= band;
    }
    last = 1000000;
    for (int x = width - 1; x >= 0; --x) {
      if (rgba[4 * (std::size_t(y) * width + x) + 3] >= solid_cut) last = x;
      rows[std::size_t(y) * width + x] |= last - x <= band;
    }
  }
  for (int x = 0; x < width; ++x)
    for (int y = 0; y < height; ++y) {
      bool any = false;
      for (int d = -band; d <= band && !any; ++d) {
        const int yy = y + d;
        any = yy >= 0 && yy < height && rows[std::size_t(yy) * width + x];
      }
      near[std::size_t(y) * width + x] = any;
    }
  // 4-connected regions of soft dark pixels beyond the band (a flood fill on a stack).
  std::vector<std::uint32_t> region(n, 0);
  std::vector<std::size_t> stack, members;
  std::uint32_t regions = 0;
  std::size_t found = 0;
  double alpha_sum = 0;
  report.shadow_x0 = width, report.shadow_y0 = height, report.shadow_x1 = -1, report.shadow_y1 = -1;
  for (std::size_t seed = 0; seed < n; ++seed) {
    if (region[seed] || near[seed] || !soft_dark(seed)) continue;
    ++regions;
    members.clear();
    stack.assign(1, seed);
    region[seed] = regions;
    double sum = 0;
    while (!stack.empty()) {
      const std::size_t i = stack.back();
      stack.pop_back();
      members.push_back(i);
      sum += rgba[4 * i + 3];
      const int x = int(i % std::size_t(width)), y = int(i / std::size_t(width));
      const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
      for (int k = 0; k < 4; ++k) {
        if (nx[k] < 0 || ny[k] < 0 || nx[k] >= width || ny[k] >= height) continue;
        const std::size_t j = std::size_t(ny[k]) * width + nx[k];
        if (!region[j] && !near[j] && soft_dark(j)) region[j] = regions, stack.push_back(j);
      }
    }
    if (members.size() < std::max<std::size_t>(12, solid * 3 / 100)) continue;
    const double mean = sum / double(members.size());
    // Grown into the band, through its dark pixels no more opaque than the
    // region's mean alpha + 0.25: the shadow under the feet.
    for (std::size_t m = 0; m < members.size(); ++m) {
      const std::size_t i = members[m];
      const int x = int(i % std::size_t(width)), y = int(i / std::size_t(width));
      const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
      for (int k = 0; k < 4; ++k) {
        if (nx[k] < 0 || ny[k] < 0 || nx[k] >= width || ny[k] >= height) continue;
        const std::size_t j = std::size_t(ny[k]) * width + nx[k];
        // Unclaimed only: a band pixel two shadows reach belongs to the first.
        if (region[j] != 0 || !near[j] || !soft_dark(j) || rgba[4 * j + 3] > mean + 0.25 * 255) continue;
        region[j] = regions;
        members.push_back(j);
        sum += rgba[4 * j + 3];
      }
    }
    for (std::size_t i : members) {
      shadow[i] = 1;
      const int x = int(i % std::size_t(width)), y = int(i / std::size_t(width));
      report.shadow_x0 = std::min(report.shadow_x0, x), report.shadow_x1 = std::max(report.shadow_x1, x);
      report.shadow_y0 = std::min(report.shadow_y0, y), report.shadow_y1 = std::max(report.shadow_y1, y);
    }
    found += members.size();
    alpha_sum += sum;
  }
  report.shadow_pixels = found;
  report.shadow_alpha = found ? alpha_sum / double(found) / 255.0 : 0;
  return found;
}

}  // namespace posemorph::bake::mapping
