// SPDX-License-Identifier: MIT
// OpenRaster (.ora) in: a zip (libzip) holding stack.xml (tinyxml2) and one
// PNG per layer (libpng, through the bake's bounded decoder). The format:
// https://www.openraster.org/ (stack.xml: <image w h><stack> of <stack>
// and <layer> elements, the first child on top; a layer's src, x, y,
// opacity, visibility and composite-op).
#include <zip.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include <tinyxml2.h>

#include "posemorph/bake/error.h"
#include "posemorph/bake/import/layered_image.h"
#include "posemorph/bake/input_file.h"
#include "posemorph/bake/mapping/outline_image.h"

namespace posemorph::bake::import {
namespace {

constexpr zip_int64_t kMaxEntries = 4096;
constexpr std::uint64_t kMaxInflatedBytes = std::uint64_t(512) << 20;  // all entries read, inflated

struct ZipCloser {
  void operator()(zip_t* z) const { zip_discard(z); }
};

class OpenRasterReader {
 public:
  OpenRasterReader(const std::vector<unsigned char>& bytes, std::string file) : file_(std::move(file)) {
    zip_error_t error;
    zip_error_init(&error);
    zip_source_t* source = zip_source_buffer_create(bytes.data(), bytes.size(), 0, &error);
    if (!source) Fail("cannot read the zip container: " + std::string(zip_error_strerror(&error)));
    zip_.reset(zip_open_from_source(source, ZIP_RDONLY, &error));
    if (!zip_) {
      zip_source_free(source);
      const std::string why = zip_error_strerror(&error);
      zip_error_fini(&error);
      Fail("not an OpenRaster file (its zip container cannot be read: " + why + ")");
    }
    zip_error_fini(&error);
    if (zip_get_num_entries(zip_.get(), 0) > kMaxEntries)
      Fail("more than " + std::to_string(kMaxEntries) + " files in the zip container");
  }

  LayeredImage Read() {
    LayeredImage image;
    image.file = file_;
    const std::vector<unsigned char> mimetype = Entry("mimetype", 64);
    if (std::string(mimetype.begin(), mimetype.end()) != "image/openraster")
      Fail("not an OpenRaster file (its mimetype entry is not image/openraster)");
    const std::vector<unsigned char> xml = Entry("stack.xml", std::size_t(16) << 20);
    tinyxml2::XMLDocument doc;
    if (doc.Parse(reinterpret_cast<const char*>(xml.data()), xml.size()) != tinyxml2::XML_SUCCESS)
      Fail("stack.xml: " + std::string(doc.ErrorStr() ? doc.ErrorStr() : "not XML"));
    const tinyxml2::XMLElement* root = doc.RootElement();
    if (!root || std::string(root->Name()) != "image") Fail("stack.xml: the root element is not <image>");
    image.width = root->IntAttribute("w", 0);
    image.height = root->IntAttribute("h", 0);
    if (image.width <= 0 || image.height <= 0 ||
        std::uint64_t(image.width) * std::uint64_t(image.height) > kMaxDrawingPixels)
      Fail("stack.xml: a canvas of " + std::to_string(image.width) + " x " + std::to_string(image.height) +
           " pixels (1 to " + std::to_string(kMaxDrawingPixels) + " pixels, 4096 x 4096, are read)");
    const tinyxml2::XMLElement* stack = root->FirstChildElement("stack");
    if (!stack) Fail("stack.xml: <image> holds no <stack>");
    image.layers = Children(*stack, 0, "");
    image.notes = std::move(notes_);
    return image;
  }

 private:
  [[noreturn]] void Fail(const std::string& problem) const { throw BakeError(file_, problem); }

  std::vector<unsigned char> Entry(const std::string& name, std::size_t limit) {
    zip_stat_t st;
    zip_stat_init(&st);
    if (zip_stat(zip_.get(), name.c_str(), 0, &st) != 0) Fail("the zip container holds no " + name);
    if (!(st.valid & ZIP_STAT_SIZE) || st.size > limit || inflated_ + st.size > kMaxInflatedBytes)
      Fail(name + " is larger than " + std::to_string(limit) + " bytes");
    std::unique_ptr<zip_file_t, int (*)(zip_file_t*)> f(zip_fopen(zip_.get(), name.c_str(), 0), zip_fclose);
    if (!f) Fail("cannot open " + name + " in the zip container: " + zip_strerror(zip_.get()));
    std::vector<unsigned char> out(std::size_t(st.size) + 1);
    const zip_int64_t n = zip_fread(f.get(), out.data(), out.size());
    if (n < 0 || std::uint64_t(n) != st.size)
      Fail("cannot read " + name + " in the zip container (it is damaged, or not the size its entry says)");
    out.resize(std::size_t(n));
    inflated_ += out.size();
    if (inflated_ > kMaxInflatedBytes)
      Fail("the zip container inflates to more than " + std::to_string(kMaxInflatedBytes) + " bytes");
    return out;
  }

