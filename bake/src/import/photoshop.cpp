// SPDX-License-Identifier: MIT
// Photoshop (.psd) in, written here from Adobe's "Photoshop File Formats
// Specification": the header, the colour mode data and image resources
// (skipped), and the layer and mask information: layer records (box,
// channels, blend mode, opacity, flags, name, tagged blocks 'luni' for the
// Unicode name and 'lsct'/'lsdk' for groups), then each layer's channels,
// raw or PackBits (RLE). Every length, count and offset is checked against
// what is left of the file before it is used.
#include <algorithm>
#include <array>
#include <cstring>
#include <string>

#include "posemorph/bake/error.h"
#include "posemorph/bake/import/layered_image.h"
#include "posemorph/bake/input_file.h"

namespace posemorph::bake::import {
namespace {

constexpr int kMaxOffset = 1 << 20;  // a layer's box, in pixels from the canvas's corner

// A bounded view of the file's bytes.
class Bytes {
 public:
  Bytes(const unsigned char* data, std::size_t size, std::size_t base, const std::string* file)
      : data_(data), size_(size), base_(base), file_(file) {}
  std::size_t Left() const { return size_ - at_; }
  std::size_t Offset() const { return base_ + at_; }
  [[noreturn]] void Truncated(const std::string& what) const {
    throw BakeError(*file_,
                    "damaged or truncated: " + what + " runs past its end (at byte " + std::to_string(Offset()) + ")");
  }
  const unsigned char* Take(std::size_t n, const char* what) {
    if (n > Left()) Truncated(what);
    const unsigned char* p = data_ + at_;
    at_ += n;
    return p;
  }
  std::uint8_t U8(const char* what) { return *Take(1, what); }
  std::uint16_t U16(const char* what) {
    const unsigned char* p = Take(2, what);
    return std::uint16_t((p[0] << 8) | p[1]);
  }
  std::int16_t I16(const char* what) { return std::int16_t(U16(what)); }
  std::uint32_t U32(const char* what) {
    const unsigned char* p = Take(4, what);
    return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) | p[3];
  }
  std::int32_t I32(const char* what) { return std::int32_t(U32(what)); }
  std::string Tag(const char* what) {
    const unsigned char* p = Take(4, what);
    return std::string(reinterpret_cast<const char*>(p), 4);
  }
  // The next `n` bytes as a view of their own.
  Bytes Sub(std::size_t n, const char* what) {
    const std::size_t offset = Offset();
    const unsigned char* p = Take(n, what);
    return Bytes(p, n, offset, file_);
  }
  // A section: its 4-byte length, then that many bytes.
  Bytes Section(const char* what) { return Sub(U32(what), what); }

