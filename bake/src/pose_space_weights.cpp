// SPDX-License-Identifier: MIT
#include "posemorph/bake/pose_space_weights.h"

#include <Eigen/SparseCore>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "posemorph/bake/error.h"
#include "posemorph/bake/pose_space_samples.h"
#include "posemorph/bake/thin_plate_spline.h"
#include "posemorph/bake/triangle_math.h"

namespace posemorph::bake {
namespace {

// The grid triangle holding a point, with exactly the arithmetic the
// runtime's WeightsJob uses (grid_location.h), so that W(p_i) = e_i holds for
// the values it computes, not just for the exact ones. Each cell is four
// triangles meeting at its centre.
GridLocation Locate(const WeightGrid& g, const Eigen::Vector2d& p) { return LocateInGrid(g, true, p.x(), p.y()); }

// The grid: the points' box grown by margin x spread on every side (a 1D
// arrangement still gets a 2D domain), covered by square cells; no weights
// yet. With narrow_line_layout, a layout on a horizontal or vertical line
// is kLineLayoutCells wide across it.
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
  if (params.narrow_line_layout) {
    if (box.sizes().x() <= 1e-12 * spread) g.cells_x = std::min(g.cells_x, kLineLayoutCells);
    if (box.sizes().y() <= 1e-12 * spread) g.cells_y = std::min(g.cells_y, kLineLayoutCells);
  }
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

// The grid interpolates the spline's values, so W(p_i) = e_i holds only to
// the interpolation error (~1e-3); move the three grid values around each
// point along its barycentric coordinates by the residual so the runtime's
// arithmetic gives e_i to roundoff. Points in neighbouring cells share
// nodes, so sweep until no residual is left (Gauss-Seidel on a positive
// definite system: it converges). Residuals sum to 0 over the poses, so row
// sums stay 1.
void PinPoints(const WeightGrid& g, const std::vector<Eigen::Vector2d>& points, std::vector<double>& all) {
  const std::size_t N = points.size();
  for (int sweep = 0; sweep < 100; ++sweep) {
    double largest = 0;
    for (std::size_t i = 0; i < N; ++i) {
      const GridLocation loc = Locate(g, points[i]);
      const double norm = loc.lambda[0] * loc.lambda[0] + loc.lambda[1] * loc.lambda[1] + loc.lambda[2] * loc.lambda[2];
      for (std::size_t j = 0; j < N; ++j) {
        double value = 0;
        for (int k = 0; k < 3; ++k) value += loc.lambda[k] * all[loc.node[k] * N + j];
        const double residual = (i == j ? 1.0 : 0.0) - value;
        largest = std::max(largest, std::abs(residual));
        for (int k = 0; k < 3; ++k) all[loc.node[k] * N + j] += loc.lambda[k] / norm * residual;
      }
    }
    if (largest <= 1e-15) return;
  }
}

// Distance from x to the convex hull (counter-clockwise; a segment or a
// point when the points are collinear); 0 inside.
double DistanceToHull(const std::vector<Eigen::Vector2d>& hull, const Eigen::Vector2d& x) {
  if (hull.size() == 1) return (x - hull[0]).norm();
  bool inside = hull.size() >= 3;
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d& a = hull[i];
    const Eigen::Vector2d ab = hull[(i + 1) % hull.size()] - a, ax = x - a;
    if (ab.x() * ax.y() - ab.y() * ax.x() < 0) inside = false;
    const double t = std::clamp(ax.dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    nearest = std::min(nearest, (ax - t * ab).norm());
  }
  return inside ? 0.0 : nearest;
}

}  // namespace

WeightGrid SolvePoseSpaceWeights(const std::vector<Eigen::Vector2d>& points, const std::vector<std::string>& names,
                                 const BakeParameters& params, const std::string& file,
                                 std::vector<std::string>* warnings) {
  const std::size_t N = points.size();
  double spread = 0;
  WeightGrid g = CoveringGrid(points, params, &spread);
  const GridMesh mesh = Tessellate(g);
  const std::size_t corners = mesh.corners, G = mesh.nodes.size();
  // Two points in one cell would ask one triangle's three values for two
  // different unit vectors.
  std::vector<std::uint32_t> cell_owner(std::size_t(g.cells_x) * g.cells_y, std::uint32_t(-1));
  for (std::size_t i = 0; i < N; ++i) {
    const GridLocation loc = Locate(g, points[i]);
    if (cell_owner[loc.cell] != std::uint32_t(-1))
      throw BakeError(file, "pose points '" + names[cell_owner[loc.cell]] + "' and '" + names[i] +
                                "' fall in one pose-space grid cell; raise bake.grid_resolution (now " +
                                std::to_string(params.grid_resolution) + ") or move them apart");
    cell_owner[loc.cell] = std::uint32_t(i);
  }
  for (std::size_t i = 0; warnings && i < N; ++i)
    for (std::size_t j = i + 1; j < N; ++j) {
      const double apart = (points[i] - points[j]).norm() / g.cell;
      if (apart >= 2) continue;
      const int needed = std::min(256, int(std::ceil(params.grid_resolution * 2 / apart)));
      std::ostringstream s;
      s.precision(2);
      s << file << ": pose points '" << names[i] << "' and '" << names[j] << "' are " << std::fixed << apart
        << " pose-space grid cells apart: the weights between them are interpolated coarsely; bake.grid_resolution "
        << needed << " (now " << params.grid_resolution << ") puts them two cells apart";
      warnings->push_back(s.str());
    }

  // Near the hull: the thin-plate spline, at every node of every cell whose
  // centre lies within two cells of the hull (so every point of the hull is
  // interpolated from spline values only, and the field around a pose point
  // on the hull is the spline's).
  const ThinPlateSpline spline(points);
  const std::vector<Eigen::Vector2d> hull = ConvexHull(points);
  std::vector<char> fixed(G, 0);
  std::vector<double> all(G * N, 0.0);  // corners, then centres
  auto set_spline = [&](std::size_t v) {
    if (fixed[v]) return;
    fixed[v] = 1;
    const Eigen::VectorXd w = spline(mesh.nodes[v]);
    for (std::size_t i = 0; i < N; ++i) all[v * N + i] = w(Eigen::Index(i));
  };
  for (std::size_t cell = 0; cell < std::size_t(g.cells_x) * g.cells_y; ++cell) {
    if (DistanceToHull(hull, mesh.nodes[corners + cell]) > 2.0 * g.cell) continue;
    for (int k = 0; k < 4; ++k) set_spline(mesh.triangles[4 * cell + std::size_t(k)][0]);
    set_spline(corners + cell);
  }

  // Outside: the energy with the spline's values held, so that the field
  // continues the spline smoothly and levels out. eps is relative to the
  // points' spread so that it means the same at any pose-space scale and grid
  // resolution: the field levels out over distances of about spread /
  // sqrt(eps).
  std::vector<Eigen::Triplet<double>> q = EnergyTriplets(mesh, params.epsilon / (spread * spread));
  std::vector<int> unknown(G, -1);
  int free_count = 0;
  for (std::size_t v = 0; v < G; ++v)
    if (!fixed[v]) unknown[v] = free_count++;
  if (free_count > 0) {
    std::vector<Eigen::Triplet<double>> qff;
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(free_count, Eigen::Index(N));
    for (const auto& t : q) {
      const int r = unknown[std::size_t(t.row())];
      if (r < 0) continue;
      const int c = unknown[std::size_t(t.col())];
      if (c >= 0) {
        qff.emplace_back(r, c, t.value());
      } else {
        for (std::size_t i = 0; i < N; ++i) rhs(r, Eigen::Index(i)) -= t.value() * all[std::size_t(t.col()) * N + i];
      }
    }
    Eigen::SparseMatrix<double> Q(free_count, free_count);
    Q.setFromTriplets(qff.begin(), qff.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(Q);
    // Q is positive definite (the gradient term, and nodes held): a failure
    // here is a layout beyond the grid's precision; say which layout.
    auto layout_problem = [&](const std::string& symptom) {
      std::ostringstream s;
      s << "the pose-space weights cannot be solved for these pose points (" << symptom << "): " << N << " points on a "
        << g.cells_x << " x " << g.cells_y << " grid of cell size " << g.cell
        << "; move points that nearly coincide apart, or change bake.grid_resolution (now " << params.grid_resolution
        << ")";
      return BakeError(file, s.str());
    };
    if (ldlt.info() != Eigen::Success) throw layout_problem("the factorisation failed");
    const Eigen::MatrixXd solution = ldlt.solve(rhs);
    if (ldlt.info() != Eigen::Success || !solution.allFinite())
      throw layout_problem("the solve gave non-finite weights");
    for (std::size_t v = 0; v < G; ++v)
      if (unknown[v] >= 0)
        for (std::size_t i = 0; i < N; ++i) all[v * N + i] = solution(unknown[v], Eigen::Index(i));
  }
  for (std::size_t v = 0; v < G; ++v) {
    // The exact field sums to 1 (the spline reproduces constants and the
    // constant 1 continues it at zero energy); dividing by the sum removes
    // roundoff.
    double sum = 0;
    for (std::size_t i = 0; i < N; ++i) sum += all[v * N + i];
    for (std::size_t i = 0; i < N; ++i) all[v * N + i] /= sum;
  }
  PinPoints(g, points, all);
  g.weights.assign(all.begin(), all.begin() + std::ptrdiff_t(corners * N));
  g.centre_weights.assign(all.begin() + std::ptrdiff_t(corners * N), all.end());
  return g;
}

}  // namespace posemorph::bake
