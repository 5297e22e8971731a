// SPDX-License-Identifier: MIT
// When no outward push encloses a span of the corresponded boundary (a
// pixel-art outline's hair-thin notch, a narrow gap), the enclosing
// simplification splits spans and tries again (enclosing_simplification.cpp).
// New corresponding points go in every pose at the same share of the span's
// arc length, so the correspondence keeps its order, and never beyond
// kMaxMatchedSamples points in all.
#pragma once
#include <cstddef>
#include <vector>

#include "posemorph/bake/mapping/boundary_matching.h"

namespace posemorph::bake::mapping {

// Splits the span of every edge in `edges` (indices among the M points) of
// pose i in two, at the outline vertex farthest outside the edge in pose i.
// False when no span could be split.
bool SplitSpans(const std::vector<Polygon>& outlines, std::size_t i, std::vector<std::size_t> edges,
                CorrespondedBoundary& b);

// Splits, in every pose, each span whose outline stands farther than
// `deviation` outside or inside its chord, for a few rounds; whether
// anything was split.
bool SplitDeviating(const std::vector<Polygon>& outlines, double deviation, CorrespondedBoundary& b);

}  // namespace posemorph::bake::mapping
