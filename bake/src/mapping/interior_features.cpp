// SPDX-License-Identifier: MIT
// Features become shared vertices: inserted where the outlines'
// correspondence puts them (a triangle's centroid in every pose), then moved
// to their points with the interior following harmonically.
#include "posemorph/bake/mapping/interior_features.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <string>

#include "format_number.h"
#include "geometry.h"
#include "posemorph/bake/mapping/compatible_refinement.h"

namespace posemorph::bake::mapping {
namespace {

using Tri = std::array<std::size_t, 3>;
constexpr std::size_t kNone = ~std::size_t(0);

// The triangle holding q in these positions (inside or on an edge), or kNone.
std::size_t Holding(const Polygon& pos, const std::vector<Tri>& tris, const Point& q) {
  for (std::size_t t = 0; t < tris.size(); ++t) {
    const Tri& r = tris[t];
    if (Cross(pos[r[0]], pos[r[1]], q) >= 0 && Cross(pos[r[1]], pos[r[2]], q) >= 0 &&
        Cross(pos[r[2]], pos[r[0]], q) >= 0)
      return t;
  }
  return kNone;
}

// Splits triangle t at a new vertex at its centroid in every pose.
std::size_t SplitAtCentroid(CompatibleMesh& mesh, std::size_t t) {
  const Tri r = mesh.triangles[t];
  const std::size_t w = mesh.vertices[0].size();
  for (Polygon& pos : mesh.vertices) pos.push_back(Snap((pos[r[0]] + pos[r[1]] + pos[r[2]]) / 3));
  mesh.triangles[t] = {r[0], r[1], w};
  mesh.triangles.push_back({r[1], r[2], w});
  mesh.triangles.push_back({r[2], r[0], w});
  return w;
}

// The bi-Laplacian energy |L d|^2 of the displacements d (L the uniform
// graph Laplacian), restricted to the free vertices and factored once for
// every pose (it depends on the connectivity only). A point displacement
// spreads smoothly over the interior (like r^2 log r), where the harmonic
// one (|grad d|^2) stays within a ring of the point and folds it.
struct FreeLaplacian {
  std::vector<int> unknown;  // vertex -> row, -1 when held
  std::vector<std::vector<std::size_t>> neighbours;
  Eigen::SparseMatrix<double> coupling;  // Q restricted to free rows, all columns
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor;
  int rows = 0;
};

void Factor(const CompatibleMesh& mesh, const std::vector<char>& held, FreeLaplacian& L) {
  const std::size_t V = mesh.vertices[0].size();
  L.neighbours.assign(V, {});
  for (const Tri& t : mesh.triangles)
    for (int e = 0; e < 3; ++e) {
      L.neighbours[t[e]].push_back(t[(e + 1) % 3]);
      L.neighbours[t[(e + 1) % 3]].push_back(t[e]);
    }
  for (auto& n : L.neighbours) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  L.unknown.assign(V, -1);
  L.rows = 0;
  for (std::size_t v = 0; v < V; ++v)
    if (!held[v]) L.unknown[v] = L.rows++;
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t v = 0; v < V; ++v) {
    entries.emplace_back(int(v), int(v), double(L.neighbours[v].size()));
    for (std::size_t u : L.neighbours[v]) entries.emplace_back(int(v), int(u), -1.0);
  }
  Eigen::SparseMatrix<double> lap{Eigen::Index(V), Eigen::Index(V)};
  lap.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SparseMatrix<double> Q = Eigen::SparseMatrix<double>(lap.transpose()) * lap;
  // Select the free rows (and, for the factor, the free columns).
  std::vector<Eigen::Triplet<double>> free_rows, free_block;
  for (int c = 0; c < Q.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(Q, c); it; ++it) {
      const int r = L.unknown[std::size_t(it.row())];
      if (r < 0) continue;
      free_rows.emplace_back(r, int(it.col()), it.value());
      if (L.unknown[std::size_t(it.col())] >= 0)
        free_block.emplace_back(r, L.unknown[std::size_t(it.col())], it.value());
    }
  L.coupling.resize(L.rows, int(V));
  L.coupling.setFromTriplets(free_rows.begin(), free_rows.end());
  Eigen::SparseMatrix<double> A(L.rows, L.rows);
  A.setFromTriplets(free_block.begin(), free_block.end());
  if (L.rows > 0) L.factor.compute(A);
}

// The held vertices' displacements spread over the free ones: the free
// displacements that minimise |L d|^2 with the held ones given.
void MoveInterior(Polygon& pos, const FreeLaplacian& L, const std::vector<Point>& displacement) {
  if (L.rows == 0) return;
  Eigen::MatrixX2d held = Eigen::MatrixX2d::Zero(Eigen::Index(pos.size()), 2);
  for (std::size_t v = 0; v < pos.size(); ++v)
    if (L.unknown[v] < 0) held.row(Eigen::Index(v)) = displacement[v].transpose();
  const Eigen::MatrixX2d rhs = -(L.coupling * held);
  const Eigen::MatrixX2d d = L.factor.solve(rhs);
  for (std::size_t v = 0; v < pos.size(); ++v) {
    if (L.unknown[v] < 0)
      pos[v] = pos[v] + displacement[v];
    else
      pos[v] = Snap(pos[v] + d.row(L.unknown[v]).transpose());
  }
}

}  // namespace

