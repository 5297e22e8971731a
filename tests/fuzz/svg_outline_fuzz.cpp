// SPDX-License-Identifier: MIT
// libFuzzer harness: the SVG outline reader (XML, the outline element, path
// data, curve flattening). Refusals are BakeErrors; an outline it returns
// has finite points within its limit.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "posemorph/bake/error.h"
#include "posemorph/bake/mapping/nway_mapping.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace posemorph::bake;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const mapping::SvgOutline o = mapping::OutlineFromSvgText(text, 0.25, "fuzz.svg");
    if (o.outline.size() > mapping::kMaxOutlinePoints + 1) std::abort();
    for (const mapping::Point& p : o.outline)
      if (!std::isfinite(p.x()) || !std::isfinite(p.y())) std::abort();
  } catch (const BakeError&) {
  }
  return 0;
}
