// SPDX-License-Identifier: MIT
// Mapping by deformation (mesh_registration.h): pose 0's mesh made alone,
// then deformed onto every other pose by Newton steps on the symmetric
// Dirichlet energy with the boundary pulled to its targets.
#include "posemorph/bake/mapping/mesh_registration.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <limits>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "posemorph/bake/run_each.h"
#include "refiner.h"

namespace posemorph::bake::mapping {
namespace {

using refine::EdgeMap;
using refine::Key;
using refine::Tri;
using Vec4 = Eigen::Matrix<double, 4, 1>;
using Mat4 = Eigen::Matrix4d;
using Mat46 = Eigen::Matrix<double, 4, 6>;

constexpr double kResidual = 1e-4;   // boundary within this share of the mean edge of its target
constexpr double kFirstWeight = 1;   // the boundary's pull at first, against a triangle's energy
constexpr double kLastWeight = 1e9;  // and at most
constexpr int kStepsPerWeight = 40;  // Newton steps at each weight, at most
constexpr int kPathSteps = 8;        // steps along the boundary's path, when the straight pull gets stuck
constexpr double kPathWeight = 1e4;  // the pull at each step but the last

bool OnBoundary(const std::vector<bool>& boundary, std::uint64_t key) {
  return boundary[key >> 32] && boundary[key & 0xffffffffu];
}

// Vertices on an edge that only one triangle uses.
std::vector<bool> MeshBoundary(const CompatibleMesh& m) {
  std::vector<bool> on(m.vertices[0].size(), false);
  for (const auto& [key, ts] : EdgeMap(m.triangles).at)
    if (ts[1] == EdgeMap::kNone) on[key >> 32] = on[key & 0xffffffffu] = true;
  return on;
}

// Splits every interior edge whose ends both lie on the boundary (a chord):
// afterwards every triangle has a vertex off the boundary, free to follow.
void SplitChords(CompatibleMesh& m) {
  refine::Refiner r(m, std::numeric_limits<std::size_t>::max());
  for (bool split = true; split;) {
    split = false;
    const std::vector<bool> boundary = MeshBoundary(m);
    const EdgeMap em(m.triangles);
    for (const auto& [key, ts] : em.at)
      if (ts[1] != EdgeMap::kNone && OnBoundary(boundary, key) && r.SplitEdge(key >> 32, key & 0xffffffffu, em)) {
        split = true;
        break;  // the edge map is stale now
      }
  }
}

// Where every boundary vertex of `m` (pose 0 alone, its first K vertices the
// polygon's corners) goes in `polygon`: the corners to their corners, each
// vertex between two corners at the same share of the way along the edge.
std::vector<std::pair<std::size_t, Point>> BoundaryTargets(const CompatibleMesh& m, std::size_t K,
                                                           const Polygon& polygon) {
  std::vector<std::size_t> next(m.vertices[0].size(), EdgeMap::kNone);
  for (const auto& [key, ts] : EdgeMap(m.triangles).at) {
    if (ts[1] != EdgeMap::kNone) continue;
    Tri t = m.triangles[ts[0]];
    refine::EdgeFirst(t, key >> 32, key & 0xffffffffu);
    next[t[0]] = t[1];  // counter-clockwise along the outline
  }
  const Polygon& p0 = m.vertices[0];
  std::vector<std::pair<std::size_t, Point>> targets;
  for (std::size_t corner = 0; corner < K; ++corner) {
    targets.emplace_back(corner, polygon[corner]);
    std::vector<std::size_t> chain;
    std::vector<double> along{0};
    std::size_t v = corner;
    for (std::size_t guard = 0; guard < p0.size(); ++guard) {
      const std::size_t w = next[v];
      along.push_back(along.back() + (p0[w] - p0[v]).norm());
      if (w < K) break;
      chain.push_back(w);
      v = w;
    }
    const Point &a = polygon[corner], &b = polygon[(corner + 1) % K];
    for (std::size_t j = 0; j < chain.size(); ++j)
      targets.emplace_back(chain[j], refine::OnEdgeOrOutside(a, b, a + (b - a) * (along[j + 1] / along.back())));
  }
  return targets;
}

// Where a closed boundary (points in order round it) is a share t of the
// way from `from` to `to` when each edge turns by its own angle (unwrapped
// along the boundary, so that neighbouring edges turn alike) and stretches
// evenly: edges integrated from the first point's straight path, the gap
// left at the end spread along the loop.
std::vector<Eigen::Vector2d> BoundaryPath(const std::vector<Eigen::Vector2d>& from,
                                          const std::vector<Eigen::Vector2d>& to, double t) {
  const std::size_t n = from.size();
  std::vector<Eigen::Vector2d> edges(n);
  double previous = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d a = from[(i + 1) % n] - from[i], b = to[(i + 1) % n] - to[i];
    double turn = std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
    if (i > 0) turn += 2 * M_PI * std::nearbyint((previous - turn) / (2 * M_PI));
    previous = turn;
    const double length = (1 - t) * a.norm() + t * b.norm();
    const double angle = std::atan2(a.y(), a.x()) + t * turn;
    edges[i] = length * Eigen::Vector2d(std::cos(angle), std::sin(angle));
  }
  std::vector<Eigen::Vector2d> at(n);
  at[0] = (1 - t) * from[0] + t * to[0];
  Eigen::Vector2d gap = Eigen::Vector2d::Zero();  // where the loop ends, less where it began: zero when closed
  for (std::size_t i = 0; i < n; ++i) gap += edges[i];
  for (std::size_t i = 1; i < n; ++i) at[i] = at[i - 1] + edges[i - 1] - gap / double(n);
  return at;
}

// The symmetric Dirichlet energy of one triangle's map J (infinite when it
// turns over), with its gradient and positive semi-definite Hessian in
// vec(J) = (J00, J01, J10, J11).
double Dirichlet(const Eigen::Matrix2d& J, Vec4* gradient, Mat4* hessian) {
  const double det = J.determinant();
  if (!(det > 0)) return std::numeric_limits<double>::infinity();
  const double f = J.squaredNorm(), g = 1 + 1 / (det * det);
  if (!gradient) return f * g;
  const Vec4 j(J(0, 0), J(0, 1), J(1, 0), J(1, 1));
  const Vec4 cof(J(1, 1), -J(1, 0), -J(0, 1), J(0, 0));  // d det / d vec(J)
  const Vec4 df = 2 * j, dg = -2 / (det * det * det) * cof;
  *gradient = g * df + f * dg;
  Mat4 hdet = Mat4::Zero();
  hdet(0, 3) = hdet(3, 0) = 1;
  hdet(1, 2) = hdet(2, 1) = -1;
  const Mat4 ddg = 6 / (det * det * det * det) * cof * cof.transpose() - 2 / (det * det * det) * hdet;
  const Mat4 h = 2 * g * Mat4::Identity() + df * dg.transpose() + dg * df.transpose() + f * ddg;
  Eigen::SelfAdjointEigenSolver<Mat4> eigen(h);
  *hessian = eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0).asDiagonal() * eigen.eigenvectors().transpose();
  return f * g;
}

