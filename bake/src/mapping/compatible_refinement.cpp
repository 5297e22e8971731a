// SPDX-License-Identifier: MIT
// Compatible refinement of N triangle meshes with one connectivity
// (compatible_refinement.h): the order of the Refiner's steps (refiner.h).
#include <algorithm>
#include <cmath>
#include <iterator>
#include <utility>
#include <vector>

#include "posemorph/bake/run_each.h"
#include "refiner.h"

namespace posemorph::bake::mapping {
namespace {

using bake::RunEach;
using refine::MinAngleOf;
using refine::Refiner;

// Graded rounds (RefineCompatibly): a bad triangle's longest edge is split
// below min_length where, in its worst pose, it is more than `ratio` times
// the triangle's shortest edge; one run per ratio, the best mesh kept. The
// outcome of one ratio swings with small changes of the drawing (Pip at
// 512 / 1024 / 2048 / 4096 px, smallest angle after the bake: ratio 4 9.7 /
// 9.2 / 13.5 (after 16 rounds) / 12.3 degrees, 5 10.0 / 10.1 / 11.7 / 10.3,
// 6 7.8 / 9.9 / 11.7 / 11.0; 3 made 1,034 vertices at 512 px). The best of
// 4, 5 and 6 gave 10.0 / 11.5 / 11.8 / 11.0, each in one mapping; with 5.5
// too, 10.6 / 11.5 / 11.8 / 11.0 (256 px: 10.4, no grading); without 6,
// 10.0 / 10.1 / 11.8 / 12.3. The runs share out the machine's cores (four
// runs on two cores take as long as two on one).
constexpr double kGradedRatios[] = {4, 5, 5.5, 6};
// A graded mesh has at most this many times the vertices of the usual
// rounds' mesh (Pip at 512-4096 px: 1.02-1.05x).
constexpr double kGradedGrowth = 1.25;

// The better of two meshes: the larger smallest angle, then fewer vertices.
bool Better(const CompatibleMesh& a, const CompatibleMesh& b) {
  const double angle_a = MinAngleDegrees(a), angle_b = MinAngleDegrees(b);
  return angle_a > angle_b || (angle_a == angle_b && a.vertices[0].size() < b.vertices[0].size());
}

// Rounds of splitting the longest edge of bad triangles, then flips and
// smoothing; with `collapse`, each round first removes the boundary vertices
// that make slivers (Refiner::CollapseBoundarySlivers); with `graded`, the
// splits go below min_length toward short edges (kGradedRatio), and where
// the last rounds only added vertices (the smallest angle the same as after
// an earlier round), the mesh after that earlier round is kept (Pip at 2048
// px, ratio 5.5: 11.8 degrees with 717 vertices after the third round, 727
// after the fourth). The Refiner is not used after a graded run: it may then
// hold another mesh's state.
void RefineRounds(Refiner& r, CompatibleMesh& mesh, const RefinementParameters& prm, bool collapse, double graded = 0) {
  const double goal = prm.min_angle_goal * M_PI / 180;
  const double min_length = prm.max_edge_length > 0 ? prm.max_edge_length / 4 : 0;
  CompatibleMesh earliest;  // graded: the mesh after the first round with the largest smallest angle yet
  double earliest_angle = -1;
  for (int round = 0; round < prm.rounds; ++round) {
    if (MinAngleDegrees(mesh) >= prm.min_angle_goal) break;
    const int collapsed = collapse ? r.CollapseBoundarySlivers(goal, prm.max_collapse_distance) : 0;
    if (r.SplitBad(goal, min_length, graded) == 0 && collapsed == 0) break;
    r.Flip();
    r.Smooth(24);
    r.Flip();
    const double angle = MinAngleDegrees(mesh);
    if (graded > 0 && angle > earliest_angle) {
      earliest = mesh;
      earliest_angle = angle;
    }
  }
  if (earliest_angle == MinAngleDegrees(mesh) && earliest.vertices[0].size() < mesh.vertices[0].size())
    mesh = std::move(earliest);
}

}  // namespace

bool RefineCompatibly(CompatibleMesh& mesh, const RefinementParameters& prm) {
  Refiner r(mesh, prm.max_vertices);
  const bool within_budget = prm.max_edge_length > 0 ? r.SplitLong(prm.max_edge_length) : true;
  if (!within_budget) return false;
  // The splits for the angle goal: within max_angle_vertices too.
  const std::size_t budget = prm.max_angle_vertices > 0
                                 ? std::max(mesh.vertices[0].size(), std::min(prm.max_vertices, prm.max_angle_vertices))
                                 : prm.max_vertices;
  r.SetMaxVertices(budget);
  r.Flip();
  r.Smooth(24);
  r.Flip();
  // Below the quality floor (half the goal) after the rounds, the rounds run
  // again from here graded toward short edges, and the better mesh is kept:
  // min_length (a quarter of max_edge_length) stops the splits that would
  // lift a sliver whose short edge one pose squeezes (Pip drawn at 2048 px:
  // a boundary edge 0.24 working pixels long in 'stretch', 3.6 in 'squash',
  // its triangle's other edges 2.1). A mesh at the floor is not touched.
  const CompatibleMesh start = mesh;
  if (!prm.collapse_slivers) {
    RefineRounds(r, mesh, prm, false);
  } else {
    // Removing vertices can also leave the boundary too coarse for the splits
    // that follow: the rounds without it are run too, and the better kept.
    CompatibleMesh plain = start;
    Refiner p(plain, budget);  // holds the same: the boundary and the features
    RunEach(2, prm.threads,
            [&](std::size_t i) { i == 0 ? RefineRounds(p, plain, prm, false) : RefineRounds(r, mesh, prm, true); });
    if (MinAngleDegrees(plain) >= MinAngleDegrees(mesh)) mesh = std::move(plain);
  }
  // Not below a quarter of the floor: such an angle comes from an outline
  // finer than any split lifts (a star's spikes), where grading only spent
  // the vertex budget (a 1024-pixel star of 60 spikes: 10 s and 395 MiB).
  // And a graded mesh grows by kGradedGrowth at most.
  const double angle = MinAngleDegrees(mesh);
  if (angle < prm.min_angle_goal / 2 && angle >= prm.min_angle_goal / 8) {
    const std::size_t most = std::min(budget, std::size_t(double(mesh.vertices[0].size()) * kGradedGrowth));
    std::vector<CompatibleMesh> graded(std::size(kGradedRatios), start);
    RunEach(graded.size(), prm.threads, [&](std::size_t i) {
      Refiner g(graded[i], most);
      RefineRounds(g, graded[i], prm, false, kGradedRatios[i]);
    });
    for (CompatibleMesh& g : graded)  // in order: the same mesh whichever thread ran first
      if (Better(g, mesh)) mesh = std::move(g);
  }
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
