// SPDX-License-Identifier: MIT
// Layered files' drawings written as PNGs (import_command.cpp), shared by
// `posemorph-bake import` and `posemorph-bake init`.
#pragma once
#include <ostream>
#include <string>
#include <vector>

#include "posemorph/bake/import/layered_character.h"

namespace posemorph::bake::cli {

// Writes every drawing of `c` into `folder` as c.FileName(pose, part), each
// atomically, after all are encoded (a file that cannot be read or breaks
// the convention writes nothing). Existing files are replaced only with
// `overwrite`; otherwise the first one found is refused before anything is
// written. Returns the paths written, in the character's order; each note
// goes to `warnings` as one line.
std::vector<std::string> WriteLayeredCharacter(const import::LayeredCharacter& c, const std::string& folder,
                                               bool overwrite, std::ostream& warnings);

}  // namespace posemorph::bake::cli
