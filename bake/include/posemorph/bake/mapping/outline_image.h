// SPDX-License-Identifier: MIT
// A drawing's outline from a PNG with alpha (stage 1 of N-way mapping).
#pragma once
#include <string>
#include <vector>

#include "posemorph/bake/error.h"
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
  std::size_t filled_notch_corners = 0;  // with fill_notches: corners of thin notches filled
};
// PNG with alpha: pixels with alpha >= threshold form the shape; the largest
// 4-connected component is kept, holes filled, diagonal pinches closed, and
// the outline traced where alpha crosses the threshold (marching squares,
// sub-pixel). Throws BakeError naming the file, or as `source` says (in a
// bake: "DESCRIPTION: POSE: DRAWING: problem"). With fill_notches, every
// concave corner of a notch thinner than 1/16 pixel (a faint pixel with
// opaque ones on three sides makes the border dip to its centre) is filled:
// the outline only grows, and its normals no longer point every way.
ImageOutline OutlineFromPng(const std::string& path, double alpha_threshold);
ImageOutline OutlineFromPng(const std::string& path, double alpha_threshold, const ErrorSource& source,
                            bool fill_notches = false);
// The same from a PNG already in memory (`source` names it in messages).
ImageOutline OutlineFromPngBytes(const std::vector<unsigned char>& png, double alpha_threshold,
                                 const ErrorSource& source);
// The alpha channel of a PNG (any colour type), row by row. Throws BakeError naming the file (or `source`).
std::vector<unsigned char> ReadPngAlpha(const std::string& path, int* width, int* height);
std::vector<unsigned char> ReadPngAlpha(const std::string& path, int* width, int* height, const ErrorSource& source);
// Straight-alpha RGBA bytes of a PNG with alpha, row by row (the same checks).
std::vector<unsigned char> ReadPngRgba(const std::string& path, int* width, int* height, const ErrorSource& source);
ImageOutline OutlineFromAlpha(const std::vector<unsigned char>& alpha, int width, int height, double alpha_threshold,
                              const ErrorSource& source, bool fill_notches = false);

}  // namespace posemorph::bake::mapping
