// SPDX-License-Identifier: MIT
#include "drawings.h"

#include <algorithm>
#include <cstdio>

namespace posemorph::viewer {

std::string Printable(const std::string& text, std::size_t max) {
  std::string out;
  for (unsigned char c : text.substr(0, max)) {
    if (c < 0x20 || c == 0x7F) {
      char hex[8];
      std::snprintf(hex, sizeof(hex), "\\x%02x", c);
      out += hex;
    } else {
      out += char(c);
    }
  }
  return text.size() > max ? out + "..." : out;
}

namespace {

bool TooMany(std::uint32_t parts, std::uint32_t poses, std::string* error) {
  *error = "the drawings (" + (parts > 1 ? std::to_string(parts) + " parts in " : std::string()) +
           std::to_string(poses) + " poses) would share a texture array of more than " +
           std::to_string(kMaxTexturePixels) + " pixels in all; draw them smaller";
  return false;
}

}  // namespace

bool LoadDrawings(const Rig& rig, const std::string& dir, Drawings* out, std::string* error,
                  const std::string& rig_dir) {
  const std::uint32_t N = rig.pose_count(), P = rig.part_count(), K = rig.page_count();
  if (rig.uvs(0).size == 0) {
    *error = "the rig has no uvs, so there is nothing to draw its drawings with (bake it from drawings)";
    return false;
  }
  // Layer k: page k (an atlas page, beside the rig; or, without an atlas,
  // part p's drawing in pose i for k = p * N + i, in the drawing folder).
  std::uint64_t read_pixels = 0;
  std::vector<std::vector<unsigned char>> images(K);
  std::vector<std::uint32_t> w(K), h(K);
  for (std::uint32_t k = 0; k < K; ++k) {
    const TexturePage page = rig.page(k);
    const std::uint32_t p = k / N, i = k % N;
    const StringView part_name = rig.part(p).name;
    const std::string which =
        page.atlas ? "atlas page " + std::to_string(k)
                   : (P > 1 ? "part '" + Printable(std::string(part_name.data, part_name.size)) + "', " : "") +
                         "pose " + std::to_string(i);
    if (page.name.size == 0) {
      *error = which + " has no image reference";
      return false;
    }
    const std::string reference(page.name.data, page.name.size);
    if (!ImageReferenceStaysInside(reference)) {
      *error = which + ": image reference '" + Printable(reference) +
               "' leaves the images folder (absolute, '..', or a control character); refusing to open it";
      return false;
    }
    const std::string path = (page.atlas ? (rig_dir.empty() ? "." : rig_dir) : dir) + "/" + reference;
    if (!ReadPng(path, &images[k], &w[k], &h[k], error)) return false;
    if (page.atlas && (w[k] != page.width || h[k] != page.height)) {
      *error = path + ": the atlas page is " + std::to_string(w[k]) + "x" + std::to_string(h[k]) + ", the rig says " +
               std::to_string(page.width) + "x" + std::to_string(page.height) + " (bake the rig again)";
      return false;
    }
    read_pixels += std::uint64_t(w[k]) * h[k];
    if (read_pixels > kMaxTexturePixels) return TooMany(P, N, error);
  }
  const bool premultiplied = K > 0 && rig.page(0).premultiplied;
  out->pages = K;
  out->width = *std::max_element(w.begin(), w.end());
  out->height = *std::max_element(h.begin(), h.end());
  // All drawings are resampled to one size for the texture array: drawings
  // of very different shapes (8192 x 1 and 1 x 8192) must not make it huge.
  if (std::uint64_t(out->width) * out->height > kMaxDrawingPixels) {
    *error = "the drawings (" + std::to_string(out->width) + " wide, " + std::to_string(out->height) +
             " high at most) would share a texture of more than " + std::to_string(kMaxDrawingPixels) +
             " pixels; draw the poses on canvases of one size";
    return false;
  }
  if (std::uint64_t(out->width) * out->height * images.size() > kMaxTexturePixels) return TooMany(P, N, error);
  out->rgba.assign(images.size(), std::vector<unsigned char>(std::size_t(out->width) * out->height * 4));
  for (std::size_t i = 0; i < images.size(); ++i)
    for (std::uint32_t y = 0; y < out->height; ++y)
      for (std::uint32_t x = 0; x < out->width; ++x) {
        // Nearest resampling to the common size (uvs are relative, so they still fit).
        const std::uint32_t sx = x * w[i] / out->width, sy = y * h[i] / out->height;
        const unsigned char* s = &images[i][(std::size_t(sy) * w[i] + sx) * 4];
        unsigned char* d = &out->rgba[i][(std::size_t(y) * out->width + x) * 4];
        for (int c = 0; c < 3; ++c) d[c] = premultiplied ? s[c] : (unsigned char)((s[c] * s[3] + 127) / 255);
        d[3] = s[3];
      }
  out->attachments.assign(rig.attachment_count(), Drawings{});
  for (std::uint32_t a = 0; a < rig.attachment_count(); ++a)
    if (!LoadDrawings(*rig.attachment(a).rig, dir, &out->attachments[a], error, rig_dir)) {
      const StringView name = rig.attachment(a).rig->part(0).name;
      *error = "attachment '" + Printable(std::string(name.data, name.size)) + "': " + *error;
      return false;
    }
  return true;
}

}  // namespace posemorph::viewer