struct Deformation {
  std::vector<Tri> triangles;
  std::vector<double> area;                                      // pose 0, normalised
  std::vector<Eigen::Matrix2d> inverse;                          // pose 0's edge matrix, inverted
  std::vector<std::pair<std::size_t, Eigen::Vector2d>> targets;  // normalised
  // The Hessian's sparsity is the same at every step (each triangle's
  // blocks and the whole diagonal, whatever the targets), so its fill-
  // reducing ordering is found once: the same factor, bit for bit, without
  // the ordering each step (a tenth of a large failing bake's time).
  mutable Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
  mutable bool ordered = false;

  Eigen::Matrix2d Edges(const Eigen::VectorXd& y, const Tri& t) const {
    Eigen::Matrix2d d;
    d.col(0) = y.segment<2>(2 * t[1]) - y.segment<2>(2 * t[0]);
    d.col(1) = y.segment<2>(2 * t[2]) - y.segment<2>(2 * t[0]);
    return d;
  }
  double Energy(const Eigen::VectorXd& y, double w) const {
    double e = 0;
    for (std::size_t t = 0; t < triangles.size(); ++t)
      e += area[t] * Dirichlet(Edges(y, triangles[t]) * inverse[t], nullptr, nullptr);
    for (const auto& [v, target] : targets) e += w * (y.segment<2>(2 * v) - target).squaredNorm();
    return e;
  }
  // The largest step along d (at most 1) that keeps every triangle from
  // reaching zero area, with a margin.
  double LargestStep(const Eigen::VectorXd& y, const Eigen::VectorXd& d) const {
    double step = 1;
    for (const Tri& t : triangles) {
      const Eigen::Matrix2d a = Edges(y, t), b = Edges(d, t);
      // det(a + s b) = c0 + c1 s + c2 s^2
      const double c0 = a.determinant(), c2 = b.determinant();
      const double c1 = a(0, 0) * b(1, 1) + b(0, 0) * a(1, 1) - a(0, 1) * b(1, 0) - b(0, 1) * a(1, 0);
      double root = std::numeric_limits<double>::infinity();
      if (std::abs(c2) < 1e-300) {
        if (c1 < 0) root = -c0 / c1;
      } else {
        const double disc = c1 * c1 - 4 * c2 * c0;
        if (disc >= 0) {
          const double q = -0.5 * (c1 + std::copysign(std::sqrt(disc), c1));
          for (double r : {q / c2, q != 0 ? c0 / q : -1.0})
            if (r > 0) root = std::min(root, r);
        }
      }
      step = std::min(step, 0.8 * root);
    }
    return step;
  }
  // One Newton step at weight w; false when it no longer lowers the energy.
  bool Step(Eigen::VectorXd& y, double w) const {
    const Eigen::Index n = y.size();
    Eigen::VectorXd grad = Eigen::VectorXd::Zero(n);
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(triangles.size() * 36 + targets.size() * 2 + std::size_t(n));
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      const Tri& tri = triangles[t];
      const Eigen::Matrix2d& m = inverse[t];
      Mat46 B = Mat46::Zero();  // d vec(J) / d (x0, y0, x1, y1, x2, y2)
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) {
          B(2 * i + j, 2 + i) = m(0, j);
          B(2 * i + j, 4 + i) = m(1, j);
          B(2 * i + j, i) = -(m(0, j) + m(1, j));
        }
      Vec4 gj;
      Mat4 hj;
      Dirichlet(Edges(y, tri) * m, &gj, &hj);
      const Eigen::Matrix<double, 6, 1> gx = area[t] * B.transpose() * gj;
      const Eigen::Matrix<double, 6, 6> hx = area[t] * B.transpose() * hj * B;
      for (int a = 0; a < 6; ++a) {
        const Eigen::Index ra = Eigen::Index(2 * tri[std::size_t(a / 2)] + std::size_t(a % 2));
        grad[ra] += gx[a];
        for (int b = 0; b < 6; ++b)
          entries.emplace_back(ra, Eigen::Index(2 * tri[std::size_t(b / 2)] + std::size_t(b % 2)), hx(a, b));
      }
    }
    for (const auto& [v, target] : targets) {
      grad.segment<2>(2 * Eigen::Index(v)) += 2 * w * (y.segment<2>(2 * Eigen::Index(v)) - target);
      for (int c = 0; c < 2; ++c) entries.emplace_back(2 * Eigen::Index(v) + c, 2 * Eigen::Index(v) + c, 2 * w);
    }
    for (Eigen::Index i = 0; i < n; ++i) entries.emplace_back(i, i, 1e-8);
    Eigen::SparseMatrix<double> H(n, n);
    H.setFromTriplets(entries.begin(), entries.end());
    if (!ordered) solver.analyzePattern(H), ordered = true;
    solver.factorize(H);
    if (solver.info() != Eigen::Success) return false;
    const Eigen::VectorXd d = solver.solve(-grad);
    const double slope = grad.dot(d);
    if (!(slope < 0) || !d.allFinite()) return false;
    const double before = Energy(y, w);
    double step = LargestStep(y, d);
    for (int halvings = 0; halvings < 40; ++halvings, step /= 2) {
      const Eigen::VectorXd trial = y + step * d;
      const double after = Energy(trial, w);
      if (after <= before + 1e-4 * step * slope) {
        y = trial;
        return before - after > 1e-12 * before;
      }
    }
    return false;
  }
  double LargestResidual(const Eigen::VectorXd& y) const {
    double r = 0;
    for (const auto& [v, target] : targets) r = std::max(r, (y.segment<2>(2 * Eigen::Index(v)) - target).norm());
    return r;
  }
};

