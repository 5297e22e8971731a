// SPDX-License-Identifier: MIT
#include "textured_sheet.h"

#include <png.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "posemorph/bake/import/layered_reference.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/ghosting.h"
#include "posemorph/bake/input_file.h"
#include "posemorph/image_reference.h"
#include "posemorph/jobs.h"

namespace posemorph::bake {
namespace {

std::string RigString(StringView v) { return std::string(v.data, v.size); }

RgbaImage DecodeRgba(const std::vector<unsigned char>& file, const std::string& path) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, file.data(), file.size()))
    throw BakeError(path, std::string("cannot read PNG: ") + image.message);
  if (image.width == 0 || image.height == 0 || std::uint64_t(image.width) * image.height > kMaxDrawingPixels) {
    png_image_free(&image);
    throw BakeError(path, "PNG size " + std::to_string(image.width) + " x " + std::to_string(image.height) +
                              " is empty or above the limit of " + std::to_string(kMaxDrawingPixels) + " pixels");
  }
  image.format = PNG_FORMAT_RGBA;
  RgbaImage out;
  out.width = image.width;
  out.height = image.height;
  out.rgba.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, out.rgba.data(), 0, nullptr)) {
    const std::string message = image.message;
    png_image_free(&image);
    throw BakeError(path, "cannot decode PNG: " + message);
  }
  return out;
}

// Premultiplied colour of a drawing at uv (0..1 across the canvas, y down);
// transparent outside it, as the viewer's clamp-to-border sampler. Linear is
// the ghosting measure's sampler (ghosting.h).
void Sample(const RgbaImage& d, double u, double v, TextureFilter filter, double out[4]) {
  if (filter != TextureFilter::kNearest) {
    SampleDrawing(DrawingPixels{d.width, d.height, d.rgba.data()}, u, v, out);
    return;
  }
  out[0] = out[1] = out[2] = out[3] = 0;
  const double tx = std::floor(u * d.width - 0.5 + 0.5), ty = std::floor(v * d.height - 0.5 + 0.5);
  if (!(tx >= 0 && ty >= 0 && tx < double(d.width) && ty < double(d.height))) return;
  const unsigned char* p = &d.rgba[(std::size_t(ty) * d.width + std::size_t(tx)) * 4];
  const double a = p[3] / 255.0;
  out[0] = a * p[0] / 255.0;
  out[1] = a * p[1] / 255.0;
  out[2] = a * p[2] / 255.0;
  out[3] = a;
}

// A rig with an atlas: each part's drawing in each pose cut back out of
// its page (beside the rig file) onto a canvas of its pose's size,
// transparent outside the crop the rig samples, straight alpha again.
std::vector<RgbaImage> CutFromPages(const Rig& rig, const std::string& rig_file) {
  const std::filesystem::path folder = std::filesystem::path(rig_file).parent_path();
  std::vector<RgbaImage> pages;
  for (std::uint32_t k = 0; k < rig.page_count(); ++k) {
    const TexturePage page = rig.page(k);
    const std::string ref = RigString(page.name);
    if (!ImageReferenceStaysInside(page.name))
      throw BakeError(rig_file, "atlas page '" + ref + "' is not a file beside the rig");
    const std::string path = (folder / ref).string();
    pages.push_back(DecodeRgba(ReadInputFile(path, kMaxTextFileBytes, "an atlas page"), path));
    if (pages.back().width != page.width || pages.back().height != page.height)
      throw BakeError(path, "the atlas page is " + std::to_string(pages.back().width) + "x" +
                                std::to_string(pages.back().height) + ", the rig says " + std::to_string(page.width) +
                                "x" + std::to_string(page.height) + " (bake the rig again)");
  }
  std::vector<RgbaImage> out;
  for (std::uint32_t p = 0; p < rig.part_count(); ++p)
    for (std::uint32_t i = 0; i < rig.pose_count(); ++i) {
      const TextureRegion g = rig.part_region(p, i);
      const RgbaImage& page = pages[g.page];
      const DrawingCanvas c = rig.pose_canvas(i);
      RgbaImage d;
      d.width = std::uint32_t(c.width), d.height = std::uint32_t(c.height);
      d.rgba.assign(std::size_t(d.width) * d.height * 4, 0);
      // The crop's corner on the canvas: page x = canvas x + offset_u x page width.
      const long cx = long(g.x) - std::lround(double(g.offset_u) * page.width);
      const long cy = long(g.y) - std::lround(double(g.offset_v) * page.height);
      for (std::uint32_t y = 0; y < g.height; ++y)
        for (std::uint32_t x = 0; x < g.width; ++x) {
          const long tx = cx + long(x), ty = cy + long(y);
          if (tx < 0 || ty < 0 || tx >= long(d.width) || ty >= long(d.height)) continue;
          const unsigned char* s = &page.rgba[(std::size_t(g.y + y) * page.width + (g.x + x)) * 4];
          unsigned char* t = &d.rgba[(std::size_t(ty) * d.width + std::size_t(tx)) * 4];
          for (int k = 0; k < 3; ++k) t[k] = s[3] ? (unsigned char)std::min(255, (s[k] * 255 + s[3] / 2) / s[3]) : 0;
          t[3] = s[3];
        }
      out.push_back(std::move(d));
    }
  return out;
}

}  // namespace

