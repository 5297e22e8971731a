// SPDX-License-Identifier: MIT
// A rig's texture pages for the GPU (Rig::page): its atlas's pages, or,
// without an atlas, each part's drawing in each pose, found by its
// reference (checked: rig files are hostile input), premultiplied,
// resampled to one size.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "png_io.h"
#include "posemorph/image_reference.h"
#include "posemorph/rig.h"

namespace posemorph::viewer {

// The rig's drawings, premultiplied RGBA8, all resampled to one size.
struct Drawings {
  std::uint32_t width = 0, height = 0;
  std::vector<std::vector<unsigned char>> rgba;  // one per page: layer k is Rig::page(k)
  std::uint32_t pages = 0;
  // A character with control channels (format 1.7): each attachment's own
  // drawings (its part in each of its channel's poses), in attachment order.
  std::vector<Drawings> attachments;
};
// Reads each page: an atlas page from `rig_dir` (the rig file's folder;
// "." when empty), else each part's image in each pose (rig.part_image;
// rig.pose_image for a rig without parts) from `dir`. False with a message
// naming the file when one is missing or unreadable, an atlas page is not
// the size the rig says, or the rig has no uvs. A rig's attachments' pages
// are read from the same folders (the bake records one drawing folder for
// them all, and writes one atlas for the character).
// Limits on the drawings the viewer loads (rig files are hostile input):
// kMaxDrawingPixels (png_io.h) each and as the size they are resampled to,
// and kMaxTexturePixels for all of them (the texture array they share).
constexpr std::uint64_t kMaxTexturePixels = std::uint64_t(1) << 26;  // 256 MiB of RGBA8
// Image references must stay inside `dir`:
// (posemorph/image_reference.h: the runtime's check, which the bake's
// textured contact sheet uses too).
inline bool ImageReferenceStaysInside(const std::string& reference) {
  return posemorph::ImageReferenceStaysInside(StringView{reference.data(), reference.size()});
}
// Control characters as \xNN and at most `max` characters (then "..."):
// names from a rig file or the command line, before they reach a terminal.
std::string Printable(const std::string& text, std::size_t max = 200);
bool LoadDrawings(const Rig& rig, const std::string& dir, Drawings* out, std::string* error,
                  const std::string& rig_dir = "");

}  // namespace posemorph::viewer
