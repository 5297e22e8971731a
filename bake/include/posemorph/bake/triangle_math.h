// SPDX-License-Identifier: MIT
// Per-triangle geometry of DESIGN.md section 3: edge matrices, the polar split
// A = R(alpha) S, triangle adjacency and angle unwrapping.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace posemorph::bake {

using Triangles = std::vector<std::array<std::uint32_t, 3>>;
using Points = std::vector<Eigen::Vector2d>;

// E = [p_a - p_c, p_b - p_c].
Eigen::Matrix2d EdgeMatrix(const Points& p, const std::array<std::uint32_t, 3>& t);
double SignedArea(const Points& p, const std::array<std::uint32_t, 3>& t);

struct PolarSplit {
  double alpha = 0;                                 // rotation angle in (-pi, pi]
  Eigen::Matrix2d S = Eigen::Matrix2d::Identity();  // symmetric stretch
};
// A = R(alpha) S with alpha = atan2(A21 - A12, A11 + A22). Needs det(A) > 0.
PolarSplit PolarDecompose(const Eigen::Matrix2d& A);

// For each triangle, the triangles sharing an edge with it.
std::vector<std::vector<std::uint32_t>> EdgeNeighbours(const Triangles& triangles);

// Adds 2 pi k to each angle so that it is closest to the angle of the
// already-visited neighbour it was reached from (breadth-first over each
// edge-connected part), then one 2 pi k per part so that the part's mean
// angle, weighted by `areas` (rest areas, positive), lies in (-pi, pi]: the
// result does not depend on the order of the triangles (DESIGN.md section 3).
// Angles come in from atan2.
void UnwrapAngles(const std::vector<std::vector<std::uint32_t>>& neighbours, const std::vector<double>& areas,
                  std::vector<double>& angles);

}  // namespace posemorph::bake