std::vector<RgbaImage> ReadPoseDrawings(const Rig& rig, const std::string& rig_file, const std::string& images,
                                        bool use_atlas) {
  std::vector<RgbaImage> out;
  if (rig.uvs(0).size == 0) throw BakeError(rig_file, "has no uvs: --textured needs a rig baked from drawings");
  if (rig.has_atlas() && use_atlas) return CutFromPages(rig, rig_file);
  const bool parts = rig.part_count() > 1;
  for (std::uint32_t p = 0; p < rig.part_count(); ++p)
    for (std::uint32_t i = 0; i < rig.pose_count(); ++i) {
      // "pose 'x'" for a rig without parts, "part 'a' in pose 'x'" for a layered one.
      const std::string whose = (parts ? "part '" + RigString(rig.part(p).name) + "' in pose '" : "pose '") +
                                RigString(rig.pose_name(i)) + "'";
      const std::string ref = RigString(rig.part_image(p, i));
      if (ref.empty())
        throw BakeError(rig_file,
                        whose + " has no drawing: --textured needs one per " + (parts ? "part and " : "") + "pose");
      if (!ImageReferenceStaysInside(StringView{ref.data(), ref.size()}))
        throw BakeError(rig_file, whose + ": image reference '" + ref + "' leaves the images folder");
      const std::string path = (std::filesystem::path(images) / ref).string();
      out.push_back(DecodeRgba(import::ReadDrawingBytes(path, "a drawing", ErrorSource(path)), path));
      const DrawingCanvas c = rig.pose_canvas(i);
      if (c.width > 0 && (double(out.back().width) != c.width || double(out.back().height) != c.height))
        throw BakeError(path, "is " + std::to_string(out.back().width) + " x " + std::to_string(out.back().height) +
                                  " pixels; the rig was baked from a drawing of " + std::to_string(long(c.width)) +
                                  " x " + std::to_string(long(c.height)));
    }
  return out;
}

