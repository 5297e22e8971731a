// SPDX-License-Identifier: MIT
#include "png_io.h"

#include <png.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>

namespace posemorph::viewer {

FrameDifference CompareFrames(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b,
                              std::vector<unsigned char>* diff) {
  FrameDifference r;
  r.pixels = std::min(a.size(), b.size()) / 4;
  if (diff) diff->assign(4 * r.pixels, 255);
  for (std::size_t p = 0; p < 4 * r.pixels; p += 4) {
    int d = 0;
    for (int c = 0; c < 4; ++c) d = std::max(d, std::abs(int(a[p + c]) - int(b[p + c])));
    r.worst = std::max(r.worst, d);
    if (d > 3) ++r.differing;
    if (diff) {
      const unsigned char v = (unsigned char)std::min(255, d * 8);
      (*diff)[p + 1] = (unsigned char)(255 - v), (*diff)[p + 2] = (unsigned char)(255 - v);
    }
  }
  return r;
}

bool ReadPng(const std::string& path, std::vector<unsigned char>* rgba, std::uint32_t* width, std::uint32_t* height,
             std::string* error) {
  // A regular file (a pipe would block, a device never end), its size
  // checked from the header before anything is decoded.
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) {
    *error = path + ": cannot open file";
    return false;
  }
  if (!S_ISREG(st.st_mode)) {
    *error = path + ": is not a regular file (a directory, device or pipe)";
    return false;
  }
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str())) {
    *error = path + ": cannot read PNG: " + image.message;
    return false;
  }
  if (std::uint64_t(image.width) * image.height > kMaxDrawingPixels) {
    *error = path + ": PNG of " + std::to_string(image.width) + " x " + std::to_string(image.height) +
             " pixels is above the limit of " + std::to_string(kMaxDrawingPixels) + " pixels";
    png_image_free(&image);
    return false;
  }
  image.format = PNG_FORMAT_RGBA;
  rgba->assign(PNG_IMAGE_SIZE(image), 0);
  if (!png_image_finish_read(&image, nullptr, rgba->data(), 0, nullptr)) {
    *error = path + ": cannot decode PNG: " + image.message;
    png_image_free(&image);
    return false;
  }
  *width = image.width;
  *height = image.height;
  return true;
}

bool WritePng(const std::string& path, const unsigned char* rgba, std::uint32_t width, std::uint32_t height,
              std::string* error) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  image.width = width;
  image.height = height;
  image.format = PNG_FORMAT_RGBA;
  if (!png_image_write_to_file(&image, path.c_str(), 0, rgba, 0, nullptr)) {
    *error = path + ": cannot write PNG: " + image.message;
    return false;
  }
  return true;
}

}  // namespace posemorph::viewer
