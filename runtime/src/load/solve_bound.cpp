// SPDX-License-Identifier: MIT
// The solve's worst case, bounded at load: every stored value can be within
// its limit and the factor still amplify the solve beyond any float (factor
// values of 1e3 gave positions near 7.9e303). So the loader bounds what the
// rigid solve can give for any weights the jobs accept (|w| <= kMaxJobWeight)
// and refuses the rig when that bound passes kMaxPosition; the jobs' own
// check of their output stays as a second line of defence.
//
// First a rigorous bound, per coordinate, with W = kMaxJobWeight and sums
// of absolute values where the jobs sum signed ones (rounding of the real
// sums moves them by a relative 1e-13 at most; the limit is many orders
// beyond any honest rig's bound):
// - blended stretch of triangle t: |s_ab| <= W sum_i max_ab |S_{t,i,ab}|;
//   target matrix A = R(alpha) S: each entry <= 2 max |s_ab| (|cos|, |sin| <= 1);
// - right-hand side of unknown u (vertex u + 1): |b_u| <= sum over the
//   corners of u's triangles of (|g0| + |g1|) max |A|;
// - L y = P b: |y_i| <= |b'_i| + sum_j |L_ij| |y_j|, forward by columns;
//   L^T x = D^-1 y: |x_j| <= d_j^-1 |y_j| + sum_i |L_ij| |x_i|, backward;
// - the centroid shift adds at most W sum_i |c_i| + sum_v |m_v| max |x|.
// Every rig the bake writes for the samples bounds at 3e7 to 8e11 this way,
// a 90,000-vertex grid at 1.4e11. But where the real solve's signs cancel
// and |L|'s do not (a thin spiral of 20,000 outline points, whose triangles
// are obtuse), the absolute bound overflows for an honest rig. There the
// loader estimates ||(L D L^T)^-1||_inf instead (Hager's estimator with
// Higham's refinement: a few solves, usually within a factor of 3 of the
// norm, never above it) and refuses when the estimate times the largest
// right-hand side, with a margin of kEstimateMargin, passes kMaxPosition:
// the factors that amplify a solve beyond any float (values of 1e3: an
// estimate near 1e300) are refused either way.
#include <algorithm>
#include <cmath>

#include "loader.h"
#include "posemorph/jobs.h"

namespace posemorph {

using namespace detail::load;  // NOLINT(google-build-using-namespace): the loader's own types

namespace {

// How far Hager's estimate may fall short of the norm and still refuse the
// factors it must (it is usually within a factor of 3).
constexpr double kEstimateMargin = 1e6;

// (L D L^T)^-1 v in place, over the factor's own n unknowns in its order;
// false when it is not finite. (The loader has not set f.n yet.)
bool SolveInPlace(const detail::SolveLayout& f, std::uint32_t n, double* v) {
  for (std::uint32_t j = 0; j < n; ++j)
    for (std::uint32_t q = f.col_start[j]; q < f.col_start[j + 1]; ++q) v[f.row[q]] -= f.value[q] * v[j];
  bool finite = true;
  for (std::uint32_t j = n; j-- > 0;) {
    double x = v[j] * f.inv_diagonal[j];
    for (std::uint32_t q = f.col_start[j]; q < f.col_start[j + 1]; ++q) x -= f.value[q] * v[f.row[q]];
    v[j] = x;
    finite = finite && std::fabs(x) <= 1e300;
  }
  return finite;
}

// An estimate of ||(L D L^T)^-1||_1 (= its infinity norm: it is symmetric)
// from below; infinity when a solve overflows. v: n scratch.
double EstimateInverseNorm(const detail::SolveLayout& f, std::uint32_t n, double* v) {
  double estimate = 0;
  std::int64_t unit = -1;  // the current x: uniform 1/n, or e_unit
  for (int iteration = 0; iteration < 5; ++iteration) {
    for (std::uint32_t i = 0; i < n; ++i) v[i] = unit < 0 ? 1.0 / n : (std::int64_t(i) == unit ? 1.0 : 0.0);
    if (!SolveInPlace(f, n, v)) return INFINITY;
    double norm = 0;
    for (std::uint32_t i = 0; i < n; ++i) norm += std::fabs(v[i]);
    if (iteration > 0 && norm <= estimate) break;
    estimate = norm;
    for (std::uint32_t i = 0; i < n; ++i) v[i] = v[i] >= 0 ? 1.0 : -1.0;
    if (!SolveInPlace(f, n, v)) return INFINITY;
    std::uint32_t largest = 0;
    double along_x = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
      if (std::fabs(v[i]) > std::fabs(v[largest])) largest = i;
      along_x += unit < 0 ? v[i] / n : 0;
    }
    if (unit >= 0) along_x = v[unit];
    if (std::fabs(v[largest]) <= along_x || std::int64_t(largest) == unit) break;
    unit = largest;
  }
  // Higham's alternating vector catches what the iteration can miss.
  for (std::uint32_t i = 0; i < n; ++i) v[i] = (i % 2 ? -1.0 : 1.0) * (1 + (n > 1 ? double(i) / (n - 1) : 0.0));
  if (!SolveInPlace(f, n, v)) return INFINITY;
  double alternating = 0;
  for (std::uint32_t i = 0; i < n; ++i) alternating += std::fabs(v[i]);
  return std::max(estimate, 2 * alternating / (3.0 * n));
}

}  // namespace

