// SPDX-License-Identifier: MIT
// Compatible refinement of N triangle meshes with one connectivity
// (compatible_refinement.h): the order of the Refiner's steps (refiner.h).
#include <algorithm>
#include <cmath>
#include <utility>

#include "refiner.h"

namespace posemorph::bake::mapping {
namespace {

using refine::MinAngleOf;
using refine::Refiner;

// Rounds of splitting the longest edge of bad triangles, then flips and
// smoothing; with `collapse`, each round first removes the boundary vertices
// that make slivers (Refiner::CollapseBoundarySlivers).
void RefineRounds(Refiner& r, const CompatibleMesh& mesh, const RefinementParameters& prm, bool collapse) {
  const double goal = prm.min_angle_goal * M_PI / 180;
  const double min_length = prm.max_edge_length > 0 ? prm.max_edge_length / 4 : 0;
  for (int round = 0; round < prm.rounds; ++round) {
    if (MinAngleDegrees(mesh) >= prm.min_angle_goal) break;
    const int collapsed = collapse ? r.CollapseBoundarySlivers(goal, prm.max_collapse_distance) : 0;
    if (r.SplitBad(goal, min_length) == 0 && collapsed == 0) break;
    r.Flip();
    r.Smooth(24);
    r.Flip();
  }
}

}  // namespace

bool RefineCompatibly(CompatibleMesh& mesh, const RefinementParameters& prm) {
  Refiner r(mesh, prm.max_vertices);
  const bool within_budget = prm.max_edge_length > 0 ? r.SplitLong(prm.max_edge_length) : true;
  if (!within_budget) return false;
  r.Flip();
  r.Smooth(24);
  r.Flip();
  if (!prm.collapse_slivers) {
    RefineRounds(r, mesh, prm, false);
    return true;
  }
  // Removing vertices can also leave the boundary too coarse for the splits
  // that follow: the rounds without it are run too, and the better kept.
  CompatibleMesh plain = mesh;
  Refiner p(plain, prm.max_vertices);  // holds the same: the boundary and the features
  RefineRounds(p, plain, prm, false);
  RefineRounds(r, mesh, prm, true);
  if (MinAngleDegrees(plain) >= MinAngleDegrees(mesh)) mesh = std::move(plain);
  return true;
}

void ImproveCompatibly(CompatibleMesh& mesh) {
  Refiner r(mesh, mesh.vertices[0].size());
  r.Flip();
  r.Smooth(8);
  r.Flip();
}

double MinAngleDegrees(const CompatibleMesh& mesh) {
  double worst = M_PI;
  for (const auto& t : mesh.triangles) worst = std::min(worst, MinAngleOf(mesh, t));
  return worst * 180 / M_PI;
}

}  // namespace posemorph::bake::mapping
