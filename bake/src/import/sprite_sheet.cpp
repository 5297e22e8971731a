// SPDX-License-Identifier: MIT
// A sprite sheet cut into its frames (sprite_sheet.h).
#include "posemorph/bake/import/sprite_sheet.h"

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include "posemorph/bake/error.h"
#include "posemorph/bake/mapping/outline_image.h"

namespace posemorph::bake::import {

LayeredCharacter ImportSpriteSheet(const std::string& path, const SheetCut& cut, const std::string& name) {
  const bool by_count = cut.columns > 0 && cut.rows > 0, by_size = cut.cell_width > 0 && cut.cell_height > 0;
  if (by_count == by_size)
    throw BakeError(path,
                    "a sprite sheet is cut by its columns and rows or by its cells' size in pixels (one of the two)");
  int width = 0, height = 0;
  const std::vector<unsigned char> rgba = mapping::ReadPngRgba(path, &width, &height, ErrorSource(path));
  const int columns = by_count ? cut.columns : width / cut.cell_width;
  const int rows = by_count ? cut.rows : height / cut.cell_height;
  const int cw = by_count ? width / std::max(columns, 1) : cut.cell_width;
  const int ch = by_count ? height / std::max(rows, 1) : cut.cell_height;
  auto size = [](int w, int h) { return std::to_string(w) + " x " + std::to_string(h); };
  if (columns < 1 || rows < 1 || cw < 1 || ch < 1 || columns * cw != width || rows * ch != height)
    throw BakeError(path, "a sheet of " + size(width, height) + " pixels does not divide into " +
                              (by_count ? size(columns, rows) + " cells"
                                        : "cells of " + size(cut.cell_width, cut.cell_height) + " pixels") +
                              ": give columns x rows (--frames) or a cell size (--cell) that divide it exactly");
  LayeredCharacter c;
  c.width = cw, c.height = ch;
  const std::size_t cells = std::size_t(columns) * std::size_t(rows);
  const std::string digits = std::to_string(cells - 1);
  const std::string stem = SafeName(name, false);
  std::size_t frame = 0;
  for (int r = 0; r < rows; ++r)
    for (int k = 0; k < columns; ++k) {
      // The cell's rows, each a run of cw pixels in the sheet's row.
      const std::size_t row_bytes = std::size_t(cw) * 4;
      std::vector<unsigned char> cell(row_bytes * std::size_t(ch));
      for (int y = 0; y < ch; ++y) {
        const std::size_t from = ((std::size_t(r) * std::size_t(ch) + std::size_t(y)) * std::size_t(width) +
                                  std::size_t(k) * std::size_t(cw)) *
                                 4;
        std::copy_n(rgba.begin() + std::ptrdiff_t(from), row_bytes, cell.begin() + std::ptrdiff_t(y * row_bytes));
      }
      bool drawn = false;
      for (std::size_t p = 3; p < cell.size() && !drawn; p += 4) drawn = cell[p] > 0;
      const std::string where = "cell (column " + std::to_string(k) + ", row " + std::to_string(r) + ") at (" +
                                std::to_string(k * cw) + ", " + std::to_string(r * ch) + ")";
      if (!drawn) {
        c.notes.push_back(path + ": " + where + " is empty (no pixel above zero alpha): no frame made of it");
        continue;
      }
      std::string number = std::to_string(frame++);
      number.insert(0, digits.size() - number.size(), '0');
      c.poses.push_back(stem + "_" + number);
      c.drawings.push_back(std::move(cell));
      c.sources.push_back(path + ": " + where);
    }
  if (c.poses.empty()) throw BakeError(path, "every cell of the sheet is empty (no pixel above zero alpha)");
  return c;
}

}  // namespace posemorph::bake::import
