// SPDX-License-Identifier: MIT
#include "posemorph/bake/arap_deformer.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>

#include "posemorph/bake/error.h"

namespace posemorph::bake {

namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;
using Triplets = std::vector<Eigen::Triplet<double>>;

// Splits a symmetric matrix's unknowns into free (f) and handle (h) parts.
struct Partition {
  std::vector<int> index;  // unknown -> position within its part
  std::vector<char> is_handle;
  int free_count = 0, handle_count = 0;
};

void SplitBlocks(const SparseMatrix& M, const Partition& p, SparseMatrix* ff, SparseMatrix* fh) {
  Triplets tff, tfh;
  for (int c = 0; c < M.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(M, c); it; ++it) {
      const int r = int(it.row());
      if (p.is_handle[r]) continue;
      (p.is_handle[c] ? tfh : tff).emplace_back(p.index[r], p.index[c], it.value());
    }
  ff->resize(p.free_count, p.free_count);
  ff->setFromTriplets(tff.begin(), tff.end());
  fh->resize(p.free_count, p.handle_count);
  fh->setFromTriplets(tfh.begin(), tfh.end());
}

Partition MakePartition(std::size_t unknowns, const std::vector<std::uint32_t>& handle_unknowns) {
  Partition p;
  p.index.assign(unknowns, -1);
  p.is_handle.assign(unknowns, 0);
  for (std::uint32_t u : handle_unknowns) p.is_handle[u] = 1;
  for (std::size_t u = 0; u < unknowns; ++u) p.index[u] = p.is_handle[u] ? p.handle_count++ : p.free_count++;
  return p;
}

// Vertex k of a triangle in the frame of the edge i -> j: p_k - p_i = x d + y R90 d.
Eigen::Vector2d LocalCoordinates(const Eigen::Vector2d& pi, const Eigen::Vector2d& pj, const Eigen::Vector2d& pk) {
  const Eigen::Vector2d d = pj - pi, e = pk - pi, d90(-d.y(), d.x());
  return Eigen::Vector2d(e.dot(d), e.dot(d90)) / d.squaredNorm();
}

}  // namespace

struct ArapDeformer::Factors {
  Partition p1, p2;  // step 1: 2V interleaved unknowns; step 2: V per coordinate
  Eigen::SimplicialLDLT<SparseMatrix> g_ff, h_ff;
  SparseMatrix g_fh, h_fh;
};

ArapDeformer::ArapDeformer(Points rest, Triangles triangles, std::vector<std::uint32_t> handles,
                           const std::string& file)
    : rest_(std::move(rest)), triangles_(std::move(triangles)), handles_(std::move(handles)), factors_(new Factors) {
  const std::size_t V = rest_.size();
  if (handles_.size() < 2)
    throw BakeError(file, "a deformation needs at least 2 handles, got " + std::to_string(handles_.size()));
  for (std::size_t a = 0; a < handles_.size(); ++a) {
    if (handles_[a] >= V)
      throw BakeError(file, "handle " + std::to_string(a) + " names vertex " + std::to_string(handles_[a]) + " of " +
                                std::to_string(V));
    for (std::size_t b = 0; b < a; ++b)
      if (handles_[a] == handles_[b])
        throw BakeError(file, "handles " + std::to_string(b) + " and " + std::to_string(a) + " both hold vertex " +
                                  std::to_string(handles_[a]) + " (they coincide)");
  }
  if (handles_.size() >= V) throw BakeError(file, "every vertex is a handle: nothing left to deform");

  // Step 1: for each triangle and each of its three vertices k (edge i -> j
  // opposite), the residual v_k - (1 - x) v_i - x v_j - y R90 (v_j - v_i)
  // = Ci v_i + Cj v_j + Ck v_k with 2x2 blocks; G = sum C^T C.
  Triplets g;
  Eigen::Matrix2d R90;
  R90 << 0, -1, 1, 0;
  for (const auto& t : triangles_)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t vi = t[(k + 1) % 3], vj = t[(k + 2) % 3], vk = t[k];
      const Eigen::Vector2d xy = LocalCoordinates(rest_[vi], rest_[vj], rest_[vk]);
      Eigen::Matrix<double, 2, 6> C;
      C.block<2, 2>(0, 0) = -(1 - xy.x()) * Eigen::Matrix2d::Identity() + xy.y() * R90;
      C.block<2, 2>(0, 2) = -xy.x() * Eigen::Matrix2d::Identity() - xy.y() * R90;
      C.block<2, 2>(0, 4) = Eigen::Matrix2d::Identity();
      const Eigen::Matrix<double, 6, 6> CtC = C.transpose() * C;
      const std::uint32_t v[3] = {vi, vj, vk};
      for (int r = 0; r < 6; ++r)
        for (int c = 0; c < 6; ++c) g.emplace_back(int(2 * v[r / 2] + r % 2), int(2 * v[c / 2] + c % 2), CtC(r, c));
    }
  SparseMatrix G(static_cast<Eigen::Index>(2 * V), static_cast<Eigen::Index>(2 * V));
  G.setFromTriplets(g.begin(), g.end());
  std::vector<std::uint32_t> handle_unknowns;
  for (std::uint32_t h : handles_) handle_unknowns.insert(handle_unknowns.end(), {2 * h, 2 * h + 1});
  factors_->p1 = MakePartition(2 * V, handle_unknowns);
  SparseMatrix g_ff;
  SplitBlocks(G, factors_->p1, &g_ff, &factors_->g_fh);
  factors_->g_ff.compute(g_ff);

  // Step 2: sum over triangle edges of ||(v_j - v_i) - e_ij||^2, per coordinate.
  Triplets h;
  for (const auto& t : triangles_)
    for (int k = 0; k < 3; ++k) {
      const int i = int(t[k]), j = int(t[(k + 1) % 3]);
      h.emplace_back(i, i, 1.0), h.emplace_back(j, j, 1.0), h.emplace_back(i, j, -1.0), h.emplace_back(j, i, -1.0);
    }
  SparseMatrix H(static_cast<Eigen::Index>(V), static_cast<Eigen::Index>(V));
  H.setFromTriplets(h.begin(), h.end());
  factors_->p2 = MakePartition(V, handles_);
  SparseMatrix h_ff;
  SplitBlocks(H, factors_->p2, &h_ff, &factors_->h_fh);
  factors_->h_ff.compute(h_ff);
  if (factors_->g_ff.info() != Eigen::Success || factors_->h_ff.info() != Eigen::Success)
    throw BakeError(file, "the deformation system is singular (is the mesh connected?)");
}

