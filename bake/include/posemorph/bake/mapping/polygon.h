// SPDX-License-Identifier: MIT
// The mapping's polygons, and exact geometry on the integer grid every
// mapping stage runs on.
#pragma once
#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace posemorph::bake::mapping {

using Point = Eigen::Vector2d;
using Polygon = std::vector<Point>;  // closed implicitly

// All mapping stages run on coordinates snapped to an integer grid (|x| <
// 2^26), so orientation tests are exact in 64-bit integers.

int Orient(const Point& a, const Point& b, const Point& c);  // +1 left turn, -1 right, 0 collinear
double SignedArea(const Polygon& p);
bool IsSimplePolygon(const Polygon& p);  // no two edges meet except neighbours at their shared vertex
// The edges (i: p[i] to p[i + 1]) that keep a polygon from being simple:
// each edge that meets another, folds back onto a neighbour or has no
// length; sorted, empty for a simple polygon. Exact.
std::vector<std::size_t> SelfCrossingEdges(const Polygon& p);
// +1 strictly inside, 0 on the boundary, -1 outside. Exact.
int PointInPolygon(const Polygon& p, const Point& q);
// Every point of `inner` (vertices and edges) inside or on `outer`. Exact.
bool Encloses(const Polygon& outer, const Polygon& inner);

}  // namespace posemorph::bake::mapping