// Pose 0's mesh deformed onto `targets` (grid); the interior on the grid
// too. False when a boundary vertex cannot reach its target or a triangle
// turns over on the grid.
// `give_up`: whether to stop now, as not reached (another pose has failed).
bool Deform(const CompatibleMesh& m0, const std::vector<std::pair<std::size_t, Point>>& targets, Polygon* out,
            const std::function<bool()>& give_up) {
  const Polygon& p0 = m0.vertices[0];
  Point centre = Point::Zero();
  for (const Point& p : p0) centre += p;
  centre /= double(p0.size());
  double edge = 0;
  for (const Tri& t : m0.triangles)
    for (int e = 0; e < 3; ++e) edge += (p0[t[std::size_t(e)]] - p0[t[std::size_t((e + 1) % 3)]]).norm();
  edge /= 3 * double(m0.triangles.size());
  const Eigen::Index n = Eigen::Index(2 * p0.size());
  Eigen::VectorXd x(n);
  for (std::size_t v = 0; v < p0.size(); ++v) x.segment<2>(2 * Eigen::Index(v)) = (p0[v] - centre) / edge;

  Deformation d;
  d.triangles = m0.triangles;
  for (const Tri& t : m0.triangles) {
    const Eigen::Matrix2d e = d.Edges(x, t);
    d.area.push_back(e.determinant() / 2);
    d.inverse.push_back(e.inverse());
  }
  for (const auto& [v, target] : targets) d.targets.emplace_back(v, (target - centre) / edge);

  // The similarity that fits the boundary to its targets best (least squares).
  Eigen::Vector2d xm = Eigen::Vector2d::Zero(), tm = Eigen::Vector2d::Zero();
  for (const auto& [v, target] : d.targets) xm += x.segment<2>(2 * Eigen::Index(v)), tm += target;
  xm /= double(d.targets.size());
  tm /= double(d.targets.size());
  double a = 0, b = 0, norm = 0;
  for (const auto& [v, target] : d.targets) {
    const Eigen::Vector2d p = x.segment<2>(2 * Eigen::Index(v)) - xm, q = target - tm;
    a += p.dot(q);
    b += p.x() * q.y() - p.y() * q.x();
    norm += p.squaredNorm();
  }
  if (!(a * a + b * b > 0)) return false;
  Eigen::Matrix2d similarity;
  similarity << a / norm, -b / norm, b / norm, a / norm;
  Eigen::VectorXd y(n);
  for (Eigen::Index v = 0; v < n / 2; ++v) y.segment<2>(2 * v) = similarity * (x.segment<2>(2 * v) - xm) + tm;

  auto pull = [&](double last_weight) {
    bool reached = false;
    for (double w = kFirstWeight; w <= last_weight && !reached; w *= 10) {
      if (give_up()) return false;
      for (int s = 0; s < kStepsPerWeight; ++s)
        if (!d.Step(y, w)) break;
      reached = d.LargestResidual(y) <= kResidual;
    }
    return reached;
  };
  const Eigen::VectorXd start = y;
  if (!pull(kLastWeight)) {
    // Pulled straight at its targets, the boundary got stuck (a limb that
    // must unwind, turning further than the pull lets a triangle follow):
    // the targets are moved there in steps along the boundary's
    // as-rigid-as-possible path, each edge turning and stretching evenly.
    y = start;
    std::vector<Eigen::Vector2d> from, to;
    for (const auto& [v, target] : d.targets) {
      from.push_back(y.segment<2>(2 * Eigen::Index(v)));
      to.push_back(target);
    }
    bool reached = false;
    for (int step = 1; step <= kPathSteps; ++step) {
      const std::vector<Eigen::Vector2d> at = BoundaryPath(from, to, double(step) / kPathSteps);
      for (std::size_t i = 0; i < at.size(); ++i) d.targets[i].second = at[i];
      reached = pull(step == kPathSteps ? kLastWeight : kPathWeight);
      if (give_up()) return false;
    }
    if (!reached) return false;
  }
  Polygon& p = *out;
  p.assign(p0.size(), Point::Zero());
  for (std::size_t v = 0; v < p0.size(); ++v) p[v] = Snap(y.segment<2>(2 * Eigen::Index(v)) * edge + centre);
  for (const auto& [v, target] : targets) p[v] = target;
  for (const Tri& t : m0.triangles)
    if (!refine::Positive(p, t)) return false;
  return true;
}

}  // namespace

