// SPDX-License-Identifier: MIT
// The working level of a drawing (see working_level.h).
#include "posemorph/bake/import/layered_reference.h"
#include "posemorph/bake/mapping/working_level.h"

#include <png.h>

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "posemorph/bake/input_file.h"

namespace posemorph::bake::mapping {

std::vector<unsigned char> AlphaAtLevel(const std::vector<unsigned char>& alpha, int width, int height, int halvings,
                                        int* level_width, int* level_height) {
  if (halvings < 0 || halvings > 12 || width <= 0 || height <= 0 ||
      alpha.size() != std::size_t(width) * std::size_t(height))
    throw BakeError("", "internal: AlphaAtLevel on a bad image or level");
  const int w = int((std::int64_t(width) + (std::int64_t(1) << halvings) - 1) >> halvings);
  const int h = int((std::int64_t(height) + (std::int64_t(1) << halvings) - 1) >> halvings);
  *level_width = w;
  *level_height = h;
  if (halvings == 0) return alpha;
  // Sums of up to 2^24 bytes of 255 fit 32 bits.
  std::vector<std::uint32_t> sums(std::size_t(w) * std::size_t(h), 0);
  for (int y = 0; y < height; ++y) {
    std::uint32_t* row = &sums[std::size_t(y >> halvings) * std::size_t(w)];
    const unsigned char* a = &alpha[std::size_t(y) * std::size_t(width)];
    for (int x = 0; x < width; ++x) row[x >> halvings] += a[x];
  }
  const std::uint64_t n = std::uint64_t(1) << (2 * halvings);
  std::vector<unsigned char> level(sums.size());
  for (std::size_t i = 0; i < sums.size(); ++i) level[i] = (unsigned char)((sums[i] + n / 2) / n);
  return level;
}

int WorkingHalvings(int width, int height, int working_size) {
  if (working_size <= 0) return 0;
  const std::int64_t side = std::max(width, height);
  int h = 0;
  while (h < 12 && ((side + (std::int64_t(1) << h) - 1) >> h) > working_size) ++h;
  return h;
}

void ReadPngSize(const std::string& path, int* width, int* height, const ErrorSource& source) {
  const std::vector<unsigned char> file = import::ReadDrawingBytes(path, "a PNG drawing", source);
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, file.data(), file.size()))
    throw source.Error(std::string("cannot read PNG: ") + image.message);
  *width = int(std::min<png_uint_32>(image.width, 1u << 30));
  *height = int(std::min<png_uint_32>(image.height, 1u << 30));
  png_image_free(&image);
}

}  // namespace posemorph::bake::mapping
