// SPDX-License-Identifier: MIT
// The working level of a drawing: the pyramid level its outline is traced
// and its interior aligned on, so a 4096-pixel drawing costs what a
// 256-pixel one does (mapping's working_size).
#pragma once
#include <string>
#include <vector>

#include "posemorph/bake/error.h"

namespace posemorph::bake::mapping {

// Pyramid level h of an alpha image: pixel (x, y) is the mean (rounded) of
// the drawing's pixels [x 2^h, (x + 1) 2^h) x [y 2^h, (y + 1) 2^h), those
// past the drawing's edge counting as transparent; the level is
// ceil(width / 2^h) x ceil(height / 2^h). Linear in the drawing's pixels.
// h in 0..12 (0 returns the alpha as it is).
std::vector<unsigned char> AlphaAtLevel(const std::vector<unsigned char>& alpha, int width, int height, int halvings,
                                        int* level_width, int* level_height);
// The pyramid level a character's drawings are traced on (mapping's
// working_size): the fewest halvings that bring a width x height drawing's
// longer side to at most working_size pixels (ceil(side / 2^h) <=
// working_size); 0 when working_size is 0 (trace at full resolution).
int WorkingHalvings(int width, int height, int working_size);
// A PNG's size from its header, nothing decoded (the checks of ReadPngAlpha
// on the header). Throws BakeError as ReadPngAlpha does.
void ReadPngSize(const std::string& path, int* width, int* height, const ErrorSource& source);

}  // namespace posemorph::bake::mapping
