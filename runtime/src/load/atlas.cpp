// SPDX-License-Identifier: MIT
// The texture pages (ATLS, format 1.12; loader.h): the atlas's pages and
// regions, checked, or, for a rig without an atlas, one page per part and
// pose (its drawing) with identity regions, so that renderers draw both the
// same way.
#include <cmath>

#include "loader.h"
#include "posemorph/format/record_codec.h"
#include "posemorph/image_reference.h"

namespace posemorph {

using namespace detail::load;  // NOLINT(google-build-using-namespace): the loader's own types

bool RigLoader::ReadAtlas(const unsigned char* bytes, const Parser& parser, const Counts& c, const Sources& s, Atlas* a,
                          Error* err) {
  const Section* section = parser.table.Find(fmt::kAtlas);
  if (!section) return true;
  const unsigned char* p = bytes + section->offset;
  const std::uint64_t size = section->size;
  if (size < fmt::AtlasHeader::kSize)
    return Fail(err, ErrorCode::kBadLayout, "ATLS section of %llu bytes is shorter than its header",
                (unsigned long long)size);
  a->h = fmt::DecodeRecord<fmt::AtlasHeader>(p);
  const fmt::AtlasHeader& h = a->h;
  const std::uint64_t M = c.parts ? c.parts : 1;
  if (h.page_count < 1 || h.page_count > fmt::kMaxAtlasPages)
    return Fail(err, ErrorCode::kBadValue, "ATLS: %u pages, outside 1..%u", h.page_count, fmt::kMaxAtlasPages);
  if (h.region_count != M * c.N)
    return Fail(err, ErrorCode::kBadValue, "ATLS: %u regions for %llu parts and %llu poses (one each)", h.region_count,
                (unsigned long long)M, (unsigned long long)c.N);
  if ((h.flags & ~fmt::kAtlasPremultiplied) != 0 || h.reserved != 0)
    return Fail(err, ErrorCode::kBadValue, "ATLS: unknown flags 0x%x or a reserved field that is not zero", h.flags);
  std::uint64_t at = fmt::AtlasHeader::kSize;
  const std::uint64_t entries = std::uint64_t(h.page_count) * fmt::AtlasPageEntry::kSize +
                                std::uint64_t(h.region_count) * fmt::AtlasRegionEntry::kSize;
  if (entries > size - at) return Fail(err, ErrorCode::kBadLayout, "ATLS's entries run past the section");
  a->pages = p + at;
  a->regions = a->pages + std::uint64_t(h.page_count) * fmt::AtlasPageEntry::kSize;
  at += entries;
  std::uint32_t width = 0, height = 0;
  for (std::uint32_t k = 0; k < h.page_count; ++k) {
    const auto e = fmt::DecodeEntry<fmt::AtlasPageEntry>(a->pages, k);
    if (e.width < 1 || e.height < 1 || e.width > fmt::kMaxAtlasPageSize || e.height > fmt::kMaxAtlasPageSize)
      return Fail(err, ErrorCode::kBadValue, "ATLS page %u is %ux%u, outside 1..%u", k, e.width, e.height,
                  fmt::kMaxAtlasPageSize);
    if (k > 0 && (e.width != width || e.height != height))
      return Fail(err, ErrorCode::kBadValue, "ATLS page %u is %ux%u, page 0 %ux%u: a rig's pages have one size", k,
                  e.width, e.height, width, height);
    width = e.width, height = e.height;
  }
  for (std::uint64_t i = 0; i < c.N; ++i) {
    if (!s.canvases) return Fail(err, ErrorCode::kBadLayout, "ATLS without CANV: an atlas needs each pose's canvas");
    double canvas[4];
    std::memcpy(canvas, s.canvases + 32 * i, sizeof canvas);
    if (!(canvas[0] >= 1 && canvas[1] >= 1 && canvas[0] <= fmt::kMaxAtlasCanvasOffset &&
          canvas[1] <= fmt::kMaxAtlasCanvasOffset))
      return Fail(err, ErrorCode::kBadValue, "ATLS: the canvas of pose %llu is %gx%g, outside 1..%d",
                  (unsigned long long)i, canvas[0], canvas[1], fmt::kMaxAtlasCanvasOffset);
  }
  for (std::uint32_t k = 0; k < h.region_count; ++k) {
    const auto e = fmt::DecodeEntry<fmt::AtlasRegionEntry>(a->regions, k);
    if (e.page >= h.page_count || e.reserved != 0)
      return Fail(err, ErrorCode::kBadValue, "ATLS region %u: page %u of %u, or a reserved field that is not zero", k,
                  e.page, h.page_count);
    if (e.width < 1 || e.height < 1 || e.x > width || e.y > height || e.width > width - e.x || e.height > height - e.y)
      return Fail(err, ErrorCode::kBadValue, "ATLS region %u: %ux%u at (%u, %u) is not inside its %ux%u page", k,
                  e.width, e.height, e.x, e.y, width, height);
    if (e.canvas_x < -fmt::kMaxAtlasCanvasOffset || e.canvas_x > fmt::kMaxAtlasCanvasOffset ||
        e.canvas_y < -fmt::kMaxAtlasCanvasOffset || e.canvas_y > fmt::kMaxAtlasCanvasOffset)
      return Fail(err, ErrorCode::kBadValue, "ATLS region %u: its crop's corner (%d, %d) is beyond +-%d", k, e.canvas_x,
                  e.canvas_y, fmt::kMaxAtlasCanvasOffset);
  }
  a->names = p + at;
  for (std::uint32_t k = 0; k < h.page_count; ++k) {
    if (size - at < 4) return Fail(err, ErrorCode::kBadLayout, "ATLS's page names run past the section");
    std::uint32_t n = 0;
    fmt::FieldDecoder{p + at}(n);
    if (n < 1 || n > fmt::kMaxAtlasPageName || size - at - 4 < n)
      return Fail(err, ErrorCode::kBadLayout, "ATLS page %u's name of %u bytes is empty, too long or past the section",
                  k, n);
    if (!ImageReferenceStaysInside({reinterpret_cast<const char*>(p + at + 4), n}))
      return Fail(err, ErrorCode::kBadValue,
                  "ATLS page %u's name does not name a file beside the rig (absolute, '..', or odd characters)", k);
    a->name_bytes += n;
    at += 4 + std::uint64_t(n);
  }
  if (at != size)
    return Fail(err, ErrorCode::kBadLayout, "ATLS is %llu bytes, its entries and names %llu", (unsigned long long)size,
                (unsigned long long)at);
  a->canvases = s.canvases;
  a->present = true;
  return true;
}

void RigLoader::LayoutAtlas(ArenaLayout& arena, const Counts& c, const Atlas& a, Rig* rig) {
  const std::uint64_t regions = (c.parts ? c.parts : 1) * c.N;
  auto* pages = arena.Take<TexturePage>(a.present ? a.h.page_count : regions);
  auto* region = arena.Take<TextureRegion>(regions);
  char* chars = arena.Take<char>(a.name_bytes);
  if (!region) return;  // the sizing pass
  rig->pages_ = {pages, std::size_t(a.present ? a.h.page_count : regions)};
  rig->regions_ = {region, std::size_t(regions)};
  rig->has_atlas_ = a.present;
  if (!a.present) return;  // FillPages, once the strings are read
  const bool premultiplied = (a.h.flags & fmt::kAtlasPremultiplied) != 0;
  const unsigned char* name = a.names;
  for (std::uint32_t k = 0; k < a.h.page_count; ++k) {
    const auto e = fmt::DecodeEntry<fmt::AtlasPageEntry>(a.pages, k);
    std::uint32_t n = 0;
    fmt::FieldDecoder{name}(n);
    std::memcpy(chars, name + 4, n);
    pages[k] = TexturePage{StringView{chars, n}, e.width, e.height, true, premultiplied};
    chars += n, name += 4 + n;
  }
  const double PW = pages[0].width, PH = pages[0].height;
  const std::uint64_t N = c.N;
  for (std::uint64_t k = 0; k < regions; ++k) {
    const auto e = fmt::DecodeEntry<fmt::AtlasRegionEntry>(a.regions, k);
    double canvas[2];  // the pose's canvas (CANV, checked by ReadAtlas): W, H
    std::memcpy(canvas, a.canvases + 32 * (k % N), sizeof canvas);
    region[k] = TextureRegion{e.page,
                              float(canvas[0] / PW),
                              float((double(e.x) - e.canvas_x) / PW),
                              float(canvas[1] / PH),
                              float((double(e.y) - e.canvas_y) / PH),
                              e.x,
                              e.y,
                              e.width,
                              e.height};
  }
}

void RigLoader::FillPages(const Atlas& a, Rig* rig) {
  if (a.present) return;
  auto* pages = const_cast<TexturePage*>(rig->pages_.data);  // the arena's, laid out by LayoutAtlas
  auto* regions = const_cast<TextureRegion*>(rig->regions_.data);
  const std::uint32_t M = rig->part_count(), N = rig->pose_count_;
  for (std::uint32_t p = 0; p < M; ++p)
    for (std::uint32_t i = 0; i < N; ++i) {
      const DrawingCanvas canvas = rig->pose_canvas(i);
      const bool sized = canvas.width >= 1 && canvas.height >= 1 && canvas.width <= fmt::kMaxAtlasPageSize &&
                         canvas.height <= fmt::kMaxAtlasPageSize;
      const std::uint32_t k = p * N + i;
      pages[k] = TexturePage{rig->part_image(p, i), sized ? std::uint32_t(canvas.width) : 0u,
                             sized ? std::uint32_t(canvas.height) : 0u, false, false};
      regions[k] = TextureRegion{k, 1, 0, 1, 0, 0, 0, pages[k].width, pages[k].height};
    }
}

}  // namespace posemorph
