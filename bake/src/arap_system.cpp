// SPDX-License-Identifier: MIT
#include "posemorph/bake/arap_system.h"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "posemorph/bake/error.h"

namespace posemorph::bake {

namespace {

// K (pose 0's stiffness, vertex 0 pinned) as triplets, the gradients and the
// vertex masses (unnormalised); the smallest and largest triangle areas.
struct Assembly {
  std::vector<Eigen::Triplet<double>> entries;
  double total_area = 0, smallest_area = HUGE_VAL, largest_area = 0;
};

Assembly Assemble(const Points& rest, const Triangles& triangles, ArapSystem& sys) {
  Assembly out;
  std::vector<Eigen::Triplet<double>>& entries = out.entries;
  double &total_area = out.total_area, &smallest_area = out.smallest_area, &largest_area = out.largest_area;
  // D maps (x_a, x_b, x_c) to the edge differences (x_a - x_c, x_b - x_c).
  Eigen::Matrix<double, 2, 3> D;
  D << 1, 0, -1, 0, 1, -1;
  entries.reserve(9 * triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    const Eigen::Matrix2d E = EdgeMatrix(rest, tri);
    const double area = 0.5 * E.determinant();
    smallest_area = std::min(smallest_area, area), largest_area = std::max(largest_area, area);
    // Row d of J_t(x) is (G x^d)^T with G = E^-T D, so the energy term is
    // area ||G x^d - a_d||^2: K gets area G^T G, the right-hand side area G^T a_d.
    const Eigen::Matrix<double, 2, 3> G = E.inverse().transpose() * D;
    const Eigen::Matrix<double, 3, 2> M = area * G.transpose();
    for (int k = 0; k < 3; ++k) {
      sys.gradients[6 * t + 2 * k] = M(k, 0);
      sys.gradients[6 * t + 2 * k + 1] = M(k, 1);
      sys.vertex_masses[tri[k]] += area / 3;
    }
    total_area += area;
    const Eigen::Matrix3d Kt = M * G;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        if (tri[r] != 0 && tri[c] != 0) entries.emplace_back(int(tri[r] - 1), int(tri[c] - 1), Kt(r, c));
  }
  return out;
}

// Fill-reducing order; Eigen's AMD returns the inverse permutation, whose
// indices are exactly "which unknown goes to position k'".
Eigen::SparseMatrix<double> Reordered(ArapSystem& sys, std::size_t n) {
  Eigen::AMDOrdering<int> amd;
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse_perm;
  amd(sys.K, inverse_perm);
  sys.order.assign(inverse_perm.indices().data(), inverse_perm.indices().data() + n);
  std::vector<int> position(n);
  for (std::size_t k = 0; k < n; ++k) position[sys.order[k]] = int(k);
  std::vector<Eigen::Triplet<double>> permuted;
  permuted.reserve(sys.K.nonZeros());
  for (int c = 0; c < sys.K.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(sys.K, c); it; ++it)
      permuted.emplace_back(position[it.row()], position[it.col()], it.value());
  Eigen::SparseMatrix<double> Kp(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  Kp.setFromTriplets(permuted.begin(), permuted.end());
  return Kp;
}

}  // namespace

ArapSystem BuildArapSystem(const Points& rest, const Triangles& triangles, const std::string& file) {
  const std::size_t V = rest.size(), n = V - 1;
  ArapSystem sys;
  sys.gradients.resize(6 * triangles.size());
  sys.vertex_masses.assign(V, 0.0);

  const Assembly assembly = Assemble(rest, triangles, sys);
  const double total_area = assembly.total_area, smallest_area = assembly.smallest_area,
               largest_area = assembly.largest_area;
  const std::vector<Eigen::Triplet<double>>& entries = assembly.entries;
  for (double& m : sys.vertex_masses) m /= total_area;
  sys.K.resize(int(n), int(n));
  sys.K.setFromTriplets(entries.begin(), entries.end());

  const Eigen::SparseMatrix<double> Kp = Reordered(sys, n);

  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>> ldlt(Kp);
  // A failure here means the rest pose's triangles are beyond what double
  // precision resolves (validation refuses zero, negative and non-finite
  // areas): say so with the areas, not the solver's symptom.
  auto precision_problem = [&](const std::string& symptom) {
    std::ostringstream s;
    s << "pose 0's mesh cannot be solved as-rigidly-as-possible (" << symptom << "): its triangle areas range from "
      << smallest_area << " to " << largest_area
      << "; triangles this thin or this unequal are beyond double precision (rescale the mesh or remove slivers)";
    return BakeError(file, s.str());
  };
  if (ldlt.info() != Eigen::Success) throw precision_problem("the factorisation failed");
  const Eigen::VectorXd d = ldlt.vectorD();
  for (std::size_t k = 0; k < n; ++k) {
    if (!(d[k] > 0) || !std::isfinite(d[k]))
      throw precision_problem("pivot " + std::to_string(k) + " of " + std::to_string(n) + " for vertex " +
                              std::to_string(sys.order[k] + 1) + " is " + std::to_string(d[k]) + ", not positive");
    sys.inv_diagonal.push_back(1.0 / d[k]);
  }
  Eigen::SparseMatrix<double> L = ldlt.matrixL();
  L.makeCompressed();
  sys.col_start.push_back(0);
  for (int c = 0; c < L.outerSize(); ++c) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, c); it; ++it)
      if (it.row() > c) {
        sys.row.push_back(std::uint32_t(it.row()));
        sys.value.push_back(it.value());
      }
    sys.col_start.push_back(std::uint32_t(sys.row.size()));
  }
  return sys;
}

}  // namespace posemorph::bake
