// SPDX-License-Identifier: MIT
// A character's drawings from layered files (layered_image.h), by one of two
// conventions, both in bake/RIG_DESCRIPTION.md ("Layered files"):
//   one file of poses: a single file whose visible top-level entries are
//     all groups, two or more: one group per pose, named by the group; their
//     visible children (layers or groups) are the parts;
//   one file per pose (any other files): the pose is named by the file's
//     stem, its parts are the file's visible top-level layers or groups (a
//     group is one part, its layers composited), by name.
// With `flatten`, or when every pose has a single visible entry, a pose is
// one drawing (everything visible composited) and the character has no
// parts. Every part must be drawn in every pose; hidden entries are left out
// with a note. A name's trailing " #N" is dropped (GIMP appends it to keep
// layer names unique in an image, so a second pose's "mouth" is "mouth #1").
// Names become file names: every character but letters,
// digits, '_' and '.' (and, in part names, '-') turns into '_', so a pose
// and its part make the file name POSE-PART.png that `posemorph-bake init`
// splits at its first '-'.
#pragma once
#include <string>
#include <vector>

namespace posemorph::bake::import {

struct LayeredCharacter {
  int width = 0, height = 0;              // the canvas every drawing shares
  std::vector<std::string> poses, parts;  // parts empty: one drawing per pose
  // [pose * max(1, parts) + part]: straight-alpha RGBA of the canvas.
  std::vector<std::vector<unsigned char>> drawings;
  std::vector<std::string> sources;  // where each drawing came from: "FILE: layer 'NAME'"
  std::vector<std::string> notes;    // the files' notes, then the import's own
  // The file name a drawing is written to: POSE-PART.png, or POSE.png.
  std::string FileName(std::size_t pose, std::size_t part) const;
};

// A name as a file name, as above: characters but letters, digits, '_',
// '.' (not first) and, with `dash`, '-' (not first) turn into '_'; a
// trailing " #N" is dropped; an empty name is "layer".
std::string SafeName(const std::string& name, bool dash);

// Throws BakeError naming the file (and the layer or group) that breaks the
// convention, or that cannot be read (layered_image.h).
LayeredCharacter ImportLayeredCharacter(const std::vector<std::string>& paths, bool flatten);

// Writes every drawing of `c` into `folder` as a PNG named c.FileName(pose,
// part), each atomically, after all are encoded (nothing is written when
// one cannot be). A file that already holds those very bytes is left as it
// is (its time too, so a watcher sees no change); another existing file is
// replaced only with `overwrite`, else refused (BakeError) before anything
// is written. Returns the paths, in the character's order.
std::vector<std::string> WriteLayeredDrawings(const LayeredCharacter& c, const std::string& folder, bool overwrite);

// A description's "import" done again into `folder` (the description's):
// the files as one character (by the two conventions), or with `channels`
// each file as one (init --channels); their notes appended to `notes`.
// Returns the paths written or kept, as WriteLayeredDrawings does.
std::vector<std::string> ImportAgain(const std::vector<std::string>& files, bool channels, bool flatten,
                                     const std::string& folder, std::vector<std::string>* notes);

}  // namespace posemorph::bake::import
