// SPDX-License-Identifier: MIT
// Interior regions: the patches of flat colour drawn inside a character (an
// eye, a mouth, a cheek, a belly patch), found in each drawing and matched
// between poses, so that the interior alignment (interior_alignment.h) knows
// where each one went before it descends on the colours (issue "Interior
// correspondence", docs/DESIGN.md section 7).
//
// Why: the alignment's Gauss-Newton descent is local. When a face slides by
// half the distance between its eyes, the left eye of one drawing lies as
// near the right eye of the other as its own, and the descent settles
// between them. A region is found whole in each drawing, so matching them is
// not local: the poses' regions are paired under the one shift (of the
// outlines' mapping's prediction) that pairs the most of them, the way a
// person would see that the whole face moved.
#pragma once
#include <cstdint>
#include <vector>

#include "posemorph/bake/mapping/interior_alignment.h"

namespace posemorph::bake::mapping {

// A region: 4-connected opaque pixels of one flat colour (each within
// `colour_tolerance` of the first found, per premultiplied channel) that
// touches neither the drawing's edge nor a pixel less than half opaque,
// whose edge is sharp (at least half its outside neighbours differ by more
// than twice the tolerance: a band of a smooth gradient is no region), not
// too small or too large (RegionParameters), and not itself inside the
// holes of another region (a pupil inside an eye's white: the eye is the
// region). Its centre is the centroid of the region with its holes filled.
struct InteriorRegion {
  Eigen::Vector2d centre;  // drawing pixels (the image's)
  double area = 0;         // pixels, holes filled
  double colour[4] = {};   // premultiplied RGBA, the mean over its own pixels
};

struct RegionParameters {
  double colour_tolerance = 0.06;  // per channel, of 1
  // Bounds on a region's area (holes filled) as shares of the shape's opaque
  // area: smaller ones are lines and anti-aliasing, larger ones the body.
  double min_share = 0.0015, max_share = 0.12;
  // Two regions may pair when their colours differ by at most this per
  // channel and their areas by at most area_ratio times.
  double match_colour = 0.12, area_ratio = 2.0;
  // A pair's centres must agree within this share of the square root of the
  // shape's area, after the shift.
  double match_radius_share = 0.08;
};

// The regions of one drawing, largest first (by their own pixels; ties in
// scan order of their first pixel). Of the regions grown, at most the 64
// largest are considered: time and memory stay a small multiple of the
// drawing's pixels.
std::vector<InteriorRegion> FindInteriorRegions(const AlignmentImage& image, const RegionParameters& parameters = {});

// A region of pose 0 and where it went in pose k.
struct RegionMatch {
  std::size_t reference = 0;  // its index among pose 0's regions
  Eigen::Vector2d from, to;   // pose 0's drawing pixels, pose k's drawing pixels
  double area = 0;
};

// Pairs pose 0's regions with pose k's. `predicted[i]` is where the
// outlines' mapping puts region i of pose 0 in pose k (the caller maps it
// through the meshes; NaN when it lies outside pose 0's mesh: not paired).
// Every shift that pairs one region with a compatible one is tried, each
// refined once by the mean displacement of what it pairs; the pairs of the
// shift pairing the most area (then the least shift) are returned, each
// region used once.
std::vector<RegionMatch> MatchInteriorRegions(const std::vector<InteriorRegion>& reference,
                                              const std::vector<Eigen::Vector2d>& predicted,
                                              const std::vector<InteriorRegion>& regions, double shape_area,
                                              const RegionParameters& parameters = {});

// The opaque area (pixels at least half opaque) of a drawing.
double OpaqueArea(const AlignmentImage& image);

}  // namespace posemorph::bake::mapping
