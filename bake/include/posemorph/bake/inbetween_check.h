// SPDX-License-Identifier: MIT
// The bake checks in-betweens, not only the poses (issue 13): it evaluates the
// baked rig with the runtime at points sampled over the pose points' convex
// hull (a grid, the hull's edges, the segment between every two poses) and
// along every path, and measures each triangle's signed area in every frame
// against the smallest area that triangle has in any pose. A ratio at or
// below 0 is a fold: the triangle turned over (or collapsed) between poses.
// Inside the hull the rig blends its poses, and a fold there fails the bake
// (unless allowed); a path may leave the hull to extrapolate, and a fold only
// found there is a warning.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "posemorph/rig.h"

namespace posemorph::bake {

struct InbetweenFold {
  std::uint32_t triangle = 0;
  double area_ratio = 0;     // the most inverted the triangle gets (<= 0)
  Eigen::Vector2d at{0, 0};  // the pose-space point where it does
  std::int32_t path = -1;    // the path that point lies on, or -1
  bool in_hull = true;       // the point is inside the pose points' convex hull
};

struct InbetweenCheck {
  std::size_t frames = 0;     // frames evaluated
  int grid = 0;               // grid cells per side of the pose points' bounding box
  double min_area_ratio = 0;  // over the frames in the hull (pose points and paths inside it included)
  Eigen::Vector2d min_at{0, 0};
  std::uint32_t min_triangle = 0;
  // One per folded triangle: those folding inside the hull first (where
  // they fold most), then those folding only on paths outside it; the most
  // inverted first in each group.
  std::vector<InbetweenFold> folds;
  std::size_t FoldsInHull() const {
    std::size_t n = 0;
    while (n < folds.size() && folds[n].in_hull) ++n;
    return n;
  }
  double seconds = 0;
};

// Samples: a 64-cell grid, 64 parts per hull edge and per pair of poses, 201
// frames per path; all of them shrink together (to 2) while frames x
// vertices exceeds max_work. Throws BakeError(file) if the rig does not
// evaluate.
InbetweenCheck CheckInbetweens(const Rig& rig, const std::string& file, double max_work = 2e7);

// One line about a fold: where, the poses that weigh most there, how far the
// triangle turns over, and the triangle's centre in each of those poses'
// drawings (landmark coordinates), where a landmark would hold it.
std::string DescribeFold(const Rig& rig, const InbetweenFold& fold);

}  // namespace posemorph::bake