 private:
  const unsigned char* data_;
  std::size_t size_, at_ = 0, base_;
  const std::string* file_;
};

std::string Utf8(std::uint32_t c) {
  std::string s;
  if (c < 0x80) {
    s += char(c);
  } else if (c < 0x800) {
    s += char(0xC0 | (c >> 6)), s += char(0x80 | (c & 0x3F));
  } else if (c < 0x10000) {
    s += char(0xE0 | (c >> 12)), s += char(0x80 | ((c >> 6) & 0x3F)), s += char(0x80 | (c & 0x3F));
  } else {
    s += char(0xF0 | (c >> 18)), s += char(0x80 | ((c >> 12) & 0x3F)), s += char(0x80 | ((c >> 6) & 0x3F));
    s += char(0x80 | (c & 0x3F));
  }
  return s;
}

// 'luni': a 4-byte count of UTF-16BE code units, then the units.
std::string UnicodeName(Bytes b) {
  const std::uint32_t n = b.U32("a Unicode layer name");
  if (n > b.Left() / 2) b.Truncated("a Unicode layer name");
  std::string out;
  for (std::uint32_t i = 0; i < n; ++i) {
    std::uint32_t c = b.U16("a Unicode layer name");
    if (c >= 0xD800 && c < 0xDC00 && i + 1 < n) {
      const std::uint32_t low = b.U16("a Unicode layer name");
      ++i;
      c = (low >= 0xDC00 && low < 0xE000) ? 0x10000 + ((c - 0xD800) << 10) + (low - 0xDC00) : 0xFFFD;
    } else if (c >= 0xD800 && c < 0xE000) {
      c = 0xFFFD;
    }
    if (c == 0) break;
    out += Utf8(c);
  }
  return out;
}

// Latin-1 bytes (a Pascal name's) as UTF-8.
std::string Latin1(const unsigned char* p, std::size_t n) {
  std::string out;
  for (std::size_t i = 0; i < n; ++i) out += Utf8(p[i]);
  return out;
}

bool IsAdjustment(const std::string& key) {
  static const std::array<const char*, 22> keys{"SoCo", "GdFl", "PtFl", "brit", "levl", "curv", "expA", "vibA",
                                                "hue ", "hue2", "blnc", "blwh", "phfl", "mixr", "clrL", "nvrt",
                                                "post", "thrs", "grdm", "selc", "CgEd", "vmsk"};
  for (const char* k : keys)
    if (key == k) return true;
  return false;
}

std::string BlendName(const std::string& key) {
  static const std::array<std::array<const char*, 2>, 27> names{{{"norm", "normal"},
                                                                 {"pass", "pass through"},
                                                                 {"diss", "dissolve"},
                                                                 {"dark", "darken"},
                                                                 {"mul ", "multiply"},
                                                                 {"idiv", "colour burn"},
                                                                 {"lbrn", "linear burn"},
                                                                 {"dkCl", "darker colour"},
                                                                 {"lite", "lighten"},
                                                                 {"scrn", "screen"},
                                                                 {"div ", "colour dodge"},
                                                                 {"lddg", "linear dodge"},
                                                                 {"lgCl", "lighter colour"},
                                                                 {"over", "overlay"},
                                                                 {"sLit", "soft light"},
                                                                 {"hLit", "hard light"},
                                                                 {"vLit", "vivid light"},
                                                                 {"lLit", "linear light"},
                                                                 {"pLit", "pin light"},
                                                                 {"hMix", "hard mix"},
                                                                 {"diff", "difference"},
                                                                 {"smud", "exclusion"},
                                                                 {"fsub", "subtract"},
                                                                 {"fdiv", "divide"},
                                                                 {"hue ", "hue"},
                                                                 {"sat ", "saturation"},
                                                                 {"colr", "colour"}}};
  for (const auto& n : names)
    if (key == n[0]) return n[1];
  return "'" + key + "'";
}

struct ChannelInfo {
  std::int16_t id;
  std::uint32_t length;
};

struct Record {
  std::string name;
  std::int32_t top = 0, left = 0, bottom = 0, right = 0;
  std::vector<ChannelInfo> channels;
  std::string blend;
  std::uint8_t opacity = 255, clipping = 0, flags = 0;
  bool has_mask = false, adjustment = false;
  std::uint32_t section = 0;  // 'lsct': 1 or 2 a group (its top), 3 a group's bottom divider
  std::string adjustment_key;
};

class PhotoshopReader {
 public:
  PhotoshopReader(const std::vector<unsigned char>& bytes, std::string file) : file_(std::move(file)), bytes_(bytes) {}

