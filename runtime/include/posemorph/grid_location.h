// SPDX-License-Identifier: MIT
// The pose-space weight grid's geometry, and where a point lies in it: the
// one place this arithmetic is written. The bake solves the grid's node
// weights so that W(p_i) = e_i for exactly the barycentric coordinates the
// runtime's WeightsJob computes here, bit for bit (runtime/FORMAT.md, WGRD).
#pragma once
#include <cstddef>
#include <cstdint>

namespace posemorph {

// A regular grid of square cells over pose space.
struct GridGeometry {
  double origin_x = 0, origin_y = 0;  // lower-left corner
  double cell = 1;                    // square cell edge length
  std::uint32_t cells_x = 0, cells_y = 0;
  std::size_t corner_count() const { return (std::size_t(cells_x) + 1) * (std::size_t(cells_y) + 1); }
};

// The grid triangle holding a point and the point's barycentric coordinates
// in it. Nodes are numbered over the cell corners ((cells_x+1)(cells_y+1),
// row-major in y then x), then the cell centres (cells_x * cells_y, the same
// order). The value at the point is lambda[0] w(node[0]) + lambda[1]
// w(node[1]) + lambda[2] w(node[2]), summed in that order.
struct GridLocation {
  std::uint32_t cell = 0;  // j * cells_x + i
  std::uint32_t node[3] = {0, 0, 0};
  double lambda[3] = {0, 0, 0};
};

namespace detail {
inline double GridClamp(double v, double lo, double hi) { return v < lo ? lo : (v > hi ? hi : v); }
}  // namespace detail

// Points outside the grid are clamped onto its border; (x, y) must not be
// NaN (WeightsJob replaces NaN first). With `centres` (format 1.2) each cell
// is four triangles meeting at its centre; without (1.0, 1.1) it is split on
// its (0,0)-(1,1) diagonal.
inline GridLocation LocateInGrid(const GridGeometry& g, bool centres, double x, double y) {
  const double u = detail::GridClamp((x - g.origin_x) / g.cell, 0, double(g.cells_x));
  const double v = detail::GridClamp((y - g.origin_y) / g.cell, 0, double(g.cells_y));
  const std::uint32_t i = u >= g.cells_x ? g.cells_x - 1 : std::uint32_t(u);
  const std::uint32_t j = v >= g.cells_y ? g.cells_y - 1 : std::uint32_t(v);
  const double fx = detail::GridClamp(u - i, 0, 1), fy = detail::GridClamp(v - j, 0, 1);
  const std::uint32_t row = g.cells_x + 1, v00 = j * row + i, v10 = v00 + 1, v01 = v00 + row, v11 = v01 + 1;
  GridLocation at;
  at.cell = j * g.cells_x + i;
  auto set = [&at](std::uint32_t a, double la, std::uint32_t b, double lb, std::uint32_t c, double lc) {
    at.node[0] = a, at.node[1] = b, at.node[2] = c;
    at.lambda[0] = la, at.lambda[1] = lb, at.lambda[2] = lc;
  };
  if (centres) {
    // The diagonals fx = fy and fx + fy = 1 say which triangle holds the point.
    const std::uint32_t c = std::uint32_t(g.corner_count()) + at.cell;
    const double d1 = fx - fy, d2 = fx + fy - 1;
    if (d1 >= 0 && d2 <= 0)
      set(v00, -d2, v10, d1, c, 2 * fy);  // bottom: (0,0) (1,0) centre
    else if (d1 >= 0)
      set(v10, d1, v11, d2, c, 2 * (1 - fx));  // right: (1,0) (1,1) centre
    else if (d2 >= 0)
      set(v11, d2, v01, -d1, c, 2 * (1 - fy));  // top: (1,1) (0,1) centre
    else
      set(v01, -d1, v00, -d2, c, 2 * fx);  // left: (0,1) (0,0) centre
  } else if (fx >= fy) {
    set(v00, 1 - fx, v10, fx - fy, v11, fy);
  } else {
    set(v00, 1 - fy, v01, fy - fx, v11, fx);
  }
  return at;
}

}  // namespace posemorph
