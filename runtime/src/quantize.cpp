// SPDX-License-Identifier: MIT
#include <cmath>

#include "posemorph/quantize.h"

namespace posemorph {
namespace {

std::uint16_t Quantize(double v, double origin, double extent) {
  double s = std::isnan(v) ? 0.5 : (v - origin) / extent;
  s = s < 0 ? 0 : (s > 1 ? 1 : s);
  return std::uint16_t(std::lround(s * 65535.0));
}

}  // namespace

QuantizedPoint QuantizePoint(const PoseSpaceGrid& g, double x, double y) {
  return {Quantize(x, g.origin_x, g.cell * g.cells_x), Quantize(y, g.origin_y, g.cell * g.cells_y)};
}

void DequantizePoint(const PoseSpaceGrid& g, QuantizedPoint q, double* x, double* y) {
  *x = g.origin_x + g.cell * g.cells_x * (q.x / 65535.0);
  *y = g.origin_y + g.cell * g.cells_y * (q.y / 65535.0);
}

void PackPoint(QuantizedPoint q, unsigned char out[4]) {
  out[0] = std::uint8_t(q.x & 0xFFu);
  out[1] = std::uint8_t(q.x >> 8);
  out[2] = std::uint8_t(q.y & 0xFFu);
  out[3] = std::uint8_t(q.y >> 8);
}

QuantizedPoint UnpackPoint(const unsigned char in[4]) {
  return {std::uint16_t(in[0] | in[1] << 8), std::uint16_t(in[2] | in[3] << 8)};
}

}  // namespace posemorph