  LayeredImage Read() {
    Bytes b(bytes_.data(), bytes_.size(), 0, &file_);
    if (bytes_.size() < 4 || std::memcmp(bytes_.data(), "8BPS", 4) != 0)
      Fail("not a Photoshop file (it does not begin with 8BPS)");
    b.Take(4, "the header");
    const std::uint16_t version = b.U16("the header");
    if (version == 2) Fail("a large document (PSB) is not read: save it as PSD");
    if (version != 1) Fail("Photoshop file version " + std::to_string(version) + " is not read (version 1 is)");
    b.Take(6, "the header");
    channels_ = b.U16("the header");
    const std::uint32_t height = b.U32("the header"), width = b.U32("the header");
    const std::uint16_t depth = b.U16("the header"), mode = b.U16("the header");
    if (channels_ < 1 || channels_ > 56) Fail("the header gives " + std::to_string(channels_) + " channels (1 to 56)");
    if (depth != 8)
      Fail(std::to_string(depth) + "-bit channels are not supported: save the file with 8 bits per channel");
    if (mode != 3 && mode != 1) {
      static const char* names[] = {"bitmap", "greyscale", "indexed",      "RGB",     "CMYK",
                                    "",       "",          "multichannel", "duotone", "Lab"};
      const std::string name = mode < 10 && names[mode][0] ? names[mode] : "number " + std::to_string(mode);
      Fail("colour mode " + name + " is not supported: convert the image to RGB (or greyscale)");
    }
    grey_ = mode == 1;
    if (width < 1 || height < 1 || std::uint64_t(width) * height > kMaxDrawingPixels)
      Fail("a canvas of " + std::to_string(width) + " x " + std::to_string(height) + " pixels (1 to " +
           std::to_string(kMaxDrawingPixels) + " pixels, 4096 x 4096, are read)");
    LayeredImage image;
    image.file = file_;
    image.width = int(width), image.height = int(height);
    b.Section("the colour mode data");
    b.Section("the image resources");
    Bytes layers_and_masks = b.Section("the layer and mask information");
    if (layers_and_masks.Left() == 0)
      Fail("holds no layers (a flat image): save it with its layers, or export a PNG for each pose");
    Bytes layer_info = layers_and_masks.Section("the layer information");
    if (layer_info.Left() == 0)
      Fail("holds no layers (a flat image): save it with its layers, or export a PNG for each pose");
    image.layers = ReadLayers(layer_info);
    image.notes = std::move(notes_);
    return image;
  }

 private:
  [[noreturn]] void Fail(const std::string& problem) const { throw BakeError(file_, problem); }
  [[noreturn]] void FailLayer(const Record& r, const std::string& problem) const {
    Fail("layer '" + r.name + "': " + problem);
  }
  void Note(const Record& r, const std::string& what) { notes_.push_back(file_ + ": layer '" + r.name + "': " + what); }

  Record ReadRecord(Bytes& b) {
    Record r;
    r.top = b.I32("a layer record"), r.left = b.I32("a layer record");
    r.bottom = b.I32("a layer record"), r.right = b.I32("a layer record");
    const std::uint16_t n = b.U16("a layer record");
    if (n > 56) Fail("a layer record gives " + std::to_string(n) + " channels (at most 56)");
    for (std::uint16_t c = 0; c < n; ++c) {
      ChannelInfo info;
      info.id = b.I16("a layer record");
      info.length = b.U32("a layer record");
      r.channels.push_back(info);
    }
    if (b.Tag("a layer record") != "8BIM")
      Fail("a layer record's blend mode does not begin with 8BIM (at byte " + std::to_string(b.Offset() - 4) + ")");
    r.blend = b.Tag("a layer record");
    r.opacity = b.U8("a layer record");
    r.clipping = b.U8("a layer record");
    r.flags = b.U8("a layer record");
    b.U8("a layer record");
    Bytes extra = b.Section("a layer record's extra data");
    Bytes mask = extra.Section("a layer's mask data");
    r.has_mask = mask.Left() > 0;
    extra.Section("a layer's blending ranges");
    const std::uint8_t name_length = extra.U8("a layer's name");
    const unsigned char* name = extra.Take(name_length, "a layer's name");
    r.name = Latin1(name, name_length);
    const std::size_t padding = (4 - (1 + name_length) % 4) % 4;
    extra.Take(std::min(padding, extra.Left()), "a layer's name");
    // Tagged blocks until the extra data ends (a block that does not begin
    // with a signature ends the reading: what follows is not understood).
    while (extra.Left() >= 12) {
      const std::string signature = extra.Tag("a tagged block");
      if (signature != "8BIM" && signature != "8B64") break;
      const std::string key = extra.Tag("a tagged block");
      Bytes data = extra.Section("a tagged block");
      if (key == "luni") {
        const std::string unicode = UnicodeName(data);
        if (!unicode.empty()) r.name = unicode;
      } else if (key == "lsct" || key == "lsdk") {
        r.section = data.U32("a group's section divider");
      } else if (IsAdjustment(key)) {
        r.adjustment = true;
        r.adjustment_key = key;
      }
    }
    return r;
  }

