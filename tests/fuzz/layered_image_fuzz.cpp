// SPDX-License-Identifier: MIT
// libFuzzer harness: the layered-file readers (bake/src/import/). Input
// beginning with "8BPS" is read as a Photoshop file, anything else as an
// OpenRaster zip. Refusals are BakeErrors; a file that is read has a canvas
// within the limit, layers whose pixels match their boxes, opacities in
// 0..1 and groups no deeper than the limit, and composites onto its canvas.
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "posemorph/bake/error.h"
#include "posemorph/bake/import/layered_image.h"
#include "posemorph/bake/input_file.h"

namespace {

void Check(const std::vector<posemorph::bake::import::Layer>& layers, int depth) {
  using namespace posemorph::bake::import;
  if (depth > kMaxDepth + 1) std::abort();
  for (const Layer& l : layers) {
    if (!(l.opacity >= 0 && l.opacity <= 1)) std::abort();
    if (l.group) {
      Check(l.children, depth + 1);
    } else if (l.visible && l.rgba.size() != std::size_t(l.width) * std::size_t(l.height) * 4) {
      std::abort();
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace posemorph::bake;
  const std::vector<unsigned char> bytes(data, data + size);
  try {
    const bool psd = size >= 4 && std::memcmp(data, "8BPS", 4) == 0;
    const import::LayeredImage image =
        psd ? import::ReadPhotoshopBytes(bytes, "fuzz.psd") : import::ReadOpenRasterBytes(bytes, "fuzz.ora");
    if (image.width < 1 || image.height < 1 ||
        std::uint64_t(image.width) * std::uint64_t(image.height) > kMaxDrawingPixels)
      std::abort();
    Check(image.layers, 0);
    const std::vector<unsigned char> rgba = import::Composite(image.layers, image.width, image.height);
    if (rgba.size() != std::size_t(image.width) * std::size_t(image.height) * 4) std::abort();
  } catch (const BakeError&) {
  }
  return 0;
}