ArapDeformer::~ArapDeformer() = default;
ArapDeformer::ArapDeformer(ArapDeformer&&) noexcept = default;
ArapDeformer& ArapDeformer::operator=(ArapDeformer&&) noexcept = default;

void ArapDeformer::Deform(const std::vector<Eigen::Vector2d>& targets, Points* out, Points* similarity) const {
  const std::size_t V = rest_.size(), H = handles_.size();
  const Factors& f = *factors_;

  // Step 1: G_ff u = -G_fh q.
  Eigen::VectorXd q(2 * H);
  for (std::size_t a = 0; a < H; ++a)
    for (int d = 0; d < 2; ++d) q[f.p1.index[2 * handles_[a] + d]] = targets[a][d];
  const Eigen::VectorXd u = f.g_ff.solve(-(f.g_fh * q));
  Points step1(V);
  for (std::size_t v = 0; v < V; ++v)
    for (int d = 0; d < 2; ++d) {
      const std::size_t unknown = 2 * v + d;
      step1[v][d] = f.p1.is_handle[unknown] ? q[f.p1.index[unknown]] : u[f.p1.index[unknown]];
    }
  if (similarity) *similarity = step1;

  // Step 2a: each rest triangle rotated onto its step-1 image (2D Procrustes;
  // the rotation of the paper's similarity fit, with the scale dropped).
  // Step 2b: H_ff x = b_f - H_fh q per coordinate, b from the fitted edges.
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(V, 2);
  for (const auto& t : triangles_) {
    const Eigen::Vector2d cr = (rest_[t[0]] + rest_[t[1]] + rest_[t[2]]) / 3;
    const Eigen::Vector2d cd = (step1[t[0]] + step1[t[1]] + step1[t[2]]) / 3;
    double dot = 0, cross = 0;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d a = rest_[t[k]] - cr, s = step1[t[k]] - cd;
      dot += a.dot(s), cross += a.x() * s.y() - a.y() * s.x();
    }
    const Eigen::Rotation2Dd R(std::atan2(cross, dot));
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = t[k], j = t[(k + 1) % 3];
      const Eigen::Vector2d e = R * (rest_[j] - rest_[i]);
      b.row(i) -= e.transpose();
      b.row(j) += e.transpose();
    }
  }
  Eigen::MatrixXd b_free(f.p2.free_count, 2), q2(H, 2);
  for (std::size_t v = 0; v < V; ++v)
    if (!f.p2.is_handle[v]) b_free.row(f.p2.index[v]) = b.row(v);
  for (std::size_t a = 0; a < H; ++a) q2.row(f.p2.index[handles_[a]]) = targets[a].transpose();
  const Eigen::MatrixXd x = f.h_ff.solve(b_free - f.h_fh * q2);
  out->resize(V);
  for (std::size_t v = 0; v < V; ++v)
    (*out)[v] = f.p2.is_handle[v] ? Eigen::Vector2d(q2.row(f.p2.index[v]).transpose())
                                  : Eigen::Vector2d(x.row(f.p2.index[v]).transpose());
}

bool HandleVertex(const Points& mesh, const Triangles& triangles, const Eigen::Vector2d& point, double tolerance,
                  std::uint32_t* vertex) {
  // Distance from the point to each triangle (0 inside); keep the closest.
  double best = std::numeric_limits<double>::infinity();
  std::size_t best_triangle = 0;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const Eigen::Vector2d &a = mesh[triangles[t][0]], &b = mesh[triangles[t][1]], &c = mesh[triangles[t][2]];
    auto side = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
      return (q.x() - p.x()) * (r.y() - p.y()) - (r.x() - p.x()) * (q.y() - p.y());
    };
    double d = 0;
    if (side(a, b, point) < 0 || side(b, c, point) < 0 || side(c, a, point) < 0) {
      auto segment = [&](const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
        const double s = std::clamp((point - p).dot(q - p) / (q - p).squaredNorm(), 0.0, 1.0);
        return (p + s * (q - p) - point).norm();
      };
      d = std::min({segment(a, b), segment(b, c), segment(c, a)});
    }
    if (d < best) best = d, best_triangle = t;
  }
  if (!(best <= tolerance)) return false;
  const auto& t = triangles[best_triangle];
  *vertex = *std::min_element(t.begin(), t.end(), [&](std::uint32_t u, std::uint32_t v) {
    return (mesh[u] - point).squaredNorm() < (mesh[v] - point).squaredNorm();
  });
  return true;
}

}  // namespace posemorph::bake
