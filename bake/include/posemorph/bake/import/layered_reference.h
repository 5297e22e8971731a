// SPDX-License-Identifier: MIT
// A description's drawing may name a layer of a layered file instead of a
// PNG (RIG_DESCRIPTION.md, "drawing"):
//   NAME.ora, NAME.psd            the whole file, its visible layers composited
//   NAME.ora#Group/Layer, ...#L   the layer or group at that path of names
//                                 from the top level ('/' between names; a
//                                 name holding '/' or '#' cannot be named;
//                                 "body" also finds "body #1", the copy
//                                 number GIMP and Krita append)
// Its pixels are the layer composited onto the file's canvas, as
// `posemorph-bake import` would write it, so such a drawing maps, aligns and
// packs into the atlas exactly as that PNG does. Renderers read it from the
// rig's atlas (a rig that names one needs an atlas: the bake says so).
#pragma once
#include <string>
#include <vector>

#include "posemorph/bake/error.h"

namespace posemorph::bake::import {

struct LayeredReference {
  std::string file;               // the layered file's path (all before '#')
  std::vector<std::string> path;  // the names after '#', top level first; empty: the whole file
};

// True, with *out filled, when `reference` names a layered file (.ora or
// .psd, any case, possibly followed by '#' and a path).
bool ParseLayeredReference(const std::string& reference, LayeredReference* out = nullptr);

// The drawing a layered reference names, as PNG bytes. The file is read once
// per process while its size and modification time stay the same. Throws
// BakeError (named by `source`) when the file cannot be read (layered_image.h),
// or a name of the path is not there (the message lists the names there are).
std::vector<unsigned char> LayeredReferencePng(const std::string& reference, const ErrorSource& source);

// A PNG drawing's bytes (ReadInputFile within kMaxTextFileBytes), or a
// layered reference's (LayeredReferencePng): what every PNG reader of the
// bake reads a drawing with.
std::vector<unsigned char> ReadDrawingBytes(const std::string& path, const std::string& what,
                                            const ErrorSource& source);

}  // namespace posemorph::bake::import
