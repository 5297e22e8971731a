// SPDX-License-Identifier: MIT
// init's start landmarks (init_starts.h): outline extremes, checked against
// the outlines' bends.
#include "init_starts.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "layered_description.h"
#include "posemorph/bake/mapping/boundary_matching.h"

namespace posemorph::bake::cli {
namespace {

// In rig orientation (y up) the traced outlines, counter-clockwise as seen,
// are counter-clockwise as AlignStart takes them.
mapping::Polygon Flipped(const std::vector<Eigen::Vector2d>& points) {
  mapping::Polygon p;
  for (const Eigen::Vector2d& q : points) p.emplace_back(q.x(), -q.y());
  return p;
}

// Pose k's start against pose 0's, as the matching would align them.
mapping::StartAlignment Alignment(const DrawnOutlines& traced, const std::vector<std::array<double, 2>>& at,
                                  std::size_t k) {
  return mapping::AlignStart(Flipped(traced.poses[0].traced), {at[0][0], -at[0][1]}, Flipped(traced.poses[k].traced),
                             {at[k][0], -at[k][1]});
}

}  // namespace

const char* SideName(OutlineSide side) {
  switch (side) {
    case OutlineSide::kBottom:
      return "lowest";
    case OutlineSide::kTop:
      return "topmost";
    case OutlineSide::kLeft:
      return "leftmost";
    case OutlineSide::kRight:
      return "rightmost";
  }
  return "";
}

std::vector<std::array<double, 2>> SidePoints(const DrawnOutlines& traced, OutlineSide side) {
  // Along `axis`, toward larger values when `larger`: the bottom is the
  // largest y (drawing pixels, y down).
  const int axis = side == OutlineSide::kBottom || side == OutlineSide::kTop ? 1 : 0;
  const bool larger = side == OutlineSide::kBottom || side == OutlineSide::kRight;
  std::vector<std::array<double, 2>> out;
  for (const DrawnPoseOutline& pose : traced.poses) {
    const std::vector<Eigen::Vector2d>& outline = pose.traced;
    double extreme = larger ? -1e300 : 1e300;
    for (const Eigen::Vector2d& p : outline) extreme = larger ? std::max(extreme, p[axis]) : std::min(extreme, p[axis]);
    double lo = 1e300, hi = -1e300;  // the flat side's extent across the axis
    for (const Eigen::Vector2d& p : outline)
      if (std::abs(p[axis] - extreme) <= 0.5) lo = std::min(lo, p[1 - axis]), hi = std::max(hi, p[1 - axis]);
    const double mid = (lo + hi) / 2;
    std::array<double, 2> best{0, 0};
    double best_d = 1e300;
    for (const Eigen::Vector2d& p : outline)
      if (std::abs(p[axis] - extreme) <= 0.5 && std::abs(p[1 - axis] - mid) < best_d)
        best_d = std::abs(p[1 - axis] - mid), best = {p.x(), p.y()};
    out.push_back(best);
  }
  return out;
}

std::vector<std::array<double, 2>> StartPoints(const DrawnOutlines& traced,
                                               std::vector<std::array<double, 2>>* suggested,
                                               std::vector<std::string>* moved) {
  const std::vector<std::array<double, 2>> out = SidePoints(traced, OutlineSide::kBottom);
  *suggested = out;
  for (std::size_t k = 1; k < out.size(); ++k) {
    const mapping::StartAlignment a = Alignment(traced, out, k);
    if (!a.Misplaced()) continue;
    const mapping::Point at = mapping::PointAtArcLength(Flipped(traced.poses[k].traced), a.best_start);
    moved->push_back(traced.poses[k].label + ": from its lowest point (" + Coordinate(out[k][0]) + ", " +
                     Coordinate(out[k][1]) + ") to (" + Coordinate(at.x()) + ", " + Coordinate(-at.y()) +
                     "), where its outline's bends agree with the first pose's");
    (*suggested)[k] = {at.x(), -at.y()};
  }
  if (moved->empty()) suggested->clear();
  return out;
}

std::vector<OutlineSide> OtherSidesByAgreement(const DrawnOutlines& traced) {
  std::vector<std::pair<std::pair<int, double>, OutlineSide>> scored;
  for (OutlineSide side : {OutlineSide::kTop, OutlineSide::kLeft, OutlineSide::kRight}) {
    const std::vector<std::array<double, 2>> at = SidePoints(traced, side);
    int misplaced = 0;
    double difference = 0;
    for (std::size_t k = 1; k < at.size(); ++k) {
      const mapping::StartAlignment a = Alignment(traced, at, k);
      misplaced += a.Misplaced() ? 1 : 0;
      difference += a.cost_at_start;
    }
    scored.push_back({{misplaced, difference}, side});
  }
  std::stable_sort(scored.begin(), scored.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<OutlineSide> out;
  for (const auto& s : scored) out.push_back(s.second);
  return out;
}

}  // namespace posemorph::bake::cli
