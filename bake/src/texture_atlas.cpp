// SPDX-License-Identifier: MIT
// PackAtlas (texture_atlas.h): crop, pack on shelves, bleed, write ATLS.
#include "posemorph/bake/texture_atlas.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "posemorph/bake/error.h"
#include "posemorph/bake/import/layered_reference.h"
#include "posemorph/bake/mapping/outline_image.h"
#include "posemorph/bake/run_each.h"
#include "posemorph/rig.h"
#include "posemorph/rig_format.h"
#include "rig_writer.h"

namespace posemorph::bake {
namespace {

namespace fmt = format;

std::string Text(StringView s) { return s.data ? std::string(s.data, s.size) : std::string(); }

const Rig& ListRig(const Rig& rig, std::uint32_t list) { return list == 0 ? rig : *rig.attachment(list - 1).rig; }

// One drawing file: its pixels, the crop the rig samples, where it went.
struct Drawing {
  std::string path;
  int width = 0, height = 0;
  std::vector<unsigned char> rgba;       // straight alpha: the content box's pixels only
  int cx = 0, cy = 0, cw = 0, ch = 0;    // the content box: every pixel outside it is transparent
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;    // the crop, [x0, x1) x [y0, y1) canvas pixels; empty while x1 <= x0
  std::uint32_t page = 0, x = 0, y = 0;  // the crop's top left on its page
  int w() const { return x1 - x0; }
  int h() const { return y1 - y0; }
  void Extend(int ax0, int ay0, int ax1, int ay1) {
    if (x1 <= x0) {
      x0 = ax0, y0 = ay0, x1 = ax1, y1 = ay1;
      return;
    }
    x0 = std::min(x0, ax0), y0 = std::min(y0, ay0), x1 = std::max(x1, ax1), y1 = std::max(y1, ay1);
  }
};

// The drawing's pixels with any alpha.
// The drawing's pixels with any alpha; only that box's pixels are kept (the
// rest is transparent), so an HD drawing's empty canvas is not held while
// the others are read (Pip drawn at 4096 px: 5 canvases of 64 MiB).
void CropToContent(Drawing& d) {
  for (int y = 0; y < d.height; ++y)
    for (int x = 0; x < d.width; ++x)
      if (d.rgba[(std::size_t(y) * d.width + x) * 4 + 3] != 0) d.Extend(x, y, x + 1, y + 1);
  if (d.x1 > d.x0) d.cx = d.x0, d.cy = d.y0, d.cw = d.x1 - d.x0, d.ch = d.y1 - d.y0;
  std::vector<unsigned char> content(std::size_t(d.cw) * std::size_t(d.ch) * 4);
  for (int y = 0; y < d.ch; ++y)
    std::copy_n(&d.rgba[(std::size_t(d.cy + y) * d.width + std::size_t(d.cx)) * 4], std::size_t(d.cw) * 4,
                &content[std::size_t(y) * std::size_t(d.cw) * 4]);
  d.rgba = std::move(content);
}

// Part `part`'s vertices in pose `pose` (uvs), one pixel wider each side.
void CropToUvs(Drawing& d, const Rig& r, std::uint32_t part, std::uint32_t pose) {
  const PartView pv = r.part(part);
  const Span<const float> uv = r.uvs(pose);
  const Span<const std::uint32_t> tris = r.triangles();
  double u0 = HUGE_VAL, v0 = HUGE_VAL, u1 = -HUGE_VAL, v1 = -HUGE_VAL;
  for (std::size_t k = 3 * std::size_t(pv.first_triangle); k < 3 * std::size_t(pv.first_triangle + pv.triangle_count);
       ++k) {
    const double x = double(uv[2 * std::size_t(tris[k])]) * d.width,
                 y = double(uv[2 * std::size_t(tris[k]) + 1]) * d.height;
    u0 = std::min(u0, x), v0 = std::min(v0, y), u1 = std::max(u1, x), v1 = std::max(v1, y);
  }
  if (u1 >= u0)
    d.Extend(int(std::floor(u0)) - 1, int(std::floor(v0)) - 1, int(std::ceil(u1)) + 1, int(std::ceil(v1)) + 1);
}

// Shelf packing of the crops (each with `border` pixels around it) into
// pages of W x H: false when one page must hold them all and does not,
// or a crop does not fit a page.
bool Pack(std::vector<Drawing>& drawings, const std::vector<std::size_t>& order, std::uint32_t W, std::uint32_t H,
          std::uint32_t border, bool one_page, std::uint32_t* pages) {
  std::uint32_t page = 0, x = 0, shelf_y = 0, shelf_h = 0;
  for (std::size_t k : order) {
    Drawing& d = drawings[k];
    const std::uint32_t cw = std::uint32_t(d.w()) + 2 * border, ch = std::uint32_t(d.h()) + 2 * border;
    if (cw > W || ch > H) return false;
    if (x + cw > W) shelf_y += shelf_h, x = 0, shelf_h = 0;
    if (shelf_y + ch > H) {
      if (one_page) return false;
      ++page, x = 0, shelf_y = 0, shelf_h = 0;
    }
    d.page = page, d.x = x + border, d.y = shelf_y + border;
    x += cw, shelf_h = std::max(shelf_h, ch);
  }
  *pages = page + 1;
  return true;
}

// The crop, premultiplied, with its edge pixels repeated `border` pixels out.
void Blit(const Drawing& d, std::uint32_t border, AtlasPage& page) {
  const int b = int(border);
  for (int py = -b; py < d.h() + b; ++py)
    for (int px = -b; px < d.w() + b; ++px) {
      const int sx = std::clamp(d.x0 + px, d.x0, d.x1 - 1), sy = std::clamp(d.y0 + py, d.y0, d.y1 - 1);
      // Off the content (off the drawing too): transparent, as the page is.
      if (sx < d.cx || sy < d.cy || sx >= d.cx + d.cw || sy >= d.cy + d.ch) continue;
      const unsigned char* s = &d.rgba[(std::size_t(sy - d.cy) * std::size_t(d.cw) + std::size_t(sx - d.cx)) * 4];
      unsigned char* t = &page.rgba[(std::size_t(int(d.y) + py) * page.width + std::size_t(int(d.x) + px)) * 4];
      for (int c = 0; c < 3; ++c) t[c] = (unsigned char)((unsigned(s[c]) * s[3] + 127) / 255);
      t[3] = s[3];
    }
}

}  // namespace

RigDrawings ReadRigDrawings(const std::vector<unsigned char>& bytes) {
  Rig rig;
  if (!LoadRig(bytes.data(), bytes.size(), &rig, nullptr)) return {};
  return ReadRigDrawings(rig);
}

RigDrawings ReadRigDrawings(const Rig& rig) {
  RigDrawings out;
  out.all = true;
  for (std::uint32_t l = 0; l < 1 + rig.attachment_count(); ++l) {
    const Rig& r = ListRig(rig, l);
    for (std::uint32_t i = 0; i < r.pose_count(); ++i) {
      out.all = out.all && r.uvs(i).size != 0 && r.pose_canvas(i).width >= 1;
      for (std::uint32_t p = 0; p < r.part_count(); ++p) {
        out.all = out.all && r.part_image(p, i).size != 0;
        out.layered = out.layered || import::ParseLayeredReference(Text(r.part_image(p, i)));
      }
    }
  }
  return out;
}

std::string AtlasPageName(const std::string& rig_file, std::uint32_t page) {
  return std::filesystem::path(rig_file).stem().string() + ".page" + std::to_string(page) + ".png";
}

PackedAtlas PackAtlas(const std::vector<unsigned char>& bytes, const std::string& rig_file,
                      const std::string& drawing_folder, const AtlasSettings& settings, const std::string& file) {
  Rig rig;
  Error err;
  if (!LoadRig(bytes.data(), bytes.size(), &rig, &err))
    throw BakeError(file, std::string("internal: the rig written does not load: ") + err.message);
  const std::uint32_t lists = 1 + rig.attachment_count();
  const std::uint32_t border = (settings.padding + 1) / 2;
  std::vector<Drawing> drawings;
  std::map<std::string, std::size_t> found;
  std::vector<std::vector<std::size_t>> used(lists);  // per list, part-major: the drawing of each part and pose
  PackedAtlas out;
  // The path of part p's drawing in pose i of list l, and whether what the
  // part samples (as CropToUvs takes it) is already too large for a page: no
  // atlas then, and no drawing is decoded to find out (Pip drawn at 4096 px:
  // five 64 MiB canvases).
  auto path_of = [&](const Rig& r, std::uint32_t p, std::uint32_t i) {
    return (std::filesystem::path(drawing_folder) / Text(r.part_image(p, i))).string();
  };
  auto probe_of = [&](const Rig& r, std::uint32_t p, std::uint32_t i) {
    Drawing probe;
    probe.width = int(r.pose_canvas(i).width), probe.height = int(r.pose_canvas(i).height);
    CropToUvs(probe, r, p, i);
    return probe;
  };
  auto too_large = [&](const Drawing& probe) {
    return probe.x1 > probe.x0 && (std::uint64_t(probe.w()) + 2 * border > settings.max_page_size ||
                                   std::uint64_t(probe.h()) + 2 * border > settings.max_page_size);
  };
  auto usable = [](const Rig& r, std::uint32_t p, std::uint32_t i) {
    return r.part_image(p, i).size != 0 && r.uvs(i).size != 0 && r.pose_canvas(i).width >= 1;
  };
  // The drawings are decoded first, over the machine's cores, each cropped
  // to its content at once (two canvases in memory, not all): those the loop
  // below reads, up to the first part and pose it stops at.
  std::vector<std::string> paths;
  for (std::uint32_t l = 0, stop = 0; l < lists && !stop; ++l) {
    const Rig& r = ListRig(rig, l);
    for (std::uint32_t p = 0; p < r.part_count() && !stop; ++p)
      for (std::uint32_t i = 0; i < r.pose_count() && !stop; ++i) {
        stop = !usable(r, p, i) || too_large(probe_of(r, p, i));
        if (!stop && std::find(paths.begin(), paths.end(), path_of(r, p, i)) == paths.end())
          paths.push_back(path_of(r, p, i));
      }
  }
  std::vector<Drawing> decoded(paths.size());
  std::vector<std::string> unread(paths.size());
  RunEach(paths.size(), 0, [&](std::size_t k) {
    Drawing& d = decoded[k];
    d.path = paths[k];
    try {
      d.rgba = mapping::ReadPngRgba(d.path, &d.width, &d.height, ErrorSource(d.path));
    } catch (const BakeError& e) {
      unread[k] = e.what();
      return;
    }
    CropToContent(d);
  });
  for (std::uint32_t l = 0; l < lists; ++l) {
    const Rig& r = ListRig(rig, l);
    const std::uint32_t M = r.part_count(), N = r.pose_count();
    for (std::uint32_t p = 0; p < M; ++p)
      for (std::uint32_t i = 0; i < N; ++i) {
        const std::string whose = (l ? "attachment " + std::to_string(l - 1) + ", " : std::string()) +
                                  (M > 1 ? "part '" + Text(r.part(p).name) + "' in " : std::string()) + "pose '" +
                                  Text(r.pose_name(i)) + "'";
        if (!usable(r, p, i))
          throw BakeError(file, "texture atlas: " + whose +
                                    " has no drawing; an atlas needs one per part and pose (\"atlas\": false bakes "
                                    "without one)");
        const std::string path = path_of(r, p, i);
        const Drawing probe = probe_of(r, p, i);
        if (too_large(probe)) {
          out.skipped = path + ": the part of it the rig samples, at least " + std::to_string(probe.w()) + "x" +
                        std::to_string(probe.h()) + " pixels, does not fit a page of " +
                        std::to_string(settings.max_page_size) + " (atlas.max_page_size); the renderers read the " +
                        "drawings";
          return out;
        }
        auto [it, added] = found.emplace(path, drawings.size());
        if (added) {
          const std::size_t k = std::size_t(std::find(paths.begin(), paths.end(), path) - paths.begin());
          // A reference the bake does not read ("image" given with a
          // mesh): the game finds that drawing itself.
          if (!unread[k].empty()) {
            out.skipped = unread[k];
            return out;
          }
          Drawing d = std::move(decoded[k]);
          const DrawingCanvas canvas = r.pose_canvas(i);
          if (canvas.width > 0 && (double(d.width) != canvas.width || double(d.height) != canvas.height))
            throw BakeError(path, "is " + std::to_string(d.width) + "x" + std::to_string(d.height) +
                                      " pixels; the rig was baked from a drawing of " +
                                      std::to_string(long(canvas.width)) + "x" + std::to_string(long(canvas.height)));
          out.drawing_pixels += std::uint64_t(d.width) * std::uint64_t(d.height);
          drawings.push_back(std::move(d));
        }
        CropToUvs(drawings[it->second], r, p, i);
        used[l].push_back(it->second);
      }
  }
  // A mesh may reach a little past its drawing's edge (content touching the
  // canvas's border): the crop then holds transparent pixels there, as a
  // renderer's clamp-to-border sampling of the drawing would give. Up to a
  // canvas beyond each side; uvs farther out are not a drawing's.
  for (Drawing& d : drawings) {
    if (d.x1 <= d.x0) d.x0 = d.y0 = 0, d.x1 = d.y1 = 1;
    if (d.x0 < -d.width || d.y0 < -d.height || d.x1 > 2 * d.width || d.y1 > 2 * d.height)
      throw BakeError(d.path, "texture atlas: the rig's uvs reach (" + std::to_string(d.x0) + ", " +
                                  std::to_string(d.y0) + ") .. (" + std::to_string(d.x1) + ", " + std::to_string(d.y1) +
                                  ") pixels, far outside the drawing; bake with \"atlas\": false");
  }
  std::vector<std::size_t> order(drawings.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return drawings[a].h() != drawings[b].h() ? drawings[a].h() > drawings[b].h() : drawings[a].w() > drawings[b].w();
  });
  // The smallest page that holds every crop, W x W/2 or W x W; else pages of the largest size.
  std::uint32_t W = 64, H = 32, pages = 0;
  while (!Pack(drawings, order, W, H, border, true, &pages)) {
    if (H < W) {
      H = W;
    } else if (W < settings.max_page_size) {
      W *= 2, H = W / 2;
    } else {
      break;
    }
  }
  if (pages == 0) {
    W = H = settings.max_page_size;
    if (!Pack(drawings, order, W, H, border, false, &pages)) {
      const Drawing& big = *std::max_element(drawings.begin(), drawings.end(), [](const Drawing& a, const Drawing& b) {
        return std::max(a.w(), a.h()) < std::max(b.w(), b.h());
      });
      out.skipped = big.path + ": the part of it the rig samples, " + std::to_string(big.w()) + "x" +
                    std::to_string(big.h()) + " pixels, does not fit a page of " + std::to_string(W) +
                    " (atlas.max_page_size); the renderers read the drawings";
      return out;
    }
  }
  if (pages > fmt::kMaxAtlasPages) {
    out.skipped = "the drawings need " + std::to_string(pages) + " pages of " + std::to_string(W) +
                  " pixels, above the format's " + std::to_string(fmt::kMaxAtlasPages) +
                  " (raise atlas.max_page_size); the renderers read the drawings";
    return out;
  }
  std::uint64_t covered = 0;
  for (std::uint32_t k = 0; k < pages; ++k)
    out.pages.push_back(
        AtlasPage{AtlasPageName(rig_file, k), W, H, std::vector<unsigned char>(std::size_t(W) * H * 4)});
  for (const Drawing& d : drawings) {
    Blit(d, border, out.pages[d.page]);
    covered += std::uint64_t(d.w()) * std::uint64_t(d.h());
  }
  out.drawings = std::uint32_t(drawings.size());
  out.filled = double(covered) / (double(pages) * W * H);
  // ATLS for each list: every page, each part and pose's region.
  std::vector<RigSections::Section> atls(lists);
  for (std::uint32_t l = 0; l < lists; ++l) {
    std::vector<unsigned char>& b = atls[l].bytes;
    atls[l].tag = fmt::kAtlas;
    fmt::AtlasHeader h{};
    h.page_count = pages;
    h.region_count = std::uint32_t(used[l].size());
    h.flags = fmt::kAtlasPremultiplied;
    AppendRecord(b, h);
    for (std::uint32_t k = 0; k < pages; ++k) AppendRecord(b, fmt::AtlasPageEntry{W, H});
    for (std::size_t k : used[l]) {
      const Drawing& d = drawings[k];
      fmt::AtlasRegionEntry e{};
      e.page = std::uint16_t(d.page), e.x = std::uint16_t(d.x), e.y = std::uint16_t(d.y);
      e.width = std::uint16_t(d.w()), e.height = std::uint16_t(d.h());
      e.canvas_x = d.x0, e.canvas_y = d.y0;
      AppendRecord(b, e);
    }
    for (const AtlasPage& page : out.pages) AppendString(b, page.name);
    out.regions += h.region_count;
  }
  std::vector<std::vector<RigSections::Section>> nested;
  for (std::uint32_t l = 1; l < lists; ++l) nested.push_back({atls[l]});
  out.rig = AddRigSections(bytes, {atls[0]}, nested, file);
  // The bake checks what it wrote: it loads, and every part samples inside its region.
  Rig written;
  if (!LoadRig(out.rig.data(), out.rig.size(), &written, &err))
    throw BakeError(file, std::string("internal: the rig with its atlas does not load: ") + err.message);
  for (std::uint32_t l = 0; l < lists; ++l) {
    const Rig& r = ListRig(written, l);
    for (std::uint32_t p = 0; p < r.part_count(); ++p)
      for (std::uint32_t i = 0; i < r.pose_count(); ++i) {
        const TextureRegion g = r.part_region(p, i);
        const PartView pv = r.part(p);
        for (std::size_t k = 3 * std::size_t(pv.first_triangle);
             k < 3 * std::size_t(pv.first_triangle + pv.triangle_count); ++k) {
          const float* uv = r.uvs(i).data + 2 * std::size_t(r.triangles()[k]);
          const double x = (double(uv[0]) * g.scale_u + g.offset_u) * W,
                       y = (double(uv[1]) * g.scale_v + g.offset_v) * H;
          if (!(r.has_atlas() && x >= g.x && x <= g.x + g.width && y >= g.y && y <= g.y + g.height))
            throw BakeError(file, "internal: texture atlas: list " + std::to_string(l) + ", part " + std::to_string(p) +
                                      ", pose " + std::to_string(i) + " samples outside its region");
        }
      }
  }
  return out;
}

}  // namespace posemorph::bake
