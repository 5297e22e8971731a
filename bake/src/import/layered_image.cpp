// SPDX-License-Identifier: MIT
// Compositing a layer tree onto its canvas, and reading a layered file by
// its extension (layered_image.h).
#include "posemorph/bake/import/layered_image.h"

#include <png.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>

#include "posemorph/bake/error.h"

namespace posemorph::bake::import {
namespace {

// A premultiplied canvas of floats over a box of the document canvas.
struct Canvas {
  int x0 = 0, y0 = 0, width = 0, height = 0;
  std::vector<float> rgba;  // premultiplied, 0..1
};

struct Box {
  int x0, y0, x1, y1;  // half open
  bool Empty() const { return x1 <= x0 || y1 <= y0; }
};

Box Intersect(Box a, Box b) {
  return {std::max(a.x0, b.x0), std::max(a.y0, b.y0), std::min(a.x1, b.x1), std::min(a.y1, b.y1)};
}

// The box of what a visible entry draws, within `clip`.
Box Extent(const Layer& layer, Box clip) {
  if (!layer.visible || layer.opacity <= 0) return {0, 0, 0, 0};
  if (!layer.group) {
    const long long x1 = (long long)layer.x + layer.width, y1 = (long long)layer.y + layer.height;
    return Intersect({layer.x, layer.y, int(std::min<long long>(x1, clip.x1)), int(std::min<long long>(y1, clip.y1))},
                     clip);
  }
  Box out{0, 0, 0, 0};
  for (const Layer& child : layer.children) {
    const Box b = Extent(child, clip);
    if (b.Empty()) continue;
    out = out.Empty()
              ? b
              : Box{std::min(out.x0, b.x0), std::min(out.y0, b.y0), std::max(out.x1, b.x1), std::max(out.y1, b.y1)};
  }
  return out;
}

// Source-over of one premultiplied pixel (times `opacity`) onto `dst`.
inline void Over(float* dst, float r, float g, float b, float a, float opacity) {
  r *= opacity, g *= opacity, b *= opacity, a *= opacity;
  const float keep = 1 - a;
  dst[0] = r + dst[0] * keep;
  dst[1] = g + dst[1] * keep;
  dst[2] = b + dst[2] * keep;
  dst[3] = a + dst[3] * keep;
}

void Draw(const Layer& layer, float opacity, Canvas& dst, int depth);

// The children of a group, bottom first, onto `dst`, each with `opacity`.
void DrawChildren(const Layer& group, float opacity, Canvas& dst, int depth) {
  for (auto it = group.children.rbegin(); it != group.children.rend(); ++it) Draw(*it, opacity, dst, depth + 1);
}

void Draw(const Layer& layer, float opacity, Canvas& dst, int depth) {
  if (!layer.visible || layer.opacity <= 0 || depth > kMaxDepth) return;
  const float o = opacity * float(std::min(1.0, layer.opacity));
  const Box clip{dst.x0, dst.y0, dst.x0 + dst.width, dst.y0 + dst.height};
  if (layer.group) {
    // A group of opacity 1 draws its children straight onto what is below
    // (source-over is associative); a translucent one is composited on its
    // own first.
    if (layer.opacity >= 1) return DrawChildren(layer, o, dst, depth);
    const Box box = Extent(layer, clip);
    if (box.Empty()) return;
    Canvas own{box.x0, box.y0, box.x1 - box.x0, box.y1 - box.y0, {}};
    own.rgba.assign(std::size_t(own.width) * std::size_t(own.height) * 4, 0.f);
    DrawChildren(layer, 1.f, own, depth);
    for (int y = 0; y < own.height; ++y)
      for (int x = 0; x < own.width; ++x) {
        const float* s = &own.rgba[(std::size_t(y) * own.width + x) * 4];
        float* d = &dst.rgba[(std::size_t(y + own.y0 - dst.y0) * dst.width + std::size_t(x + own.x0 - dst.x0)) * 4];
        Over(d, s[0], s[1], s[2], s[3], o);
      }
    return;
  }
  const Box box = Extent(layer, clip);
  for (int y = box.y0; y < box.y1; ++y)
    for (int x = box.x0; x < box.x1; ++x) {
      const unsigned char* s = &layer.rgba[(std::size_t(y - layer.y) * layer.width + std::size_t(x - layer.x)) * 4];
      if (s[3] == 0) continue;
      const float a = s[3] / 255.f;
      float* d = &dst.rgba[(std::size_t(y - dst.y0) * dst.width + std::size_t(x - dst.x0)) * 4];
      Over(d, s[0] / 255.f * a, s[1] / 255.f * a, s[2] / 255.f * a, a, o);
    }
}

std::vector<unsigned char> Straight(const Canvas& c) {
  std::vector<unsigned char> out(c.rgba.size(), 0);
  for (std::size_t i = 0; i < c.rgba.size(); i += 4) {
    const float a = c.rgba[i + 3];
    const long alpha = std::lround(std::min(1.f, a) * 255.f);
    if (alpha <= 0) continue;
    for (int k = 0; k < 3; ++k)
      out[i + k] = (unsigned char)std::clamp(std::lround(c.rgba[i + k] / a * 255.f), 0L, 255L);
    out[i + 3] = (unsigned char)alpha;
  }
  return out;
}

std::string Lower(std::string s) {
  for (char& c : s) c = char(std::tolower((unsigned char)c));
  return s;
}

std::string ExtensionOf(const std::string& path) {
  const std::size_t dot = path.find_last_of('.'), slash = path.find_last_of("/\\");
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  return Lower(path.substr(dot + 1));
}

}  // namespace

std::vector<unsigned char> Composite(const std::vector<Layer>& layers, int width, int height) {
  Canvas c{0, 0, std::max(0, width), std::max(0, height), {}};
  c.rgba.assign(std::size_t(c.width) * std::size_t(c.height) * 4, 0.f);
  for (auto it = layers.rbegin(); it != layers.rend(); ++it) Draw(*it, 1.f, c, 0);
  return Straight(c);
}

std::vector<unsigned char> Composite(const Layer& layer, int width, int height) {
  Canvas c{0, 0, std::max(0, width), std::max(0, height), {}};
  c.rgba.assign(std::size_t(c.width) * std::size_t(c.height) * 4, 0.f);
  Draw(layer, 1.f, c, 0);
  return Straight(c);
}

bool IsLayeredImagePath(const std::string& path) {
  const std::string ext = ExtensionOf(path);
  return ext == "ora" || ext == "psd";
}

LayeredImage ReadLayeredImage(const std::string& path) {
  const std::string ext = ExtensionOf(path);
  if (ext == "ora") return ReadOpenRaster(path);
  if (ext == "psd") return ReadPhotoshop(path);
  throw BakeError(path, "not a layered drawing (.ora or .psd)");
}

std::vector<unsigned char> EncodeRgbaPng(const std::vector<unsigned char>& rgba, int width, int height,
                                         const std::string& file) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = png_uint_32(width);
  png.height = png_uint_32(height);
  png.format = PNG_FORMAT_RGBA;
  png_alloc_size_t size = 0;
  if (!png_image_write_get_memory_size(png, size, 0, rgba.data(), 0, nullptr))
    throw BakeError(file, std::string("cannot encode PNG: ") + png.message);
  std::vector<unsigned char> out(size);
  if (!png_image_write_to_memory(&png, out.data(), &size, 0, rgba.data(), 0, nullptr))
    throw BakeError(file, std::string("cannot encode PNG: ") + png.message);
  out.resize(size);
  return out;
}

std::string WithoutCopyNumber(std::string name) {
  const std::size_t hash = name.rfind(" #");
  if (hash != std::string::npos && hash + 2 < name.size() &&
      name.find_first_not_of("0123456789", hash + 2) == std::string::npos)
    name.resize(hash);
  return name;
}

}  // namespace posemorph::bake::import
