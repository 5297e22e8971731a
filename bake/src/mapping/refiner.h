// SPDX-License-Identifier: MIT
// The compatible refinement's working object (compatible_refinement.cpp):
// N meshes of one connectivity refined together, their edge map, and the
// predicates every step checks in all N poses. Its steps: splits, flips and
// smoothing (refiner.cpp), removal of boundary slivers (boundary_slivers.cpp).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "geometry.h"
#include "posemorph/bake/mapping/compatible_refinement.h"

namespace posemorph::bake::mapping::refine {

using Tri = std::array<std::size_t, 3>;

// An edge's key: its two vertices, smaller first.
inline std::uint64_t Key(std::size_t a, std::size_t b) {
  return (std::uint64_t(std::min(a, b)) << 32) | std::uint64_t(std::max(a, b));
}

// Each edge of a triangle list and the (one or two) triangles that use it.
struct EdgeMap {
  std::unordered_map<std::uint64_t, std::array<std::size_t, 2>> at;  // up to two triangles, npos if none
  static constexpr std::size_t kNone = ~std::size_t(0);
  explicit EdgeMap(const std::vector<Tri>& tris) {
    for (std::size_t t = 0; t < tris.size(); ++t)
      for (int e = 0; e < 3; ++e) {
        auto [it, fresh] =
            at.try_emplace(Key(tris[t][e], tris[t][(e + 1) % 3]), std::array<std::size_t, 2>{kNone, kNone});
        (void)fresh;
        it->second[it->second[0] == kNone ? 0 : 1] = t;
      }
  }
};

// The smallest angle of t over all poses, radians.
double MinAngleOf(const CompatibleMesh& m, const Tri& t);
// t is counter-clockwise (positive area) in the pose with vertices v.
bool Positive(const Polygon& v, const Tri& t);
// Rotates t so that its first edge is {a, b} in either direction; false if t lacks it.
bool EdgeFirst(Tri& t, std::size_t a, std::size_t b);
// A grid point near the midpoint of a boundary edge a -> b, on it or just
// outside (to its right), so the polygon still encloses what it enclosed.
Point BoundaryMidpoint(const Point& a, const Point& b);
// A grid point near m (a point of the boundary edge a -> b) on the edge or
// just outside it (to its right): the one nearest m of the four around it.
Point OnEdgeOrOutside(const Point& a, const Point& b, const Point& m);

class Refiner {
 public:
  Refiner(CompatibleMesh& m, std::size_t max_vertices);
  bool SplitEdge(std::size_t a, std::size_t b, const EdgeMap& em);
  double Length(std::size_t a, std::size_t b) const;
  // The vertex budget is spent.
  bool Full() const { return m_.vertices[0].size() >= max_vertices_; }
  void SetMaxVertices(std::size_t n) { max_vertices_ = n; }
  // Splits every edge longer than max_length (longest first), until none is;
  // false when the vertex budget ran out first.
  bool SplitLong(double max_length);
  int Flip();
  void Smooth(int passes);
  // Removes boundary vertices that make slivers: where a triangle's smallest
  // angle (over all poses) is below the goal and lies opposite a boundary
  // edge that is the triangle's shortest in its worst pose, one end of that
  // edge is collapsed into the other, so the boundary goes straight from the
  // removed vertex's neighbour to its other neighbour. Accepted only where
  // every changed triangle stays positive in every pose, the smallest angle
  // around the removed vertex rises, no edge is duplicated (the link
  // condition), and the removed vertex is a reflex or straight corner in
  // every pose (removing it only grows the mesh, so the mesh still encloses
  // the outline) within max_distance of the new edge (the mesh grows by no
  // more). Features are never removed. Returns the number removed.
  int CollapseBoundarySlivers(double goal, double max_distance);
  // Splits the longest edge of each triangle whose smallest angle is below
  // the goal, if that edge is min_length long in some pose; with
  // graded_ratio > 0 also a shorter one where, in the pose the triangle is
  // worst in, its longest edge is more than graded_ratio times its
  // shortest (a sliver on an edge one pose squeezes: the mesh grades toward
  // that edge).
  int SplitBad(double goal, double min_length, double graded_ratio = 0);

 private:
  int CollapseOnce(double goal, double max_distance);
  double WorstPoseEdgeRatio(const Tri& t) const;
  // Collapses boundary vertex v into its boundary neighbour u (the edge u-v
  // is in triangle `gone`, which disappears), if that is acceptable.
  bool TryCollapse(std::size_t v, std::size_t u, std::size_t gone,
                   const std::vector<std::vector<std::size_t>>& incident, const std::vector<std::size_t>& next_of,
                   const std::vector<std::size_t>& prev_of, double max_distance);

  CompatibleMesh& m_;
  std::vector<bool> held_;  // never moved: boundary vertices and features
  std::size_t max_vertices_;
};

}  // namespace posemorph::bake::mapping::refine
