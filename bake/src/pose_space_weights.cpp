// SPDX-License-Identifier: MIT
#include "posemorph/bake/pose_space_weights.h"

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "posemorph/bake/error.h"
#include "posemorph/bake/triangle_math.h"

namespace posemorph::bake {
namespace {

// The grid triangle holding a point, with exactly the arithmetic the
// runtime's WeightsJob uses (grid_location.h), so that W(p_i) = e_i holds for
// the values it computes, not just for the exact ones. Each cell is four
// triangles meeting at its centre.
GridLocation Locate(const WeightGrid& g, const Eigen::Vector2d& p) { return LocateInGrid(g, true, p.x(), p.y()); }

// The grid: the points' box grown by margin x spread on every side (a 1D
// arrangement still gets a 2D domain), covered by square cells; no weights yet.
WeightGrid CoveringGrid(const std::vector<Eigen::Vector2d>& points, const BakeParameters& params, double* spread_out) {
  Eigen::AlignedBox2d box;
  for (const auto& p : points) box.extend(p);
  const double spread = box.sizes().maxCoeff();  // > 0: points are distinct
  const Eigen::Vector2d lo = box.min().array() - params.margin * spread;
  const Eigen::Vector2d hi = box.max().array() + params.margin * spread;
  const Eigen::Vector2d size = (hi - lo).cwiseMax(1e-9 * spread);
  WeightGrid g;
  g.cell = size.maxCoeff() / params.grid_resolution;
  g.cells_x = std::max<std::uint32_t>(1, std::uint32_t(std::ceil(size.x() / g.cell - 1e-9)));
  g.cells_y = std::max<std::uint32_t>(1, std::uint32_t(std::ceil(size.y() / g.cell - 1e-9)));
  const Eigen::Vector2d center = 0.5 * (lo + hi);
  g.origin_x = center.x() - 0.5 * g.cells_x * g.cell;
  g.origin_y = center.y() - 0.5 * g.cells_y * g.cell;
  *spread_out = spread;
  return g;
}

// Nodes: the cell corners, then the cell centres. Each cell is four
// triangles meeting at its centre, so the tessellation (and the discrete
// energy below) has the grid's mirror and quarter-turn symmetries: a
// single diagonal per cell made one direction cheaper and gave
// mirror-symmetric layouts lopsided weights (0.537 against 0.149 on the snake).
struct GridMesh {
  Points nodes;
  Triangles triangles;
  std::size_t corners = 0;
};

GridMesh Tessellate(const WeightGrid& g) {
  GridMesh m;
  const std::uint32_t row = g.cells_x + 1;
  m.corners = std::size_t(row) * (g.cells_y + 1);
  const std::size_t G = m.corners + std::size_t(g.cells_x) * g.cells_y;
  m.nodes.resize(G);
  for (std::uint32_t j = 0; j <= g.cells_y; ++j)
    for (std::uint32_t i = 0; i <= g.cells_x; ++i)
      m.nodes[j * row + i] = {g.origin_x + i * g.cell, g.origin_y + j * g.cell};
  for (std::uint32_t j = 0; j < g.cells_y; ++j)
    for (std::uint32_t i = 0; i < g.cells_x; ++i) {
      const std::uint32_t v00 = j * row + i, v10 = v00 + 1, v01 = v00 + row, v11 = v01 + 1;
      const std::uint32_t c = std::uint32_t(m.corners) + j * g.cells_x + i;
      m.nodes[c] = {g.origin_x + (i + 0.5) * g.cell, g.origin_y + (j + 0.5) * g.cell};
      m.triangles.push_back({v00, v10, c});
      m.triangles.push_back({v10, v11, c});
      m.triangles.push_back({v11, v01, c});
      m.triangles.push_back({v01, v00, c});
    }
  return m;
}

// The energy's matrix Q as triplets: eps x the gradient's squared norm per
// triangle, plus the squared jump of the gradient across each interior edge.
std::vector<Eigen::Triplet<double>> EnergyTriplets(const GridMesh& m, double eps) {
  const Points& grid_points = m.nodes;
  const Triangles& tris = m.triangles;
  // Gradient operators: grad W = E^-T D (W_a, W_b, W_c).
  Eigen::Matrix<double, 2, 3> D;
  D << 1, 0, -1, 0, 1, -1;
  std::vector<Eigen::Matrix<double, 2, 3>> grads(tris.size());
  for (std::size_t t = 0; t < tris.size(); ++t) grads[t] = EdgeMatrix(grid_points, tris[t]).inverse().transpose() * D;
  std::vector<Eigen::Triplet<double>> q;
  auto add_block = [&](const std::vector<std::uint32_t>& vars, const Eigen::MatrixXd& B, double weight) {
    const Eigen::MatrixXd BtB = weight * B.transpose() * B;
    for (std::size_t r = 0; r < vars.size(); ++r)
      for (std::size_t c = 0; c < vars.size(); ++c) q.emplace_back(int(vars[r]), int(vars[c]), BtB(r, c));
  };
  const auto neighbours = EdgeNeighbours(tris);
  for (std::uint32_t t = 0; t < tris.size(); ++t) {
    add_block({tris[t][0], tris[t][1], tris[t][2]}, grads[t], eps * std::abs(SignedArea(grid_points, tris[t])));
    for (std::uint32_t u : neighbours[t]) {
      if (u < t) continue;  // each pair once
      std::vector<std::uint32_t> vars = {tris[t][0], tris[t][1], tris[t][2]};
      for (std::uint32_t v : tris[u])
        if (std::find(vars.begin(), vars.end(), v) == vars.end()) vars.push_back(v);
      Eigen::MatrixXd B = Eigen::MatrixXd::Zero(2, vars.size());
      for (int k = 0; k < 3; ++k) {
        B.col(k) += grads[t].col(k);
        B.col(std::find(vars.begin(), vars.end(), tris[u][k]) - vars.begin()) -= grads[u].col(k);
      }
      add_block(vars, B, 1.0);
    }
  }
  return q;
}

// The KKT solve meets W(p_i) = e_i only to its conditioning (~1e-12 here);
// move the three grid values around each point along its barycentric
// coordinates by the residual so the runtime's arithmetic gives e_i to
// roundoff. Residuals sum to 0 over the poses, so row sums stay 1.
void PinPoints(const WeightGrid& g, const std::vector<Eigen::Vector2d>& points, std::vector<double>& all) {
  const std::size_t N = points.size();
  for (std::size_t i = 0; i < N; ++i) {
    const GridLocation loc = Locate(g, points[i]);
    const double norm = loc.lambda[0] * loc.lambda[0] + loc.lambda[1] * loc.lambda[1] + loc.lambda[2] * loc.lambda[2];
    for (std::size_t j = 0; j < N; ++j) {
      double value = 0;
      for (int k = 0; k < 3; ++k) value += loc.lambda[k] * all[loc.node[k] * N + j];
      const double residual = (i == j ? 1.0 : 0.0) - value;
      for (int k = 0; k < 3; ++k) all[loc.node[k] * N + j] += loc.lambda[k] / norm * residual;
    }
  }
}

}  // namespace

WeightGrid SolvePoseSpaceWeights(const std::vector<Eigen::Vector2d>& points, const std::vector<std::string>& names,
                                 const BakeParameters& params, const std::string& file) {
  const std::size_t N = points.size();
  double spread = 0;
  WeightGrid g = CoveringGrid(points, params, &spread);
  const GridMesh mesh = Tessellate(g);
  const std::size_t corners = mesh.corners, G = mesh.nodes.size();
  // eps is relative to the points' spread so that it means the same at any
  // pose-space scale and grid resolution: the field levels out over distances
  // of about spread / sqrt(eps).
  std::vector<Eigen::Triplet<double>> q = EnergyTriplets(mesh, params.epsilon / (spread * spread));
  // Point constraints by Lagrange multipliers: [Q C^T; C 0] [W; mu] = [0; I].
  std::vector<std::uint32_t> cell_owner(std::size_t(g.cells_x) * g.cells_y, std::uint32_t(-1));
  for (std::size_t i = 0; i < N; ++i) {
    const GridLocation loc = Locate(g, points[i]);
    if (cell_owner[loc.cell] != std::uint32_t(-1))
      throw BakeError(file, "pose points '" + names[cell_owner[loc.cell]] + "' and '" + names[i] +
                                "' fall in one pose-space grid cell; raise bake.grid_resolution (now " +
                                std::to_string(params.grid_resolution) + ") or move them apart");
    cell_owner[loc.cell] = std::uint32_t(i);
    for (int k = 0; k < 3; ++k) {
      q.emplace_back(int(G + i), int(loc.node[k]), loc.lambda[k]);
      q.emplace_back(int(loc.node[k]), int(G + i), loc.lambda[k]);
    }
  }
  Eigen::SparseMatrix<double> kkt(int(G + N), int(G + N));
  kkt.setFromTriplets(q.begin(), q.end());
  kkt.makeCompressed();
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(kkt);
  // The grid and constraint checks above leave a solvable system; a failure
  // here is a layout beyond the grid's precision: say which layout.
  auto layout_problem = [&](const std::string& symptom) {
    std::ostringstream s;
    s << "the pose-space weights cannot be solved for these pose points (" << symptom << "): " << N << " points on a "
      << g.cells_x << " x " << g.cells_y << " grid of cell size " << g.cell
      << "; move points that nearly coincide apart, or change bake.grid_resolution (now " << params.grid_resolution
      << ")";
    return BakeError(file, s.str());
  };
  if (lu.info() != Eigen::Success) throw layout_problem("the solver reports: " + lu.lastErrorMessage());
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(G + N, N);
  for (std::size_t i = 0; i < N; ++i) rhs(G + i, i) = 1;
  const Eigen::MatrixXd solution = lu.solve(rhs);
  if (lu.info() != Eigen::Success || !solution.allFinite()) throw layout_problem("the solve gave non-finite weights");

  std::vector<double> all(G * N);  // corners, then centres
  for (std::size_t v = 0; v < G; ++v) {
    // The exact field sums to 1 (the constant 1 meets every constraint at zero
    // energy); dividing by the sum removes the solver's roundoff.
    const double sum = solution.row(v).sum();
    for (std::size_t i = 0; i < N; ++i) all[v * N + i] = solution(v, i) / sum;
  }
  PinPoints(g, points, all);
  g.weights.assign(all.begin(), all.begin() + std::ptrdiff_t(corners * N));
  g.centre_weights.assign(all.begin() + std::ptrdiff_t(corners * N), all.end());
  return g;
}

}  // namespace posemorph::bake
