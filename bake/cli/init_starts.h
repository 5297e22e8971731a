// SPDX-License-Identifier: MIT
// Where `posemorph-bake init` puts each drawing's start landmark: a point
// every drawing shares. First its outline's lowest point (where a character
// stands), or where the outlines' bends put the start instead; where
// neither bakes (a walk whose lowest point lies on another foot in each
// frame), the outline's topmost, leftmost or rightmost point (a head, a
// nose, a tail), tried in the order the outlines' bends agree with them.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "posemorph/bake/map_drawings.h"

namespace posemorph::bake::cli {

enum class OutlineSide { kBottom, kTop, kLeft, kRight };

// "lowest", "topmost", "leftmost", "rightmost".
const char* SideName(OutlineSide side);

// Each traced pose's extreme outline point toward `side` (drawing pixels, y
// down): of the points within half a pixel of the extreme, the one nearest
// the middle of that flat side.
std::vector<std::array<double, 2>> SidePoints(const DrawnOutlines& traced, OutlineSide side);

// The lowest points; where the matching is unsure of one (the outline's
// bends agree clearly better with another start, more than an eighth of the
// way round from it: a character that stands on the other foot, or does
// not stand), `suggested` gets the start where they agree best with the
// first pose's, and `moved` says which poses (both empty when none is unsure).
std::vector<std::array<double, 2>> StartPoints(const DrawnOutlines& traced,
                                               std::vector<std::array<double, 2>>* suggested,
                                               std::vector<std::string>* moved);

// The top, left and right, the side whose points the outlines' bends agree
// with best first: the fewest poses whose start seems to sit elsewhere
// (StartAlignment::Misplaced), then the least bend difference at the starts.
std::vector<OutlineSide> OtherSidesByAgreement(const DrawnOutlines& traced);

}  // namespace posemorph::bake::cli
