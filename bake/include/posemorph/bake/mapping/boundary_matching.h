// SPDX-License-Identifier: MIT
// Stage 2 of N-way mapping: dense corresponding points on every pose's outline, by dynamic programming between
// landmarks (paper section 3.1).
#pragma once
#include <algorithm>
#include <vector>

#include "posemorph/bake/mapping/polygon.h"

namespace posemorph::bake::mapping {

struct MatchingParameters {
  double spacing = 1.0;        // arc length between samples on pose 0's outline
  double stretch_cost = 0.05;  // per unmatched step, against bending differences in radians
  int bending_scale = 3;       // turning angle measured over +-this many samples
  // Each matched position averaged with up to this many neighbours on each
  // side, within its stretch between landmarks (0: as matched). The
  // matching by bending alone can advance many samples on one outline for
  // one on the other (a limb against the body in one pose, away from it in
  // another), a squeeze no triangle at that boundary survives; averaging
  // spreads it over its neighbours.
  int smoothing = 0;
};
struct CorrespondedBoundary {
  std::vector<Polygon> points;          // per pose, M corresponding points on its outline
  std::vector<std::vector<double>> at;  // per pose, their arc-length positions (from the outline's vertex 0)
  std::vector<std::size_t> landmarks;   // index of each landmark among the M points
  double spacing = 0;                   // the spacing used: parameters.spacing, or more on long outlines
};
// outlines: CCW; landmarks[i][k]: the k-th user point of pose i (the first is
// the start point), already on outline i. Pose 0 is the parameter domain.
CorrespondedBoundary MatchBoundaries(const std::vector<Polygon>& outlines,
                                     const std::vector<std::vector<Point>>& landmarks,
                                     const MatchingParameters& parameters);
// Whether a pose's start point sits where pose 0's does, judged by the
// outlines' turning angles alone (256 samples round each, from its start
// point): the shift of the other outline's start (a share of its perimeter,
// counter-clockwise, in [0, 1)) at which it matches pose 0's best, that
// start's arc length on `outline`, the mean turning-angle difference there,
// and with no shift. A start point placed on
// a different feature than pose 0's makes the in-betweens spin.
struct StartAlignment {
  double best_shift = 0, best_start = 0, best_cost = 0, cost_at_start = 0;
  // The start seems to sit on another part of the outline than pose 0's:
  // the bends agree clearly better more than an eighth of the way round.
  bool Misplaced() const { return std::min(best_shift, 1 - best_shift) > 0.125 && best_cost < 0.8 * cost_at_start; }
};
StartAlignment AlignStart(const Polygon& outline0, const Point& start0, const Polygon& outline, const Point& start);
// Arc length from vertex 0 at each vertex, closing edge included (size n + 1; the last is the perimeter).
std::vector<double> CumulativeArcLength(const Polygon& outline);
// Where on `outline` (arc length from vertex 0) the point nearest q lies, and how far it is.
double NearestArcLength(const Polygon& outline, const Point& q, double* distance);
Point PointAtArcLength(const Polygon& outline, double s);

}  // namespace posemorph::bake::mapping
