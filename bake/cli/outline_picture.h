// SPDX-License-Identifier: MIT
// `posemorph-bake outline`'s picture of one drawn pose: the drawing scaled
// up with nearest filtering over a checkerboard (so its alpha shows), the
// outline the bake traced (cyan), the simplified boundary it meshes (magenta,
// vertices dotted) with the mesh inside (grey), each landmark as given
// (numbered red disc) inside a ring of the landmark distance tolerance, the
// point it was placed at on the outline (white), and the start landmark in
// green with an arrow along the outline in the landmarks' order
// (counter-clockwise as seen).
#pragma once
#include <cstdint>

#include "posemorph/bake/map_drawings.h"
#include "textured_sheet.h"

namespace posemorph::bake {

// The picture covers the drawing's canvas, or, when `drawing` is empty (an
// SVG drawing or a given outline), the box around the outline and landmarks
// grown by a tenth. Pixels per drawing unit: the longer side about 640
// pixels, 1 to 16 (returned in *scale).
RgbaImage OutlinePicture(const DrawnPoseOutline& pose, const Triangles& triangles, const RgbaImage& drawing,
                         int* scale = nullptr);

}  // namespace posemorph::bake
