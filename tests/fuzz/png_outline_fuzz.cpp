// SPDX-License-Identifier: MIT
// libFuzzer harness: the PNG outline tracer. The first byte picks the input:
// even, the rest is a PNG file (decoded by libpng within the pixel limit,
// then traced); odd, the next two bytes give a width and height of 1..64 and
// the rest is the alpha channel (the tracer's own logic without libpng's
// CRC checks in the way), with its thin notches filled when the width
// byte's top bit is set, and the same bytes searched for a drop shadow as
// RGBA. Refusals are BakeErrors; a traced outline is a closed loop of
// finite points inside the image.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "posemorph/bake/error.h"
#include "posemorph/bake/mapping/nway_mapping.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace posemorph::bake;
  if (size < 1) return 0;
  try {
    mapping::ImageOutline o;
    if (data[0] % 2 == 0) {
      o = mapping::OutlineFromPngBytes(std::vector<unsigned char>(data + 1, data + size), 0.5, "fuzz.png");
    } else {
      if (size < 3) return 0;
      const int w = data[1] % 64 + 1, h = data[2] % 64 + 1;
      // The bytes as RGBA too: the drop-shadow search, whose marked pixels
      // are then left out, and the notch filling on every other input.
      std::vector<unsigned char> rgba(std::size_t(w) * h * 4, 0), shadow;
      for (std::size_t i = 0; i < rgba.size() && 3 + i < size; ++i) rgba[i] = data[3 + i];
      mapping::ImageOutline found;
      const std::size_t marked = mapping::FindDropShadow(rgba.data(), w, h, 0.05, shadow, found);
      std::size_t count = 0;
      for (unsigned char m : shadow) count += m != 0;
      if (count != marked || (marked > 0 && (found.shadow_x0 > found.shadow_x1 || found.shadow_x1 >= w ||
                                             found.shadow_y0 > found.shadow_y1 || found.shadow_y1 >= h)))
        std::abort();
      std::vector<unsigned char> alpha(std::size_t(w) * h, 0);
      for (std::size_t i = 0; i < alpha.size() && 3 + i < size; ++i) alpha[i] = data[3 + i];
      o = mapping::OutlineFromAlpha(alpha, w, h, 0.5, "fuzz-alpha", (data[1] & 0x80) != 0);
    }
    for (const mapping::Point& p : o.outline)
      if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || p.x() < -1 || p.y() < -1 || p.x() > o.width + 1 ||
          p.y() > o.height + 1)
        std::abort();
  } catch (const BakeError&) {
  }
  return 0;
}
