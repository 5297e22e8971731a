// SPDX-License-Identifier: MIT
// Boundary correspondence (paper section 3.1, after Baxter et al. 2009): every
// outline i > 0 is matched to pose 0's between consecutive user landmarks by
// dynamic programming over bending (difference of turning angles) and
// stretch (a cost per step that advances on one outline only).
#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry.h"
#include "posemorph/bake/mapping/boundary_matching.h"

namespace posemorph::bake::mapping {
namespace {

double WrapAngle(double a) {
  while (a > M_PI) a -= 2 * M_PI;
  while (a < -M_PI) a += 2 * M_PI;
  return a;
}

// An outline with its cumulative edge lengths, for evaluation by arc length.
struct ArcLength {
  const Polygon& p;
  std::vector<double> c;
  explicit ArcLength(const Polygon& outline) : p(outline), c(CumulativeArcLength(outline)) {}
  Point At(double s) const {
    const double P = c.back();
    s = std::fmod(s, P);
    if (s < 0) s += P;
    const std::size_t i = std::min<std::size_t>(std::upper_bound(c.begin(), c.end(), s) - c.begin() - 1, p.size() - 1);
    const double len = c[i + 1] - c[i];
    const double t = len > 0 ? (s - c[i]) / len : 0;
    return p[i] + t * (p[(i + 1) % p.size()] - p[i]);
  }
};

// Turning angle of the outline at arc length s over +-h.
double Turning(const ArcLength& outline, double s, double h) {
  const Point a = outline.At(s - h), b = outline.At(s), c = outline.At(s + h);
  const Point u = b - a, v = c - b;
  return std::atan2(u.x() * v.y() - u.y() * v.x(), u.dot(v));
}

// Fractions u_0 = 0 < u_1 < ... < u_{m-1} < 1 from possibly repeated averages.
void MakeStrictlyIncreasing(std::vector<double>& u) {
  const std::size_t m = u.size();
  u[0] = 0;
  for (std::size_t j = 1; j < m; ++j) {
    if (u[j] > u[j - 1] && u[j] < 1) continue;
    std::size_t e = j;
    while (e < m && !(u[e] > u[j - 1] && u[e] < 1)) ++e;
    const double hi = e < m ? u[e] : 1.0;
    for (std::size_t k = j; k < e; ++k) u[k] = u[j - 1] + (hi - u[j - 1]) * double(k - j + 1) / double(e - j + 1);
  }
}

// The fractions u (u[0] = 0, the stretch's end at 1) averaged over up to w
// neighbours on each side, the window narrowed near the ends so that they
// stay where the landmarks are; strictly increasing again after.
void SmoothCorrespondence(std::vector<double>& u, int w) {
  const std::size_t m = u.size();
  std::vector<double> v(u);
  for (std::size_t j = 1; j < m; ++j) {
    const std::size_t r = std::min({std::size_t(w), j, m - j});
    double sum = 0;
    for (std::size_t k = j - r; k <= j + r; ++k) sum += k < m ? u[k] : 1.0;
    v[j] = sum / double(2 * r + 1);
  }
  u = std::move(v);
  MakeStrictlyIncreasing(u);
}

}  // namespace

std::vector<double> CumulativeArcLength(const Polygon& p) {
  std::vector<double> c(p.size() + 1, 0);
  for (std::size_t i = 0; i < p.size(); ++i) c[i + 1] = c[i] + (p[(i + 1) % p.size()] - p[i]).norm();
  return c;
}

Point PointAtArcLength(const Polygon& outline, double s) { return ArcLength(outline).At(s); }

double NearestArcLength(const Polygon& outline, const Point& q, double* distance) {
  const std::vector<double> c = CumulativeArcLength(outline);
  double best = std::numeric_limits<double>::infinity(), at = 0;
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const Point &a = outline[i], &b = outline[(i + 1) % outline.size()];
    const Point ab = b - a;
    const double l2 = ab.squaredNorm();
    const double t = l2 > 0 ? std::clamp((q - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
    const double d = (a + t * ab - q).norm();
    if (d < best) best = d, at = c[i] + t * (c[i + 1] - c[i]);
  }
  if (distance) *distance = best;
  return at;
}

namespace {

// The matching of one segment between two landmarks: the cheapest monotone
// path from pose 0's m samples to pose i's (turning angles theta0, theta;
// lambda per skipped sample), as the fraction of pose i's segment that each
// of pose 0's samples lands on, strictly increasing.
std::vector<double> MatchSegment(const std::vector<double>& theta0, const std::vector<double>& theta, double lambda) {
  const std::size_t m = theta0.size() - 1;
  // D(j, q): cheapest monotone path from (0, 0) to (j, q), kept one row
  // of j at a time; the steps taken are kept whole for the backtrack.
  const std::size_t W = m + 1;
  std::vector<double> before(W, std::numeric_limits<double>::infinity()), row(W);
  std::vector<unsigned char> from(W * W, 0);  // 0 diagonal, 1 from j-1, 2 from q-1
  for (std::size_t j = 0; j <= m; ++j) {
    for (std::size_t q = 0; q <= m; ++q) {
      const double cost = std::abs(WrapAngle(theta0[j] - theta[q]));
      if (j == 0 && q == 0) {
        row[0] = cost;
        continue;
      }
      double best = std::numeric_limits<double>::infinity();
      unsigned char step = 0;
      if (j > 0 && q > 0 && before[q - 1] < best) best = before[q - 1], step = 0;
      if (j > 0 && before[q] + lambda < best) best = before[q] + lambda, step = 1;
      if (q > 0 && row[q - 1] + lambda < best) best = row[q - 1] + lambda, step = 2;
      row[q] = best + cost;
      from[j * W + q] = step;
    }
    std::swap(before, row);
  }
  std::vector<double> sum(m + 1, 0), count(m + 1, 0);
  for (std::size_t j = m, q = m;;) {
    sum[j] += double(q), count[j] += 1;
    if (j == 0 && q == 0) break;
    const unsigned char step = from[j * W + q];
    if (step == 0)
      --j, --q;
    else if (step == 1)
      --j;
    else
      --q;
  }
  std::vector<double> u(m);
  for (std::size_t j = 0; j < m; ++j) u[j] = sum[j] / count[j] / double(m);
  MakeStrictlyIncreasing(u);
  return u;
}

// Where the matching advanced far on one outline between two neighbouring
// samples, chords there would cut through that shape: add samples in every
// pose, spread evenly over each pose's own stretch.
void Densify(const std::vector<double>& perimeter, double spacing, CorrespondedBoundary& out) {
  const std::size_t N = perimeter.size();
  const std::size_t M = out.at[0].size();
  double longest = 0;
  for (double p : perimeter) longest = std::max(longest, p);
  const double dense_spacing = std::max(spacing, longest / double(kMaxMatchedSamples));
  std::vector<std::vector<double>> dense(N);
  std::vector<std::size_t> dense_landmarks;
  std::size_t next_landmark = 0;
  for (std::size_t j = 0; j < M; ++j) {
    if (next_landmark < out.landmarks.size() && out.landmarks[next_landmark] == j) {
      dense_landmarks.push_back(dense[0].size());
      ++next_landmark;
    }
    double gap = 0;
    std::vector<double> from(N), to(N);
    for (std::size_t i = 0; i < N; ++i) {
      from[i] = out.at[i][j];
      to[i] = j + 1 < M ? out.at[i][j + 1] : out.at[i][0] + perimeter[i];
      while (to[i] < from[i]) to[i] += perimeter[i];
      gap = std::max(gap, to[i] - from[i]);
    }
    const std::size_t pieces = std::max<std::size_t>(1, std::size_t(std::ceil(gap / (1.5 * dense_spacing))));
    for (std::size_t p = 0; p < pieces; ++p)
      for (std::size_t i = 0; i < N; ++i) dense[i].push_back(from[i] + (to[i] - from[i]) * double(p) / double(pieces));
  }
  out.at = std::move(dense);
  out.landmarks = std::move(dense_landmarks);
}

}  // namespace

StartAlignment AlignStart(const Polygon& outline0, const Point& start0, const Polygon& outline, const Point& start) {
  constexpr std::size_t K = 256;
  auto turning = [](const Polygon& p, const Point& from) {
    const ArcLength arc(p);
    const double perimeter = CumulativeArcLength(p).back();
    const double s0 = NearestArcLength(p, from, nullptr), h = perimeter / double(K) * 8;
    std::vector<double> theta(K);
    for (std::size_t j = 0; j < K; ++j) theta[j] = Turning(arc, s0 + perimeter * double(j) / double(K), h);
    return theta;
  };
  const std::vector<double> a = turning(outline0, start0), b = turning(outline, start);
  StartAlignment r;
  const double s = NearestArcLength(outline, start, nullptr), perimeter = CumulativeArcLength(outline).back();
  r.best_cost = std::numeric_limits<double>::infinity();
  for (std::size_t shift = 0; shift < K; ++shift) {
    double cost = 0;
    for (std::size_t j = 0; j < K; ++j) cost += std::abs(WrapAngle(a[j] - b[(j + shift) % K]));
    cost /= double(K);
    if (shift == 0) r.cost_at_start = cost;
    if (cost < r.best_cost) r.best_cost = cost, r.best_shift = double(shift) / double(K);
  }
  r.best_start = s + r.best_shift * perimeter;
  return r;
}

CorrespondedBoundary MatchBoundaries(const std::vector<Polygon>& outlines,
                                     const std::vector<std::vector<Point>>& landmarks, const MatchingParameters& prm) {
  const std::size_t N = outlines.size(), L = landmarks[0].size();
  std::vector<std::vector<double>> s(N, std::vector<double>(L));  // landmark arc lengths, unwrapped increasing
  std::vector<double> perimeter(N);
  for (std::size_t i = 0; i < N; ++i) {
    perimeter[i] = CumulativeArcLength(outlines[i]).back();
    for (std::size_t k = 0; k < L; ++k) {
      s[i][k] = NearestArcLength(outlines[i], landmarks[i][k], nullptr);
      while (k > 0 && s[i][k] <= s[i][k - 1]) s[i][k] += perimeter[i];
    }
  }

  std::vector<ArcLength> arc;
  for (const Polygon& o : outlines) arc.emplace_back(o);
  CorrespondedBoundary out;
  out.points.resize(N);
  out.at.resize(N);
  const double lambda = prm.stretch_cost;
  // Long outlines (or a tiny spacing) get kMaxMatchedSamples samples at most.
  const double spacing = std::max(prm.spacing, perimeter[0] / double(kMaxMatchedSamples));
  out.spacing = spacing;
  for (std::size_t k = 0; k < L; ++k) {
    const double len0 = (k + 1 < L ? s[0][k + 1] : s[0][0] + perimeter[0]) - s[0][k];
    const std::size_t m =
        std::max<std::size_t>(4, std::size_t(std::lround(std::min(len0 / spacing, double(kMaxMatchedSamples)))));
    out.landmarks.push_back(out.at[0].size());
    const double h0 = len0 / double(m) * prm.bending_scale;
    std::vector<double> theta0(m + 1);
    for (std::size_t j = 0; j <= m; ++j) theta0[j] = Turning(arc[0], s[0][k] + len0 * double(j) / double(m), h0);
    for (std::size_t j = 0; j < m; ++j) out.at[0].push_back(s[0][k] + len0 * double(j) / double(m));

    for (std::size_t i = 1; i < N; ++i) {
      const double len = (k + 1 < L ? s[i][k + 1] : s[i][0] + perimeter[i]) - s[i][k];
      const double hi = len / double(m) * prm.bending_scale;
      std::vector<double> theta(m + 1);
      for (std::size_t q = 0; q <= m; ++q) theta[q] = Turning(arc[i], s[i][k] + len * double(q) / double(m), hi);
      std::vector<double> u = MatchSegment(theta0, theta, lambda);
      if (prm.smoothing > 0) SmoothCorrespondence(u, prm.smoothing);
      for (std::size_t j = 0; j < m; ++j) out.at[i].push_back(s[i][k] + len * u[j]);
    }
  }
  Densify(perimeter, spacing, out);
  for (std::size_t i = 0; i < N; ++i)
    for (double a : out.at[i]) out.points[i].push_back(arc[i].At(a));
  return out;
}

}  // namespace posemorph::bake::mapping