CompatibleMesh RegisterCompatibly(const std::vector<Polygon>& polygons, const RefinementParameters& parameters,
                                  const std::vector<ErrorSource>& poses, std::size_t max_steiner_points) {
  const std::size_t N = polygons.size(), K = polygons[0].size();
  CompatibleMesh m0 = TriangulateCompatibly({polygons[0]}, poses[0], max_steiner_points);
  RefinementParameters alone = parameters;
  alone.collapse_slivers = false;  // the corners stay: they carry the correspondence
  RefineCompatibly(m0, alone);
  SplitChords(m0);

  CompatibleMesh mesh;
  mesh.triangles = m0.triangles;
  mesh.boundary_vertices = m0.boundary_vertices;
  mesh.steiner_points = m0.steiner_points;  // as triangulated; the refinement adds the rest, as it does anyway
  mesh.vertices.resize(N);
  mesh.vertices[0] = m0.vertices[0];
  std::vector<char> reached(N, 1);
  // The first pose (by index) that cannot be reached is the one reported:
  // once one fails, the poses after it stop (their outcome cannot change
  // the message), those before it go on.
  std::atomic<std::size_t> first_failed{N};
  RunEach(N - 1, parameters.threads, [&](std::size_t i) {
    const std::size_t k = i + 1;
    reached[k] =
        Deform(m0, BoundaryTargets(m0, K, polygons[k]), &mesh.vertices[k], [&] { return first_failed.load() < k; }) ? 1
                                                                                                                    : 0;
    if (!reached[k]) {
      std::size_t seen = first_failed.load();
      while (k < seen && !first_failed.compare_exchange_weak(seen, k)) {
      }
    }
  });
  for (std::size_t k = 1; k < N; ++k)
    if (!reached[k])
      throw poses[k].Error(
          "the first pose's mesh cannot be deformed onto this pose's outline without turning a triangle over");
  return mesh;
}

}  // namespace posemorph::bake::mapping
