// SPDX-License-Identifier: MIT
// The as-rigid-as-possible normal equations of DESIGN.md section 3: per
// triangle the area-weighted gradient operator, the cotangent matrix K with
// vertex 0 pinned, ordered (AMD) and factored (LDL^T) once.
#pragma once
#include <cstdint>
#include <vector>

#include <Eigen/SparseCore>

#include "posemorph/bake/triangle_math.h"

namespace posemorph::bake {

struct ArapSystem {
  std::vector<double> gradients;      // 6 per triangle: area * (E^-T D)^T, 3 x 2 row-major
  std::vector<double> vertex_masses;  // lumped rest areas, sum 1
  Eigen::SparseMatrix<double> K;      // pinned system, (V-1) x (V-1), both triangles
  // P K P^T = L D L^T with order[k'] = k.
  std::vector<std::uint32_t> order;
  std::vector<std::uint32_t> col_start, row;
  std::vector<double> value, inv_diagonal;
};

// Throws BakeError (with `file`) if K is not positive definite.
ArapSystem BuildArapSystem(const Points& rest, const Triangles& triangles, const std::string& file);

}  // namespace posemorph::bake
