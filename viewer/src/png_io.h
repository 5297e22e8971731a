// SPDX-License-Identifier: MIT
// PNG files for the viewer and its tests: reading drawings (bounded), writing
// frames, and comparing two frames with a tolerance.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace posemorph::viewer {

// Each drawing the viewer loads is at most this many pixels (rig files are
// hostile input), and so the texture array they share.
constexpr std::uint64_t kMaxDrawingPixels = std::uint64_t(1) << 24;  // 4096 x 4096

bool WritePng(const std::string& path, const unsigned char* rgba, std::uint32_t width, std::uint32_t height,
              std::string* error);
// The tolerant comparison of two RGBA8 frames of the same size: a pixel
// differs when a channel is off by more than 3 of 255. `diff`, if given,
// becomes an image of the differences (white = equal, red = off by 32+).
struct FrameDifference {
  std::size_t differing = 0, pixels = 0;
  int worst = 0;
  double share() const { return pixels ? double(differing) / double(pixels) : 0.0; }
};
FrameDifference CompareFrames(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b,
                              std::vector<unsigned char>* diff = nullptr);

bool ReadPng(const std::string& path, std::vector<unsigned char>* rgba, std::uint32_t* width, std::uint32_t* height,
             std::string* error);

}  // namespace posemorph::viewer
