// SPDX-License-Identifier: MIT
// A pose-space point in 2 x 16 bits: what a networked avatar sends per frame.
// The range is the rig's weight grid (the runtime clamps to it anyway), so the
// step is grid extent / 65535 per axis.
#pragma once
#include "posemorph/export.h"
#include <cstdint>

#include "posemorph/rig.h"

namespace posemorph {

struct QuantizedPoint {
  std::uint16_t x = 0, y = 0;
};

PM_API QuantizedPoint QuantizePoint(const PoseSpaceGrid& grid, double x, double y);
PM_API void DequantizePoint(const PoseSpaceGrid& grid, QuantizedPoint q, double* x, double* y);
// Packs into / unpacks from 4 little-endian bytes.
PM_API void PackPoint(QuantizedPoint q, unsigned char out[4]);
PM_API QuantizedPoint UnpackPoint(const unsigned char in[4]);

}  // namespace posemorph
