// SPDX-License-Identifier: MIT
// A sprite sheet as a character's drawings: games keep a character's frames
// side by side in one PNG, in a grid of equal cells (tuxtype, mrrescue,
// gnujump and most engines' sheets). Cut into one PNG per frame, the frames
// are what `posemorph-bake init` takes (docs/bake.md, "Sprite sheets").
#pragma once
#include <string>

#include "posemorph/bake/import/layered_character.h"

namespace posemorph::bake::import {

// How the sheet is cut: `columns` x `rows` cells, or cells of `cell_width`
// x `cell_height` pixels (exactly one of the two given, the other zero).
struct SheetCut {
  int columns = 0, rows = 0;
  int cell_width = 0, cell_height = 0;
};

// The frames of the PNG at `path`, read left to right and top to bottom: a
// character of one drawing per frame (no parts), pose `name`_K for the
// K-th frame (K from 0, zero-padded to one width, so the files sort in the
// sheet's order), each the whole of its cell, so every frame keeps the
// sheet's registration: the character stands in each drawing where it
// stands in its cell. A cell with no pixel above zero alpha is left out,
// with a note (a sheet's last row is often part empty). `name` is made a
// file name as layered_character.h makes pose names ('-', which init reads
// as the pose-part split, turns into '_').
// Throws BakeError naming the file when it cannot be read, has no alpha,
// does not divide into the cells asked for (saying its size and the cell
// size), or has no frame that is not empty.
LayeredCharacter ImportSpriteSheet(const std::string& path, const SheetCut& cut, const std::string& name);

}  // namespace posemorph::bake::import
