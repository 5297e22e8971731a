// SPDX-License-Identifier: MIT
// The decoded-drawing memo of the mapping (drawing_memo.h).
#include "drawing_memo.h"

#include <mutex>
#include <vector>

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
    const std::lock_guard<std::mutex> lock(mutex_);
    if (png.size() > kBytes) return value;
    while (!entries_.empty() && (entries_.size() >= kEntries || bytes_ + png.size() > kBytes)) {
      bytes_ -= entries_.front().png.size();
      entries_.erase(entries_.begin());
    }
    bytes_ += png.size();
    entries_.push_back({settings, std::move(png), value});
    return value;
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

}  // namespace

mapping::ImageOutline TraceOutline(const std::string& path, const MappingParameters& prm, int halvings,
                                   const ErrorSource& source) {
  static DrawingMemo<TraceSettings, mapping::ImageOutline> memo;
  return memo.Get(path, {prm.alpha_threshold, prm.fill_notches, prm.drop_shadows, halvings}, source,
                  [&](const std::vector<unsigned char>& png) {
                    return mapping::OutlineFromPngBytes(png, prm.alpha_threshold, source, prm.fill_notches,
                                                        prm.drop_shadows, halvings);
                  });
}

mapping::AlignmentImage AlignmentImageOf(const std::string& path, int halvings, const ErrorSource& source) {
  static DrawingMemo<int, mapping::AlignmentImage> memo;
  return memo.Get(path, halvings, source, [&](const std::vector<unsigned char>& png) {
    int width = 0, height = 0;
    const std::vector<unsigned char> rgba = mapping::DecodePngRgba(png, &width, &height, source);
    return mapping::AlignmentImageFromRgba(rgba.data(), width, height, halvings);
  });
}

}  // namespace posemorph::bake
