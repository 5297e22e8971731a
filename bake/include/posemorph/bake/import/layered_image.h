// SPDX-License-Identifier: MIT
// Layered drawings in: the layer tree of an OpenRaster (.ora: Krita, GIMP,
// MyPaint) or Photoshop (.psd: Photoshop, Krita, GIMP) file, read within
// bounds from hostile bytes, and a layer or group composited onto the
// canvas as a drawing the bake maps.
//
// What is honoured: layer offsets (a layer's box may lie partly off the
// canvas), visibility, opacity, group nesting (a group is composited on its
// own, then onto what is below it, with its opacity). What is not supported
// is refused or ignored with one note naming the file and the layer:
//   refused (BakeError): PSD colour modes other than RGB and greyscale, 16-
//     and 32-bit channels, PSB, ZIP-compressed channels; ORA layers that are
//     not PNG; a canvas over 4096 x 4096 (kMaxDrawingPixels); more than
//     kMaxLayers entries, groups nested deeper than kMaxDepth, more than
//     kMaxLayerPixels pixels in all layers, files over kMaxLayeredFileBytes;
//     any length, offset or count that points outside the file.
//   ignored, with a note: blend modes other than normal (drawn as normal),
//     layer masks and vector masks (drawn unmasked), clipping (drawn
//     unclipped), adjustment and fill layers and ORA text elements (left
//     out), PSD groups' pass-through (composited as an isolated group, the
//     same for normal layers).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace posemorph::bake::import {

constexpr std::uint64_t kMaxLayeredFileBytes = std::uint64_t(256) << 20;
constexpr std::size_t kMaxLayers = 1024;                           // layers and groups together
constexpr int kMaxDepth = 16;                                      // groups within groups
constexpr std::uint64_t kMaxLayerPixels = std::uint64_t(1) << 27;  // all layers' boxes together

// One entry of the layer tree: a raster layer or a group.
struct Layer {
  std::string name;  // UTF-8
  bool group = false;
  bool visible = true;
  double opacity = 1;  // 0..1
  // A raster layer's box on the canvas (x, y may be negative) and its
  // straight-alpha RGBA pixels, row by row.
  int x = 0, y = 0, width = 0, height = 0;
  std::vector<unsigned char> rgba;
  std::vector<Layer> children;  // a group's, top first
};

struct LayeredImage {
  std::string file;
  int width = 0, height = 0;
  std::vector<Layer> layers;       // the top level, top first
  std::vector<std::string> notes;  // "FILE: layer 'NAME': what was ignored, and what was done instead"
};

// The file's layer tree; BakeError naming the file (and the layer) when it
// cannot be read or is refused (the header's list).
LayeredImage ReadOpenRaster(const std::string& path);
LayeredImage ReadOpenRasterBytes(const std::vector<unsigned char>& bytes, const std::string& file);
LayeredImage ReadPhotoshop(const std::string& path);
LayeredImage ReadPhotoshopBytes(const std::vector<unsigned char>& bytes, const std::string& file);
// By the file's extension (.ora or .psd, any case).
LayeredImage ReadLayeredImage(const std::string& path);
bool IsLayeredImagePath(const std::string& path);

// Straight-alpha RGBA of the canvas with `layers` (top first) composited
// over transparency, source-over with their opacity; hidden entries left
// out. A single visible layer of opacity 1 comes out with its own bytes
// (transparent pixels as 0, 0, 0, 0).
std::vector<unsigned char> Composite(const std::vector<Layer>& layers, int width, int height);
std::vector<unsigned char> Composite(const Layer& layer, int width, int height);
// A layer's name without the " #N" GIMP and Krita append to keep an
// image's names unique ("body #1" in a second pose's group is "body").
std::string WithoutCopyNumber(std::string name);

// Straight-alpha RGBA as PNG bytes; BakeError naming `file` when libpng cannot encode it.
std::vector<unsigned char> EncodeRgbaPng(const std::vector<unsigned char>& rgba, int width, int height,
                                         const std::string& file);

}  // namespace posemorph::bake::import
