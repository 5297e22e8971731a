// SPDX-License-Identifier: MIT
// The last step of a bake from drawings: every drawing of the rig (each
// part in each pose, the attachments' too) packed into a few texture pages
// (runtime/FORMAT.md, ATLS), so that a renderer uploads one texture (or a
// few) per character instead of one per drawing and never switches
// textures between parts. Each drawing is cropped to what the rig samples
// of it (its pixels with any alpha, and its part's uvs in that pose, one
// pixel wider for linear filtering), the crops are packed on shelves
// (tallest first) into the smallest square power-of-two page that holds
// them all, or into pages of the largest size allowed, `padding` pixels
// apart, each crop's edge pixels repeated into half the padding around it
// (bleeding), so that filtering at a crop's edge never picks up a
// neighbour. Pages hold premultiplied RGBA. A drawing several parts or
// poses show is packed once.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "posemorph/bake/rig_sections.h"
#include "posemorph/rig.h"

namespace posemorph::bake {

// The description's "atlas" (RIG_DESCRIPTION.md): false, or the page size
// limit and the padding.
struct AtlasSettings {
  bool enabled = true;
  std::uint32_t max_page_size = 2048;  // pixels, a power of two in 64..16384
  std::uint32_t padding = 2;           // pixels between crops, 0..64
};

// A page: premultiplied RGBA, rows top to bottom; `name` is its file name
// beside the rig (what ATLS records).
struct AtlasPage {
  std::string name;
  std::uint32_t width = 0, height = 0;
  std::vector<unsigned char> rgba;
};

struct PackedAtlas {
  std::vector<unsigned char> rig;  // the rig file with ATLS in it (and in each attachment's rig)
  std::vector<AtlasPage> pages;
  std::uint32_t drawings = 0;        // distinct drawings packed
  std::uint32_t regions = 0;         // parts x poses, over the character's rigs
  double filled = 0;                 // fraction of the pages' pixels the crops cover
  std::uint64_t drawing_pixels = 0;  // the drawings' canvases' pixels together, for comparison
  // Why there is no atlas (a drawing the bake cannot read: a reference given
  // as "image" with a mesh, which the game resolves; drawings too large for
  // the pages); the rest is then empty.
  std::string skipped;
};

// What the rig file `rig` draws, read in one load: `all`, it has uvs and
// canvases and every part of it and of its attachments names a drawing in
// every pose (what an atlas needs; a rig from meshes alone has none);
// `layered`, some part draws a layer of a layered file
// (import/layered_reference.h), which renderers can only read from an atlas.
struct RigDrawings {
  bool all = false, layered = false;
};
RigDrawings ReadRigDrawings(const std::vector<unsigned char>& rig);
// The same of a rig already loaded (the bake's own verification load:
// BakeReport::drawings), which spares a large rig a second load.
RigDrawings ReadRigDrawings(const Rig& rig);

// The pages' file names for a rig written to `rig_file`: its name without
// the extension, then ".page<k>.png".
std::string AtlasPageName(const std::string& rig_file, std::uint32_t page);

// Packs the drawings of the rig in `rig` (a rig file's bytes, written by
// this bake), found in `drawing_folder` (the description's folder: the
// references are relative to it), and returns the rig with an atlas. The
// rig loads and every part's uvs in every pose land inside its region (the
// bake checks both). No atlas, with `skipped` saying why, when a drawing
// cannot be read, a crop does not fit the largest page, or the pages would
// be more than the format allows. Throws BakeError naming `file` and the
// problem: a drawing not its canvas's size, a part or pose without a
// drawing or canvas.
PackedAtlas PackAtlas(const std::vector<unsigned char>& rig, const std::string& rig_file,
                      const std::string& drawing_folder, const AtlasSettings& settings, const std::string& file);

// The rig file `rig` with `top` added to its own sections and `nested[a]`
// to attachment a's rig (the CHAN section rebuilt around the new nested
// rigs); a section of the same tag is replaced. The file is written anew
// (format version of this bake). Throws BakeError naming `file` when the
// bytes are not a rig the runtime reads.
std::vector<unsigned char> AddRigSections(const std::vector<unsigned char>& rig,
                                          const std::vector<RigSections::Section>& top,
                                          const std::vector<std::vector<RigSections::Section>>& nested,
                                          const std::string& file);

}  // namespace posemorph::bake
