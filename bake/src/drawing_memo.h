// SPDX-License-Identifier: MIT
// The decoded-drawing memo of the mapping (drawing_memo.cpp): a PNG
// drawing's traced outline, its alignment image and its copy for the
// ghosting measure, kept by the drawing's
// exact bytes and the settings they were made with. A bake maps the same
// drawings again and again (the fold retries, further refinement, each
// part and channel), and at 4096 pixels decoding a drawing and finding its
// drop shadow cost more than the mapping on the working level. The bytes
// are compared exactly (no hash stands in for them), so a drawing
// rewritten between two bakes of one process is read again. At most 64
// values and 64 MB of drawings are kept per memo (the oldest go first);
// thread-safe. Internal to the bake.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "posemorph/bake/error.h"
#include "posemorph/bake/mapping/interior_alignment.h"
#include "posemorph/bake/mapping/outline_image.h"
#include "posemorph/bake/rig_description.h"

namespace posemorph::bake {

// OutlineFromPngBytes of the drawing at `path` with the mapping's alpha
// threshold, notch filling and drop-shadow settings, traced on pyramid
// level `halvings`. Throws BakeError as `source` says.
mapping::ImageOutline TraceOutline(const std::string& path, const MappingParameters& parameters, int halvings,
                                   const ErrorSource& source);
// AlignmentImageFromRgba of the drawing at `path` on pyramid level
// `halvings`. Throws BakeError as `source` says.
mapping::AlignmentImage AlignmentImageOf(const std::string& path, int halvings, const ErrorSource& source);
// The drawing at `path` halved to at most 512 px (ReduceDrawing, ghosting.h),
// premultiplied means, straight alpha: what the ghosting measure samples.
// Throws BakeError as `source` says.
std::vector<unsigned char> GhostingDrawingOf(const std::string& path, const ErrorSource& source, std::uint32_t* width,
                                             std::uint32_t* height);

}  // namespace posemorph::bake
