// SPDX-License-Identifier: MIT
// A drawing's outline from a PNG with alpha (stage 1 of N-way mapping).
#pragma once
#include <string>
#include <vector>

#include "posemorph/bake/mapping/polygon.h"

namespace posemorph::bake::mapping {

struct ImageOutline {
  Polygon outline;  // pixel units, y down (image rows); either orientation
  int width = 0, height = 0;
  int dropped_components = 0;  // separate parts smaller than the kept shape
  std::size_t dropped_pixels = 0;
  std::vector<std::size_t> dropped_parts;  // pixels of each dropped part, largest first
  std::size_t shape_pixels = 0;            // every pixel at or above the threshold, before anything is dropped
  std::size_t filled_hole_pixels = 0;
};
// PNG with alpha: pixels with alpha >= threshold form the shape; the largest
// 4-connected component is kept, holes filled, diagonal pinches closed, and
// the outline traced where alpha crosses the threshold (marching squares,
// sub-pixel). Throws BakeError naming the file.
ImageOutline OutlineFromPng(const std::string& path, double alpha_threshold);
// The same from a PNG already in memory (`file` names it in messages).
ImageOutline OutlineFromPngBytes(const std::vector<unsigned char>& png, double alpha_threshold,
                                 const std::string& file);
// The alpha channel of a PNG (any colour type), row by row. Throws BakeError naming the file.
std::vector<unsigned char> ReadPngAlpha(const std::string& path, int* width, int* height);
ImageOutline OutlineFromAlpha(const std::vector<unsigned char>& alpha, int width, int height, double alpha_threshold,
                              const std::string& file);

}  // namespace posemorph::bake::mapping
