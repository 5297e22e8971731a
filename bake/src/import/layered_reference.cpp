// SPDX-License-Identifier: MIT
// Drawings named as layers of layered files (layered_reference.h).
#include "posemorph/bake/import/layered_reference.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>

#include "posemorph/bake/import/layered_image.h"
#include "posemorph/bake/input_file.h"

namespace posemorph::bake::import {
namespace {

bool EndsWithLayeredExtension(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s.size() > 4 && (s.compare(s.size() - 4, 4, ".ora") == 0 || s.compare(s.size() - 4, 4, ".psd") == 0);
}

// Layered files read in this process, by path, while their size and time stay.
struct CachedImage {
  std::uintmax_t size = 0;
  std::filesystem::file_time_type time;
  std::shared_ptr<const LayeredImage> image;
};
std::mutex cache_mutex;
std::map<std::string, CachedImage> cache;

std::shared_ptr<const LayeredImage> Read(const std::string& file) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  const std::filesystem::file_time_type time =
      ec ? std::filesystem::file_time_type{} : std::filesystem::last_write_time(file, ec);
  {
    const std::lock_guard<std::mutex> lock(cache_mutex);
    const auto it = cache.find(file);
    if (!ec && it != cache.end() && it->second.size == size && it->second.time == time) return it->second.image;
  }
  auto image = std::make_shared<const LayeredImage>(ReadLayeredImage(file));
  if (!ec) {
    const std::lock_guard<std::mutex> lock(cache_mutex);
    if (cache.size() >= 16) cache.erase(cache.begin());  // a few characters' files at most
    cache[file] = CachedImage{size, time, image};
  }
  return image;
}

}  // namespace

bool ParseLayeredReference(const std::string& reference, LayeredReference* out) {
  const std::size_t hash = reference.find('#');
  const std::string file = reference.substr(0, hash);
  if (!EndsWithLayeredExtension(file)) return false;
  if (out) {
    out->file = file;
    out->path.clear();
    if (hash != std::string::npos) {
      std::size_t at = hash + 1;
      while (at <= reference.size()) {
        const std::size_t slash = std::min(reference.find('/', at), reference.size());
        out->path.push_back(reference.substr(at, slash - at));
        at = slash + 1;
      }
    }
  }
  return true;
}

std::vector<unsigned char> LayeredReferencePng(const std::string& reference, const ErrorSource& source) {
  LayeredReference ref;
  if (!ParseLayeredReference(reference, &ref)) throw source.Error("not a layered file (.ora or .psd)");
  const std::shared_ptr<const LayeredImage> image = Read(ref.file);
  if (ref.path.empty())
    return EncodeRgbaPng(Composite(image->layers, image->width, image->height), image->width, image->height, ref.file);
  const std::vector<Layer>* level = &image->layers;
  const Layer* found = nullptr;
  std::string where = ref.file;
  for (const std::string& name : ref.path) {
    found = nullptr;
    for (const Layer& l : *level)  // its exact name first, then without a copy number
      if (l.name == name) {
        found = &l;
        break;
      }
    for (const Layer& l : *level)
      if (!found && WithoutCopyNumber(l.name) == name) found = &l;
    if (!found) {
      std::string names;
      for (const Layer& l : *level) names += (names.empty() ? "'" : ", '") + l.name + "'";
      throw source.Error("no layer or group '" + name + "' in " + where +
                         (names.empty() ? " (it holds none)" : " (it holds " + names + ")"));
    }
    where = "'" + name + "'";
    level = &found->children;
  }
  return EncodeRgbaPng(Composite(*found, image->width, image->height), image->width, image->height, ref.file);
}

std::vector<unsigned char> ReadDrawingBytes(const std::string& path, const std::string& what,
                                            const ErrorSource& source) {
  if (ParseLayeredReference(path)) return LayeredReferencePng(path, source);
  return ReadInputFile(path, kMaxTextFileBytes, what, source);
}

}  // namespace posemorph::bake::import
