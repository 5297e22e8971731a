// SPDX-License-Identifier: MIT
// Layered files' drawings written as PNGs (import_command.cpp), shared by
// `posemorph-bake import` and `posemorph-bake init`.
#pragma once
#include <ostream>
#include <string>
#include <vector>

#include "posemorph/bake/import/layered_character.h"

namespace posemorph::bake::cli {

// import::WriteLayeredDrawings, each of the character's notes first going to
// `warnings` as one line.
std::vector<std::string> WriteLayeredCharacter(const import::LayeredCharacter& c, const std::string& folder,
                                               bool overwrite, std::ostream& warnings);

}  // namespace posemorph::bake::cli
