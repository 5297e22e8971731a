// SPDX-License-Identifier: MIT
// The contact sheet drawn with the drawings (`posemorph-bake sheet --textured`):
// each frame rasterised on the CPU, every pixel of a triangle taking each
// pose's drawing at that pose's uvs, blended by the texture weights as the
// viewer's exact cross-fade does, over a light background. A layered
// character's parts are drawn back to front, each with its own drawings, in
// the order of the frame's dominant drawing's pose (as the runtime's
// DrawList orders them). The base poses in the first row, then the sheet's
// grid of pose-space points: ghosting and texture swimming show without a GPU.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "posemorph/draw_list.h"
#include "posemorph/rig.h"
#include "preview.h"

namespace posemorph::bake {

struct RgbaImage {
  std::uint32_t width = 0, height = 0;
  std::vector<unsigned char> rgba;  // straight (not premultiplied) alpha, rows top to bottom
};

// Reads every part's drawing in every pose, part after part (drawings[part *
// N + pose]; a rig without parts is one part, the poses' drawings): references relative to `images`, never leaving
// it ('..', absolute paths, backslashes and control characters are refused),
// regular files of at most 64 MiB and 16,777,216 pixels, each the size its
// pose's canvas records. A rig with an atlas (Rig::has_atlas): each drawing
// cut back out of its page (beside `rig_file`) onto its canvas, transparent
// outside the part of it the rig samples. Throws BakeError naming the rig or the file.
// use_atlas false: the drawings themselves, atlas or not (the ghosting
// measure, which the bake took on them).
std::vector<RgbaImage> ReadPoseDrawings(const Rig& rig, const std::string& rig_file, const std::string& images,
                                        bool use_atlas = true);

struct TexturedSheetLayout {
  std::uint32_t cell = 0;               // pixels per cell side
  std::uint32_t columns = 0, rows = 0;  // rows of the pose-space grid (after the base row)
  double scale = 0;                     // pixels per rig unit
  double centre_x = 0, centre_y = 0;    // rig point at each cell's centre
};

// A character with control channels: each attachment's drawings
// (ReadPoseDrawings of its rig), in attachment order; empty for other rigs.
std::vector<std::vector<RgbaImage>> ReadAttachmentDrawings(const Rig& rig, const std::string& rig_file,
                                                           const std::string& images);

// What every frame of a sheet is drawn with, as DrawListJob's colours and
// part opacities: the character's tint and opacity, and its parts'
// opacities by part index (empty: all 1; the attachments' parts are 1).
struct SheetColour {
  posemorph::Colour colour;
  std::vector<float> part_opacities;
};

// Row 0: the base poses at their points; rows 1..: SheetPoints(columns, rows).
// Over channel `channel`'s pose space (its rig's poses and grid), every
// other channel at its first pose; the attachments drawn with
// `attachment_drawings` (ReadAttachmentDrawings), merged among the body's
// parts by draw order; every part multiplied by `colour` as the viewer's
// shader does (DrawList "Drawing a DrawList", step 4).
RgbaImage TexturedSheet(const Rig& rig, const std::vector<RgbaImage>& drawings, int columns, int rows,
                        const EvalOptions& options, TextureFilter filter, std::uint32_t cell,
                        TexturedSheetLayout* layout = nullptr, std::uint32_t channel = 0,
                        const std::vector<std::vector<RgbaImage>>& attachment_drawings = {},
                        const SheetColour& colour = {});

// A PNG drawing as RGBA: a regular file of at most 64 MiB and 16,777,216
// pixels. Throws BakeError naming the file.
RgbaImage ReadRgbaPng(const std::string& path);

// PNG bytes of an image (libpng's simplified API).
std::vector<unsigned char> EncodePng(const RgbaImage& image, const std::string& file);

}  // namespace posemorph::bake
