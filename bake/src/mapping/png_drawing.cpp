// SPDX-License-Identifier: MIT
// A drawing's PNG bytes -> its alpha or straight-alpha RGBA pixels
// (outline_image.h), with the header's size checked before anything is
// decoded.
#include <png.h>

#include <cstdint>
#include <cstring>

#include "posemorph/bake/error.h"
#include "posemorph/bake/import/layered_reference.h"
#include "posemorph/bake/input_file.h"
#include "posemorph/bake/mapping/outline_image.h"

namespace posemorph::bake::mapping {

// The alpha bytes, or with `rgba` straight-alpha RGBA bytes, row by row.
namespace {

std::vector<unsigned char> DecodePng(const std::vector<unsigned char>& file, const ErrorSource& source, int* width,
                                     int* height, bool rgba) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, file.data(), file.size()))
    throw source.Error(std::string("cannot read PNG: ") + image.message);
  if (!(image.format & PNG_FORMAT_FLAG_ALPHA)) {
    png_image_free(&image);
    throw source.Error(
        "has no alpha channel (and no transparent colour): the bake takes the character's shape from "
        "alpha; save the drawing with transparency");
  }
  image.format = rgba ? PNG_FORMAT_RGBA : PNG_FORMAT_GA;  // grey + alpha: only the alpha is used
  // The header's size, checked before anything is decoded: a small file can
  // claim a huge image (a decompression bomb).
  if (image.width == 0 || image.height == 0 || image.width > 16384 || image.height > 16384 ||
      std::uint64_t(image.width) * image.height > kMaxDrawingPixels) {
    png_image_free(&image);
    throw source.Error("PNG size " + std::to_string(image.width) + " x " + std::to_string(image.height) +
                       " is outside 1..16384 per side or above the limit of " + std::to_string(kMaxDrawingPixels) +
                       " pixels");
  }
  std::vector<unsigned char> ga(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, ga.data(), 0, nullptr)) {
    const std::string message = image.message;
    png_image_free(&image);
    throw source.Error("cannot decode PNG: " + message);
  }
  *width = int(image.width);
  *height = int(image.height);
  if (rgba) return ga;
  // Keep the alpha bytes in place (byte i moves down from 2i + 1).
  const std::size_t pixels = std::size_t(image.width) * image.height;
  for (std::size_t i = 0; i < pixels; ++i) ga[i] = ga[2 * i + 1];
  ga.resize(pixels);
  ga.shrink_to_fit();
  return ga;
}

}  // namespace

std::vector<unsigned char> DecodePngAlpha(const std::vector<unsigned char>& png, int* width, int* height,
                                          const ErrorSource& source) {
  return DecodePng(png, source, width, height, false);
}

std::vector<unsigned char> ReadPngAlpha(const std::string& path, int* width, int* height, const ErrorSource& source) {
  return DecodePng(import::ReadDrawingBytes(path, "a PNG drawing", source), source, width, height, false);
}

std::vector<unsigned char> DecodePngRgba(const std::vector<unsigned char>& png, int* width, int* height,
                                         const ErrorSource& source) {
  return DecodePng(png, source, width, height, true);
}

std::vector<unsigned char> ReadPngRgba(const std::string& path, int* width, int* height, const ErrorSource& source) {
  return DecodePngRgba(import::ReadDrawingBytes(path, "a PNG drawing", source), width, height, source);
}

std::vector<unsigned char> ReadPngAlpha(const std::string& path, int* width, int* height) {
  return ReadPngAlpha(path, width, height, ErrorSource(path));
}

}  // namespace posemorph::bake::mapping