  std::string Where(const std::string& path) const { return path.empty() ? "" : "layer '" + path + "': "; }

  std::vector<Layer> Children(const tinyxml2::XMLElement& stack, int depth, const std::string& path) {
    if (depth > kMaxDepth) Fail(Where(path) + "groups nested deeper than " + std::to_string(kMaxDepth));
    std::vector<Layer> out;
    for (const tinyxml2::XMLElement* e = stack.FirstChildElement(); e; e = e->NextSiblingElement()) {
      const std::string kind = e->Name();
      const char* name_attr = e->Attribute("name");
      Layer layer;
      layer.name = name_attr ? name_attr : "";
      const std::string here = path.empty() ? layer.name : path + "/" + layer.name;
      if (kind != "stack" && kind != "layer") {
        notes_.push_back(file_ + ": " + Where(here) + "a <" + kind + "> element is not a layer: left out");
        continue;
      }
      if (++count_ > kMaxLayers) Fail("more than " + std::to_string(kMaxLayers) + " layers and groups");
      const char* visibility = e->Attribute("visibility");
      layer.visible = !visibility || std::string(visibility) != "hidden";
      layer.opacity = e->DoubleAttribute("opacity", 1.0);
      if (!(layer.opacity >= 0 && layer.opacity <= 1))
        Fail(Where(here) + "opacity " + std::string(e->Attribute("opacity")) + " is not between 0 and 1");
      const char* op = e->Attribute("composite-op");
      if (op && std::string(op) != "svg:src-over")
        notes_.push_back(file_ + ": " + Where(here) + "composite-op " + op +
                         " is not supported: composited as normal (svg:src-over)");
      const int x = e->IntAttribute("x", 0), y = e->IntAttribute("y", 0);
      if (std::abs(x) > 1 << 20 || std::abs(y) > 1 << 20) Fail(Where(here) + "an offset beyond 1048576 pixels");
      if (kind == "stack") {
        layer.group = true;
        if (x != 0 || y != 0)
          notes_.push_back(file_ + ": " + Where(here) + "a group's offset is not part of OpenRaster 0.0.x: ignored");
        layer.children = Children(*e, depth + 1, here);
      } else {
        if (!layer.visible) {  // not decoded: a hidden layer is never drawn
          out.push_back(std::move(layer));
          continue;
        }
        const char* src = e->Attribute("src");
        if (!src) Fail(Where(here) + "a <layer> without src");
        const std::string s = src;
        if (s.size() < 4 || (s.compare(s.size() - 4, 4, ".png") != 0 && s.compare(s.size() - 4, 4, ".PNG") != 0))
          Fail(Where(here) + "src " + s + " is not a PNG (OpenRaster layers are PNG)");
        const std::vector<unsigned char> png = Entry(s, kMaxLayeredFileBytes);
        layer.rgba = mapping::DecodePngRgba(png, &layer.width, &layer.height, ErrorSource(file_, Where(here) + s));
        pixels_ += std::uint64_t(layer.width) * std::uint64_t(layer.height);
        if (pixels_ > kMaxLayerPixels)
          Fail(Where(here) + "the layers hold more than " + std::to_string(kMaxLayerPixels) + " pixels in all");
        layer.x = x, layer.y = y;
      }
      out.push_back(std::move(layer));
    }
    return out;
  }

  std::string file_;
  std::unique_ptr<zip_t, ZipCloser> zip_;
  std::size_t count_ = 0;
  std::uint64_t pixels_ = 0, inflated_ = 0;
  std::vector<std::string> notes_;
};

}  // namespace

LayeredImage ReadOpenRasterBytes(const std::vector<unsigned char>& bytes, const std::string& file) {
  return OpenRasterReader(bytes, file).Read();
}

LayeredImage ReadOpenRaster(const std::string& path) {
  return ReadOpenRasterBytes(ReadInputFile(path, kMaxLayeredFileBytes, "an OpenRaster drawing"), path);
}

}  // namespace posemorph::bake::import
