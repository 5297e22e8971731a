// SPDX-License-Identifier: MIT
// A drawing's outline from a PNG with alpha (stage 1 of N-way mapping).
#pragma once
#include <string>
#include <vector>

#include "posemorph/bake/error.h"
#include "posemorph/bake/mapping/working_level.h"
#include "posemorph/bake/mapping/polygon.h"

namespace posemorph::bake::mapping {

struct ImageOutline {
  Polygon outline;  // pixel units, y down (image rows); either orientation
  int width = 0, height = 0;
  int dropped_components = 0;  // separate parts smaller than the kept shape
  std::size_t dropped_pixels = 0;
  std::vector<std::size_t> dropped_parts;  // pixels of each dropped part, largest first
  // The largest dropped part's box in the drawing's pixels (inclusive; the
  // first in raster order of the largest where several tie).
  int dropped_x0 = 0, dropped_y0 = 0, dropped_x1 = 0, dropped_y1 = 0;
  std::size_t shape_pixels = 0;  // every pixel at or above the threshold, before anything is dropped
  std::size_t filled_hole_pixels = 0;
  std::size_t filled_notch_corners = 0;  // with fill_notches: corners of thin notches filled
  // A drop shadow found and left out (OutlineFromPng with drop_shadows):
  // pixels, their box in the drawing's pixels and their mean alpha (0-1).
  std::size_t shadow_pixels = 0;
  int shadow_x0 = 0, shadow_y0 = 0, shadow_x1 = 0, shadow_y1 = 0;
  double shadow_alpha = 0;
};

// A drop shadow in straight-alpha RGBA: the pixels of every 4-connected
// region of dark (luminance <= 0.3), semi-transparent pixels (alpha under
// 0.7, at or above `threshold`) that lies more than 2 pixels from the
// drawing's solid pixels (alpha >= 0.7) and covers at least 3% of their
// count (and 12 pixels), grown into that 2-pixel band through the dark
// pixels there no more opaque than its mean alpha + 0.25; only when the drawing has 16 solid
// pixels or more (a drawing that is all soft has no shadow to tell apart).
// Marks them in `shadow` (one byte per pixel) and returns their count; the
// report's shadow fields describe them.
std::size_t FindDropShadow(const unsigned char* rgba, int width, int height, double threshold,
                           std::vector<unsigned char>& shadow, ImageOutline& report);
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
// The same with a drop shadow (FindDropShadow) left out of the shape when
// drop_shadows is set: its pixels count as transparent for the tracing.
// With `halvings` h > 0 the shape is traced on the drawing's pyramid level h
// (AlphaAtLevel: each traced pixel is the mean of 2^h x 2^h of the drawing's,
// after the drop shadow is left out at full resolution), and the outline is
// given in the drawing's pixels all the same (level coordinates times 2^h,
// exact); the pixel counts of the result count each level pixel as 4^h.
ImageOutline OutlineFromPng(const std::string& path, double alpha_threshold, const ErrorSource& source,
                            bool fill_notches, bool drop_shadows, int halvings = 0);
// The same from a PNG already in memory (`source` names it in messages).
ImageOutline OutlineFromPngBytes(const std::vector<unsigned char>& png, double alpha_threshold,
                                 const ErrorSource& source);
ImageOutline OutlineFromPngBytes(const std::vector<unsigned char>& png, double alpha_threshold,
                                 const ErrorSource& source, bool fill_notches, bool drop_shadows, int halvings);
// The same from straight-alpha RGBA pixels already decoded (DecodePngRgba).
ImageOutline OutlineFromRgba(const std::vector<unsigned char>& rgba, int width, int height, double alpha_threshold,
                             const ErrorSource& source, bool fill_notches, bool drop_shadows, int halvings);
// The alpha channel of a PNG (any colour type), row by row. Throws BakeError naming the file (or `source`).
std::vector<unsigned char> ReadPngAlpha(const std::string& path, int* width, int* height);
std::vector<unsigned char> ReadPngAlpha(const std::string& path, int* width, int* height, const ErrorSource& source);
// Straight-alpha RGBA bytes of a PNG with alpha, row by row (the same checks).
std::vector<unsigned char> ReadPngRgba(const std::string& path, int* width, int* height, const ErrorSource& source);
// The same from a PNG already in memory; and its alpha channel alone.
std::vector<unsigned char> DecodePngAlpha(const std::vector<unsigned char>& png, int* width, int* height,
                                          const ErrorSource& source);
std::vector<unsigned char> DecodePngRgba(const std::vector<unsigned char>& png, int* width, int* height,
                                         const ErrorSource& source);
ImageOutline OutlineFromAlpha(const std::vector<unsigned char>& alpha, int width, int height, double alpha_threshold,
                              const ErrorSource& source, bool fill_notches = false);

}  // namespace posemorph::bake::mapping
