// SPDX-License-Identifier: MIT
// The decoded-drawing memo of the mapping (drawing_memo.h).
#include "drawing_memo.h"

#include <algorithm>
#include <cstdint>
#include <mutex>
#include <vector>

#include "posemorph/bake/ghosting.h"
#include "posemorph/bake/import/layered_reference.h"
#include "posemorph/bake/input_file.h"

namespace posemorph::bake {
namespace {

// Values by the drawing's exact bytes and their settings (drawing_memo.h).
template <class Settings, class Value>
class DrawingMemo {
 public:
  template <class Make>
  Value Get(const std::string& path, const Settings& settings, const ErrorSource& source, const Make& make) {
    std::vector<unsigned char> png = import::ReadDrawingBytes(path, "a PNG drawing", source);
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      for (const Entry& e : entries_)
        if (e.settings == settings && e.png == png) return e.value;
    }
    Value value = make(png);
    Put(std::move(png), settings, value);
    return value;
  }

  // Keeps `value` for the drawing whose bytes are `png` (made from them
  // while decoding them for another memo), unless it is kept already.
  void Put(std::vector<unsigned char> png, const Settings& settings, const Value& value) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (png.size() > kBytes) return;
    for (const Entry& e : entries_)
      if (e.settings == settings && e.png == png) return;
    while (!entries_.empty() && (entries_.size() >= kEntries || bytes_ + png.size() > kBytes)) {
      bytes_ -= entries_.front().png.size();
      entries_.erase(entries_.begin());
    }
    bytes_ += png.size();
    entries_.push_back({settings, std::move(png), value});
  }

 private:
  static constexpr std::size_t kEntries = 64, kBytes = std::size_t(64) << 20;
  struct Entry {
    Settings settings;
    std::vector<unsigned char> png;
    Value value;
  };
  std::mutex mutex_;
  std::vector<Entry> entries_;
  std::size_t bytes_ = 0;
};

struct TraceSettings {
  double threshold;
  bool fill_notches, drop_shadows;
  int halvings;
  bool operator==(const TraceSettings& o) const {
    return threshold == o.threshold && fill_notches == o.fill_notches && drop_shadows == o.drop_shadows &&
           halvings == o.halvings;
  }
};

// The drawing halved to at most 512 px for the ghosting measure (ghosting.h).
struct GhostingCopy {
  std::vector<unsigned char> rgba;
  std::uint32_t width = 0, height = 0;
};

GhostingCopy MakeGhostingCopy(std::vector<unsigned char> rgba, int width, int height) {
  GhostingCopy g;
  g.width = std::uint32_t(width), g.height = std::uint32_t(height);
  g.rgba = ReduceDrawing(std::move(rgba), &g.width, &g.height);
  return g;
}

// One memo of each kind for the whole process.
DrawingMemo<TraceSettings, mapping::ImageOutline>& TraceMemo() {
  static DrawingMemo<TraceSettings, mapping::ImageOutline> memo;
  return memo;
}
DrawingMemo<int, mapping::AlignmentImage>& AlignmentMemo() {
  static DrawingMemo<int, mapping::AlignmentImage> memo;
  return memo;
}
DrawingMemo<int, GhostingCopy>& GhostingMemo() {
  static DrawingMemo<int, GhostingCopy> memo;
  return memo;
}

}  // namespace

// A drawing is decoded once for all three: the tracing's decode also makes
// the alignment image (at the level the alignment takes when every drawing
// is this one's size) and the ghosting copy. Pip drawn at 2048 px was
// decoded three times in the bake (and once more by the atlas), 40% of
// the bake's time in libpng and zlib.
mapping::ImageOutline TraceOutline(const std::string& path, const MappingParameters& prm, int halvings,
                                   const ErrorSource& source) {
  return TraceMemo().Get(
      path, {prm.alpha_threshold, prm.fill_notches, prm.drop_shadows, halvings}, source,
      [&](const std::vector<unsigned char>& png) {
        int width = 0, height = 0;
        std::vector<unsigned char> rgba = mapping::DecodePngRgba(png, &width, &height, source);
        mapping::ImageOutline outline = mapping::OutlineFromRgba(rgba, width, height, prm.alpha_threshold, source,
                                                                 prm.fill_notches, prm.drop_shadows, halvings);
        const int align = std::max(halvings, mapping::AlignmentHalvings(width, height));
        AlignmentMemo().Put(png, align, mapping::AlignmentImageFromRgba(rgba.data(), width, height, align));
        GhostingMemo().Put(png, 0, MakeGhostingCopy(std::move(rgba), width, height));
        return outline;
      });
}

mapping::AlignmentImage AlignmentImageOf(const std::string& path, int halvings, const ErrorSource& source) {
  return AlignmentMemo().Get(path, halvings, source, [&](const std::vector<unsigned char>& png) {
    int width = 0, height = 0;
    const std::vector<unsigned char> rgba = mapping::DecodePngRgba(png, &width, &height, source);
    return mapping::AlignmentImageFromRgba(rgba.data(), width, height, halvings);
  });
}

std::vector<unsigned char> GhostingDrawingOf(const std::string& path, const ErrorSource& source, std::uint32_t* width,
                                             std::uint32_t* height) {
  GhostingCopy g = GhostingMemo().Get(path, 0, source, [&](const std::vector<unsigned char>& png) {
    int w = 0, h = 0;
    return MakeGhostingCopy(mapping::DecodePngRgba(png, &w, &h, source), w, h);
  });
  *width = g.width, *height = g.height;
  return std::move(g.rgba);
}

}  // namespace posemorph::bake