std::vector<char> BoundaryVertices(const CompatibleMesh& mesh) {
  std::vector<std::pair<std::size_t, std::size_t>> edges;
  for (const Tri& t : mesh.triangles)
    for (int e = 0; e < 3; ++e) edges.emplace_back(std::min(t[e], t[(e + 1) % 3]), std::max(t[e], t[(e + 1) % 3]));
  std::sort(edges.begin(), edges.end());
  std::vector<char> boundary(mesh.vertices[0].size(), 0);
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i == 1) boundary[edges[i].first] = boundary[edges[i].second] = 1;
    i = j;
  }
  return boundary;
}

void PlaceFeatures(CompatibleMesh& mesh, const std::vector<std::vector<Point>>& features,
                   const std::vector<ErrorSource>& poses, double grid_scale) {
  const std::size_t N = mesh.vertices.size(), F = features[0].size();
  if (F == 0) return;
  // Where the outlines' correspondence puts each feature: a pose-0 triangle's
  // centroid, the same triangle's in every pose.
  std::vector<std::size_t> ids;
  for (std::size_t f = 0; f < F; ++f) {
    const std::size_t t = Holding(mesh.vertices[0], mesh.triangles, features[0][f]);
    if (t == kNone) throw poses[0].Error("feature " + std::to_string(f) + " lies outside the mesh");
    ids.push_back(SplitAtCentroid(mesh, t));
  }
  std::vector<char> held = BoundaryVertices(mesh);
  for (std::size_t v : mesh.features) held[v] = 1;
  for (std::size_t v : ids) held[v] = 1;
  mesh.features.insert(mesh.features.end(), ids.begin(), ids.end());
  // Move them in steps, each as long as leaves every triangle positive in
  // every pose (halved until it does), with flips and smoothing in between
  // (held: the features), so the interior flows around them.
  double done = 0;  // share of the way behind
  double step = 1;
  FreeLaplacian L;
  Factor(mesh, held, L);
  while (done < 1) {
    step = std::min(step, 1 - done);
    const std::vector<Polygon> before = mesh.vertices;
    std::size_t bad_pose = N, bad_triangle = 0;
    for (std::size_t k = 0; k < N && bad_pose == N; ++k) {
      Polygon& pos = mesh.vertices[k];
      std::vector<Point> displacement(pos.size(), Point::Zero());
      const double share = step / (1 - done);
      for (std::size_t f = 0; f < F; ++f)
        displacement[ids[f]] = share >= 1 ? features[k][f] - pos[ids[f]] : Snap((features[k][f] - pos[ids[f]]) * share);
      MoveInterior(pos, L, displacement);
      for (std::size_t t = 0; t < mesh.triangles.size() && bad_pose == N; ++t) {
        const Tri& r = mesh.triangles[t];
        if (Cross(pos[r[0]], pos[r[1]], pos[r[2]]) <= 0) bad_pose = k, bad_triangle = t;
      }
    }
    if (bad_pose == N) {
      done += step;
      step *= 2;
      ImproveCompatibly(mesh);
      Factor(mesh, held, L);
      continue;
    }
    mesh.vertices = before;
    if (step > 1.0 / 256) {
      step /= 2;
      continue;
    }
    // Name the feature nearest the triangle that turned over.
    const Polygon& pos = mesh.vertices[bad_pose];
    const Tri& r = mesh.triangles[bad_triangle];
    const Point at = (pos[r[0]] + pos[r[1]] + pos[r[2]]) / 3;
    std::size_t nearest = 0;
    for (std::size_t f = 1; f < F; ++f)
      if ((features[bad_pose][f] - at).norm() < (features[bad_pose][nearest] - at).norm()) nearest = f;
    throw poses[bad_pose].Error(
        "feature " + std::to_string(nearest) + " cannot be moved to its point without turning a triangle over (" +
        Format((features[bad_pose][nearest] - pos[ids[nearest]]).norm() / grid_scale) +
        " short of it); add landmarks on the outline near it, or check that the features are listed in the same "
        "order in every pose");
  }
}

}  // namespace posemorph::bake::mapping