namespace {

// The sheet being drawn: premultiplied colour accumulated per pixel, and
// which pixels a triangle of the part being drawn has covered (a pixel on a
// shared edge is drawn once per part): the stamp of the last part that drew
// it, each part of each frame drawn with a stamp of its own.
struct SheetCanvas {
  std::uint32_t width = 0;
  std::vector<double> acc;
  std::vector<std::uint32_t> stamp;
  std::uint32_t next_stamp = 0;
};

// One part of a frame into its cell (centred at ox, oy; cell column cx, row
// cy): each triangle rasterised, each pixel the texture-weighted mix of the
// part's drawings (drawings[part * N + pose]), laid over what the parts
// behind it left there (premultiplied "over"), each sample multiplied by
// `tint` (premultiplied: r a, g a, b a, a).
void DrawPart(const Rig& rig, const std::vector<RgbaImage>& drawings, const Frame& f, std::uint32_t part,
              std::uint32_t cx, std::uint32_t cy, const TexturedSheetLayout& lay, TextureFilter filter,
              const std::array<double, 4>& tint, SheetCanvas& canvas) {
  const std::uint32_t N = rig.pose_count(), cell = lay.cell;
  const PartView range = rig.part(part);
  const std::uint32_t first = rig.part_count() > 1 ? range.first_triangle : 0;
  const std::uint32_t end = rig.part_count() > 1 ? first + range.triangle_count : rig.triangle_count();
  const double ox = (cx + 0.5) * cell, oy = (cy + 0.5) * cell;
  std::vector<double>& acc = canvas.acc;
  const std::uint32_t stamp = ++canvas.next_stamp;
  auto sx = [&](std::uint32_t v) { return ox + (f.positions[2 * v] - lay.centre_x) * lay.scale; };
  auto sy = [&](std::uint32_t v) { return oy - (f.positions[2 * v + 1] - lay.centre_y) * lay.scale; };
  for (std::uint32_t t = first; t < end; ++t) {
    const std::uint32_t* tri = rig.triangles().data + 3 * t;
    const double ax = sx(tri[0]), ay = sy(tri[0]), bx = sx(tri[1]), by = sy(tri[1]), qx = sx(tri[2]), qy = sy(tri[2]);
    const double area = (bx - ax) * (qy - ay) - (by - ay) * (qx - ax);
    if (!(std::abs(area) > 1e-12)) continue;
    const long px0 = std::max<long>(long(std::floor(std::min({ax, bx, qx}))), long(cx * cell));
    const long px1 = std::min<long>(long(std::ceil(std::max({ax, bx, qx}))), long((cx + 1) * cell) - 1);
    const long py0 = std::max<long>(long(std::floor(std::min({ay, by, qy}))), long(cy * cell));
    const long py1 = std::min<long>(long(std::ceil(std::max({ay, by, qy}))), long((cy + 1) * cell) - 1);
    for (long py = py0; py <= py1; ++py)
      for (long px = px0; px <= px1; ++px) {
        const std::size_t at = std::size_t(py) * canvas.width + std::size_t(px);
        if (canvas.stamp[at] == stamp) continue;  // a pixel on a shared edge is drawn once
        const double x = px + 0.5, y = py + 0.5;
        const double l1 = ((x - ax) * (qy - ay) - (y - ay) * (qx - ax)) / area;
        const double l2 = ((bx - ax) * (y - ay) - (by - ay) * (x - ax)) / area;
        const double l0 = 1 - l1 - l2;
        if (l0 < -1e-9 || l1 < -1e-9 || l2 < -1e-9) continue;
        canvas.stamp[at] = stamp;
        double colour[4] = {0, 0, 0, 0};
        for (std::uint32_t i = 0; i < N; ++i) {
          const double w = f.texture[i];
          if (!(w > 1e-6)) continue;
          const auto uv = rig.uvs(i);
          const double u = l0 * uv[2 * tri[0]] + l1 * uv[2 * tri[1]] + l2 * uv[2 * tri[2]];
          const double v = l0 * uv[2 * tri[0] + 1] + l1 * uv[2 * tri[1] + 1] + l2 * uv[2 * tri[2] + 1];
          double c[4];
          Sample(drawings[std::size_t(part) * N + i], u, v, filter, c);
          for (int ch = 0; ch < 4; ++ch) colour[ch] += w * c[ch];
        }
        for (int ch = 0; ch < 4; ++ch) colour[ch] *= tint[std::size_t(ch)];
        for (int ch = 0; ch < 4; ++ch)
          acc[at * 4 + std::size_t(ch)] = colour[ch] + (1 - colour[3]) * acc[at * 4 + std::size_t(ch)];
      }
  }
}

// A cell of the sheet: the body's frame and, for a character with control
// channels, each attachment's (positions placed by AttachJob, texture
// weights its channel's).
struct Cell {
  Frame body;
  std::vector<Frame> attached;
};

// The cell at point (x, y) of channel `channel`'s pose space, every other
// channel at its first pose's point.
Cell EvaluateCell(const Rig& rig, std::uint32_t channel, double x, double y, const EvalOptions& options) {
  Cell cell;
  const double bx = channel == 0 ? x : rig.pose_points()[0], by = channel == 0 ? y : rig.pose_points()[1];
  cell.body = EvaluateFrame(rig, bx, by, options);
  if (rig.attachment_count() == 0) return cell;
  const std::size_t NW = rig.attached_weight_count();
  std::vector<double> w(NW), wl(NW), texture(NW);
  for (std::uint32_t c = 1; c < rig.channel_count(); ++c) {
    const Rig& ch = *rig.channel_rig(c);
    const std::size_t at = rig.channel_weight_offset(c), n = ch.pose_count();
    WeightsJob job;
    job.rig = &ch;
    job.x = c == channel ? x : ch.pose_points()[0];
    job.y = c == channel ? y : ch.pose_points()[1];
    job.sigma = options.sigma < 0 ? ch.default_sigma() : options.sigma;
    job.limit_weights = options.limit_weights;
    job.raw = {w.data() + at, n}, job.limited = {wl.data() + at, n}, job.texture = {texture.data() + at, n};
    job.Run();
  }
  std::vector<double> positions(2 * std::size_t(rig.attached_vertex_count())), work(rig.attach_workspace_size());
  AttachJob attach;
  attach.rig = &rig;
  attach.body_positions = {cell.body.positions.data(), cell.body.positions.size()};
  attach.weights = {w.data(), NW}, attach.limited_weights = {wl.data(), NW};
  attach.interpolation = options.interpolation;
  attach.workspace = {work.data(), work.size()}, attach.positions = {positions.data(), positions.size()};
  attach.Run();
  std::size_t offset = 0;
  for (std::uint32_t a = 0; a < rig.attachment_count(); ++a) {
    const AttachmentView v = rig.attachment(a);
    const std::size_t p2 = 2 * std::size_t(v.rig->vertex_count()), at = rig.channel_weight_offset(v.channel);
    Frame f;
    f.positions.assign(positions.begin() + std::ptrdiff_t(offset), positions.begin() + std::ptrdiff_t(offset + p2));
    f.texture.assign(texture.begin() + std::ptrdiff_t(at), texture.begin() + std::ptrdiff_t(at + v.rig->pose_count()));
    cell.attached.push_back(std::move(f));
    offset += p2;
  }
  return cell;
}

// The dominant drawing's pose of a frame (the largest texture weight, ties
// to the lower pose).
std::uint32_t Dominant(const Rig& rig, const Frame& f) {
  std::uint32_t dominant = 0;
  for (std::uint32_t i = 1; i < rig.pose_count(); ++i)
    if (f.texture[i] > f.texture[dominant]) dominant = i;
  return dominant;
}

// One cell: its parts back to front, in the order of its dominant
// drawing's pose, as the runtime's DrawList orders them; a character with
// channels has its attachments merged in by draw order (ties: the body's
// parts first), as posemorph-view draws them.
void DrawCell(const Rig& rig, const std::vector<RgbaImage>& drawings,
              const std::vector<std::vector<RgbaImage>>& attachment_drawings, const Cell& cell, std::uint32_t cx,
              std::uint32_t cy, const TexturedSheetLayout& lay, TextureFilter filter, const SheetColour& colour,
              SheetCanvas& canvas) {
  struct Item {
    std::int32_t order;
    const Rig* rig;
    const std::vector<RgbaImage>* drawings;
    const Frame* frame;
    std::uint32_t part;
  };
  std::vector<Item> items;
  const std::uint32_t dominant = Dominant(rig, cell.body);
  for (std::uint32_t part : rig.draw_sequence(dominant))
    items.push_back({rig.part_draw_order(part, dominant), &rig, &drawings, &cell.body, part});
  for (std::uint32_t a = 0; a < cell.attached.size() && a < attachment_drawings.size(); ++a) {
    const Rig& r = *rig.attachment(a).rig;
    const std::uint32_t d = Dominant(r, cell.attached[a]);
    for (std::uint32_t part : r.draw_sequence(d))
      items.push_back({r.part_draw_order(part, d), &r, &attachment_drawings[a], &cell.attached[a], part});
  }
  std::stable_sort(items.begin(), items.end(), [](const Item& l, const Item& r) { return l.order < r.order; });
  const posemorph::Colour c = posemorph::ClampColour(colour.colour);
  for (const Item& item : items) {
    // The body's parts at their own opacities; the attachments' at the character's.
    const bool body = item.rig == &rig;
    const double part = body && item.part < colour.part_opacities.size()
                            ? double(posemorph::ClampColour({1, 1, 1, colour.part_opacities[item.part]}).a)
                            : 1.0;
    const double a = double(c.a) * part;
    const std::array<double, 4> tint = {c.r * a, c.g * a, c.b * a, a};
    DrawPart(*item.rig, *item.drawings, *item.frame, item.part, cx, cy, lay, filter, tint, canvas);
  }
}

}  // namespace