  // One channel of a layer into `plane` (w x h bytes), raw or PackBits.
  void ReadChannel(Bytes data, const Record& r, int w, int h, std::vector<unsigned char>& plane) {
    const std::uint16_t compression = data.U16("a layer's channel");
    const std::size_t n = std::size_t(w) * std::size_t(h);
    if (compression == 0) {
      const unsigned char* p = data.Take(n, "a layer's channel");
      plane.assign(p, p + n);
    } else if (compression == 1) {
      std::vector<std::uint16_t> counts(static_cast<std::size_t>(h));
      for (int y = 0; y < h; ++y) counts[std::size_t(y)] = data.U16("a layer's RLE row lengths");
      plane.assign(n, 0);
      for (int y = 0; y < h; ++y) {
        Bytes row = data.Sub(counts[std::size_t(y)], "a layer's RLE row");
        unsigned char* out = plane.data() + std::size_t(y) * std::size_t(w);
        int x = 0;
        while (row.Left() > 0) {
          const int c = std::int8_t(row.U8("a layer's RLE row"));
          if (c == -128) continue;
          if (c >= 0) {
            if (x + c + 1 > w) FailLayer(r, "an RLE row longer than the layer is wide (damaged)");
            const unsigned char* p = row.Take(std::size_t(c) + 1, "a layer's RLE row");
            std::copy(p, p + c + 1, out + x);
            x += c + 1;
          } else {
            if (x + 1 - c > w) FailLayer(r, "an RLE row longer than the layer is wide (damaged)");
            const unsigned char v = row.U8("a layer's RLE row");
            std::fill(out + x, out + x + 1 - c, v);
            x += 1 - c;
          }
        }
        if (x != w) FailLayer(r, "an RLE row shorter than the layer is wide (damaged)");
      }
    } else if (compression == 2 || compression == 3) {
      FailLayer(r, "ZIP-compressed channels are not supported: save with RLE compression (or none)");
    } else {
      FailLayer(r, "unknown channel compression " + std::to_string(compression));
    }
  }

  Layer ReadPixels(Bytes& b, const Record& r) {
    Layer layer;
    layer.name = r.name;
    layer.visible = (r.flags & 0x02) == 0;
    layer.opacity = r.opacity / 255.0;
    const long long w = (long long)r.right - r.left, h = (long long)r.bottom - r.top;
    if (w < 0 || h < 0 || std::abs((long long)r.left) > kMaxOffset || std::abs((long long)r.top) > kMaxOffset ||
        std::abs((long long)r.right) > kMaxOffset || std::abs((long long)r.bottom) > kMaxOffset)
      FailLayer(r, "a box from (" + std::to_string(r.left) + ", " + std::to_string(r.top) + ") to (" +
                       std::to_string(r.right) + ", " + std::to_string(r.bottom) + ") (damaged)");
    if (std::uint64_t(w) * std::uint64_t(h) > kMaxDrawingPixels)
      FailLayer(r, "a box of " + std::to_string(w) + " x " + std::to_string(h) + " pixels (at most " +
                       std::to_string(kMaxDrawingPixels) + ")");
    pixels_ += std::uint64_t(w) * std::uint64_t(h);
    if (pixels_ > kMaxLayerPixels)
      FailLayer(r, "the layers hold more than " + std::to_string(kMaxLayerPixels) + " pixels in all");
    layer.x = r.left, layer.y = r.top, layer.width = int(w), layer.height = int(h);
    const std::size_t n = std::size_t(w) * std::size_t(h);
    std::array<std::vector<unsigned char>, 4> planes;
    std::array<bool, 4> have{false, false, false, false};
    std::vector<unsigned char> plane;
    for (const ChannelInfo& c : r.channels) {
      Bytes data = b.Sub(c.length, "a layer's channel data");
      const bool colour = c.id >= 0 && c.id < (grey_ ? 1 : 3);
      if (c.id == -1 || colour) {
        if (data.Left() < 2) FailLayer(r, "a channel without its compression (damaged)");
        ReadChannel(data, r, int(w), int(h), plane);
        const int k = c.id == -1 ? 3 : c.id;
        planes[std::size_t(k)] = plane, have[std::size_t(k)] = true;
      } else if (c.id == -2 || c.id == -3) {
        // the mask's own data, noted with the record
      } else {
        Note(r, "channel " + std::to_string(c.id) + " (a spot colour or extra channel) ignored");
      }
    }
    if (grey_) {
      for (int k = 1; k < 3; ++k) planes[std::size_t(k)] = planes[0], have[std::size_t(k)] = have[0];
    }
    layer.rgba.assign(n * 4, 0);
    for (int k = 0; k < 4; ++k) {
      if (!have[std::size_t(k)]) {
        if (k == 3)
          for (std::size_t i = 0; i < n; ++i) layer.rgba[i * 4 + 3] = 255;
        continue;
      }
      const std::vector<unsigned char>& p = planes[std::size_t(k)];
      for (std::size_t i = 0; i < n; ++i) layer.rgba[i * 4 + std::size_t(k)] = p[i];
    }
    return layer;
  }