bool RigLoader::CheckSolveBound(const Counts& c, const Scratch& scratch, const Rig& rig, Error* err) {
  const std::uint64_t V = c.V, T = c.T, N = c.N, n = c.n;
  if (n == 0) return true;
  double* bound = scratch.solve_bound;     // n: the right-hand side, then y, then x
  std::uint32_t* slot = scratch.row_fill;  // n, free after the transpose: where unknown u sits in P b
  for (std::uint64_t k = 0; k < n; ++k) slot[rig.solve_.order[k]] = std::uint32_t(k);
  for (std::uint64_t k = 0; k < n; ++k) bound[k] = 0;
  const double W = kMaxJobWeight;
  for (std::uint64_t t = 0; t < T; ++t) {
    double stretch = 0;
    for (std::uint64_t i = 0; i < N; ++i) {
      const double* s = rig.stretches_.data + 3 * (t * N + i);
      stretch += std::max({std::fabs(s[0]), std::fabs(s[1]), std::fabs(s[2])});
    }
    const double a = 2 * W * stretch;  // every entry of the target matrix
    const std::uint32_t* tri = rig.triangles_.data + 3 * t;
    const double* g = rig.gradients_.data + 6 * t;
    for (int k = 0; k < 3; ++k)
      if (tri[k] != 0) bound[slot[tri[k] - 1]] += (std::fabs(g[2 * k]) + std::fabs(g[2 * k + 1])) * a;
  }
  double rhs = 0;  // the largest right-hand side
  for (std::uint64_t k = 0; k < n; ++k) rhs = std::max(rhs, bound[k]);
  const std::uint32_t* col = rig.solve_.col_start.data;
  const std::uint32_t* row = rig.solve_.row.data;
  const double* value = rig.solve_.value.data;
  for (std::uint64_t j = 0; j < n; ++j)
    for (std::uint32_t q = col[j]; q < col[j + 1]; ++q) bound[row[q]] += std::fabs(value[q]) * bound[j];
  double largest = 0;
  for (std::uint64_t j = n; j-- > 0;) {
    double x = rig.solve_.inv_diagonal[j] * bound[j];
    for (std::uint32_t q = col[j]; q < col[j + 1]; ++q) x += std::fabs(value[q]) * bound[row[q]];
    bound[j] = x;
    if (!(x <= kMaxPosition)) {  // (also a NaN, from inf * 0)
      largest = x;
      break;
    }
    largest = std::max(largest, x);
  }
  double mass = 0, centroid = 0;
  for (std::uint64_t v = 0; v < V; ++v) mass += std::fabs(rig.vertex_masses_[v]);
  for (std::uint64_t i = 0; i < N; ++i)
    centroid = std::max({centroid, std::fabs(rig.pose_centroids_[2 * i]), std::fabs(rig.pose_centroids_[2 * i + 1])});
  const double shift = W * double(N) * centroid;
  const double worst = largest * (1 + mass) + shift;
  if (worst <= kMaxPosition) return true;
  // The absolute bound does not hold it: the estimate.
  const double estimate = EstimateInverseNorm(rig.solve_, std::uint32_t(n), bound) * rhs * (1 + mass) + shift;
  if (estimate * kEstimateMargin <= kMaxPosition) return true;
  return Fail(err, ErrorCode::kBadValue,
              "the factor can amplify the solve beyond %g (positions estimated up to %.3g for weights up to %g): "
              "a frame would not be finite",
              kMaxPosition, estimate, kMaxJobWeight);
}

}  // namespace posemorph