std::vector<std::vector<RgbaImage>> ReadAttachmentDrawings(const Rig& rig, const std::string& rig_file,
                                                           const std::string& images) {
  std::vector<std::vector<RgbaImage>> out;
  for (std::uint32_t a = 0; a < rig.attachment_count(); ++a)
    out.push_back(ReadPoseDrawings(*rig.attachment(a).rig, rig_file, images));
  return out;
}

RgbaImage TexturedSheet(const Rig& rig, const std::vector<RgbaImage>& drawings, int columns, int rows,
                        const EvalOptions& options, TextureFilter filter, std::uint32_t cell,
                        TexturedSheetLayout* layout, std::uint32_t channel,
                        const std::vector<std::vector<RgbaImage>>& attachment_drawings, const SheetColour& colour) {
  const Rig& space = channel < rig.channel_count() ? *rig.channel_rig(channel) : rig;
  if (channel >= rig.channel_count()) channel = 0;
  const std::uint32_t N = space.pose_count();
  const auto pts = space.pose_points();
  std::vector<Cell> frames;
  for (std::uint32_t i = 0; i < N; ++i)
    frames.push_back(EvaluateCell(rig, channel, pts[2 * i], pts[2 * i + 1], options));
  const std::vector<std::array<double, 2>> points = SheetPoints(space, columns, rows);
  for (const auto& p : points) frames.push_back(EvaluateCell(rig, channel, p[0], p[1], options));
  const std::uint32_t grid_rows = std::uint32_t(points.size()) / std::uint32_t(columns);

  // One scale and one centre for every cell, so that sizes and places compare.
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  auto extend = [&](const Frame& f) {
    for (std::size_t k = 0; k + 1 < f.positions.size(); k += 2) {
      x0 = std::min(x0, f.positions[k]), x1 = std::max(x1, f.positions[k]);
      y0 = std::min(y0, f.positions[k + 1]), y1 = std::max(y1, f.positions[k + 1]);
    }
  };
  for (const Cell& c : frames) {
    extend(c.body);
    for (const Frame& f : c.attached) extend(f);
  }
  TexturedSheetLayout lay;
  lay.cell = cell;
  lay.columns = std::uint32_t(std::max<int>(columns, int(N)));
  lay.rows = grid_rows;
  lay.scale = 0.92 * cell / std::max({x1 - x0, y1 - y0, 1e-12});
  lay.centre_x = 0.5 * (x0 + x1);
  lay.centre_y = 0.5 * (y0 + y1);
  if (layout) *layout = lay;

  RgbaImage sheet;
  sheet.width = lay.columns * cell;
  sheet.height = (1 + grid_rows) * cell;
  SheetCanvas canvas;
  canvas.width = sheet.width;
  canvas.acc.assign(std::size_t(sheet.width) * sheet.height * 4, 0.0);
  canvas.stamp.assign(std::size_t(sheet.width) * sheet.height, 0);
  const std::vector<double>& acc = canvas.acc;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const std::uint32_t cx = k < N ? std::uint32_t(k) : std::uint32_t(k - N) % std::uint32_t(columns);
    const std::uint32_t cy = k < N ? 0 : 1 + std::uint32_t(k - N) / std::uint32_t(columns);
    DrawCell(rig, drawings, attachment_drawings, frames[k], cx, cy, lay, filter, colour, canvas);
  }
  // Over a light background, as the viewer's.
  const double background[3] = {0.93, 0.94, 0.95};
  sheet.rgba.resize(acc.size());
  for (std::size_t p = 0; p < canvas.stamp.size(); ++p) {
    const double a = std::clamp(acc[p * 4 + 3], 0.0, 1.0);
    for (int ch = 0; ch < 3; ++ch)
      sheet.rgba[p * 4 + std::size_t(ch)] = static_cast<unsigned char>(
          std::lround(255 * std::clamp(acc[p * 4 + std::size_t(ch)] + (1 - a) * background[ch], 0.0, 1.0)));
    sheet.rgba[p * 4 + 3] = 255;
  }
  return sheet;
}

RgbaImage ReadRgbaPng(const std::string& path) {
  return DecodeRgba(import::ReadDrawingBytes(path, "a drawing", ErrorSource(path)), path);
}

std::vector<unsigned char> EncodePng(const RgbaImage& image, const std::string& file) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = image.width;
  png.height = image.height;
  png.format = PNG_FORMAT_RGBA;
  // Written once into the largest size it can take (the pixels stored, plus
  // the chunks'), not measured by a first encoding and written by a second:
  // an atlas page of 2048 x 2048 took half a second each time.
  png_alloc_size_t size = PNG_IMAGE_PNG_SIZE_MAX(png);
  std::vector<unsigned char> out(size);
  if (!png_image_write_to_memory(&png, out.data(), &size, 0, image.rgba.data(), 0, nullptr))
    throw BakeError(file, std::string("cannot encode PNG: ") + png.message);
  out.resize(size);
  out.shrink_to_fit();  // the largest size is about the pixels' own
  return out;
}

}  // namespace posemorph::bake