  std::vector<Layer> ReadLayers(Bytes& info) {
    const int count = std::abs(int(info.I16("the layer count")));
    if (std::size_t(count) > kMaxLayers)
      Fail(std::to_string(count) + " layers and groups (at most " + std::to_string(kMaxLayers) + ")");
    std::vector<Record> records;
    for (int i = 0; i < count; ++i) records.push_back(ReadRecord(info));
    // The records and the channels run bottom first; groups are bracketed
    // by a divider below their children and the group's record above them.
    std::vector<std::vector<Layer>> open(1);  // each open group's children, bottom first
    std::vector<std::size_t> opened_at;
    for (std::size_t i = 0; i < records.size(); ++i) {
      const Record& r = records[i];
      Layer layer = ReadPixels(info, r);
      if (r.section == 3) {
        if (open.size() > std::size_t(kMaxDepth)) Fail("groups nested deeper than " + std::to_string(kMaxDepth));
        open.emplace_back();
        opened_at.push_back(i);
        continue;
      }
      if (r.section == 1 || r.section == 2) {
        if (open.size() < 2) FailLayer(r, "a group's record without the divider below its layers (damaged)");
        layer.group = true;
        layer.children.assign(std::make_move_iterator(open.back().rbegin()),
                              std::make_move_iterator(open.back().rend()));
        layer.rgba.clear(), layer.width = layer.height = 0;
        open.pop_back();
        opened_at.pop_back();
        if (r.blend != "norm" && r.blend != "pass")
          Note(r, "blend mode " + BlendName(r.blend) + " is not supported: composited as normal");
      } else if (r.adjustment) {
        Note(r, "an adjustment or fill layer ('" + r.adjustment_key + "') is not supported: left out");
        continue;
      } else if (r.blend != "norm") {
        Note(r, "blend mode " + BlendName(r.blend) + " is not supported: composited as normal");
      }
      if (r.has_mask) Note(r, "its layer mask is not supported: drawn unmasked");
      if (r.clipping != 0) Note(r, "clipping to the layer below is not supported: drawn unclipped");
      open.back().push_back(std::move(layer));
    }
    if (open.size() != 1)
      FailLayer(records[opened_at.back()], "a group's divider without the group's record above it (damaged)");
    return std::vector<Layer>(std::make_move_iterator(open[0].rbegin()), std::make_move_iterator(open[0].rend()));
  }

  std::string file_;
  const std::vector<unsigned char>& bytes_;
  std::uint16_t channels_ = 0;
  bool grey_ = false;
  std::uint64_t pixels_ = 0;
  std::vector<std::string> notes_;
};

}  // namespace

LayeredImage ReadPhotoshopBytes(const std::vector<unsigned char>& bytes, const std::string& file) {
  return PhotoshopReader(bytes, file).Read();
}

LayeredImage ReadPhotoshop(const std::string& path) {
  return ReadPhotoshopBytes(ReadInputFile(path, kMaxLayeredFileBytes, "a Photoshop drawing"), path);
}

}  // namespace posemorph::bake::import
