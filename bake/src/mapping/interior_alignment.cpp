// SPDX-License-Identifier: MIT
// Interior alignment by the drawings (interior_alignment.h, docs/DESIGN.md section 7).
#include "posemorph/bake/mapping/interior_alignment.h"

#include "posemorph/bake/mapping/interior_regions.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

namespace posemorph::bake::mapping {
namespace {

using Vec2 = Eigen::Vector2d;

// One pyramid level of a drawing, blurred, with its central-difference
// gradients: what Gauss-Newton samples.
struct Level {
  int width = 0, height = 0;
  std::vector<float> c, gx, gy;  // 4 channels each

  // Bilinear at (x, y) in this level's pixels (centres at i + 0.5), zero
  // outside the image, into out[0..3] (and the gradients when asked).
  void Sample(double x, double y, double out[4], double dx[4] = nullptr, double dy[4] = nullptr) const {
    for (int ch = 0; ch < 4; ++ch) {
      out[ch] = 0;
      if (dx) dx[ch] = dy[ch] = 0;
    }
    const double fx = x - 0.5, fy = y - 0.5;
    if (!(fx > -1 && fy > -1 && fx < width && fy < height)) return;
    const double x0 = std::floor(fx), y0 = std::floor(fy), ax = fx - x0, ay = fy - y0;
    const long ix = long(x0), iy = long(y0);
    const double w[4] = {(1 - ax) * (1 - ay), ax * (1 - ay), (1 - ax) * ay, ax * ay};
    const long px[4] = {ix, ix + 1, ix, ix + 1}, py[4] = {iy, iy, iy + 1, iy + 1};
    for (int k = 0; k < 4; ++k) {
      if (px[k] < 0 || py[k] < 0 || px[k] >= width || py[k] >= height || w[k] == 0) continue;
      const std::size_t at = (std::size_t(py[k]) * std::size_t(width) + std::size_t(px[k])) * 4;
      for (int ch = 0; ch < 4; ++ch) {
        out[ch] += w[k] * c[at + std::size_t(ch)];
        if (dx) dx[ch] += w[k] * gx[at + std::size_t(ch)], dy[ch] += w[k] * gy[at + std::size_t(ch)];
      }
    }
  }
};

// Half the size: each pixel the mean of the 2 x 2 it covers (transparent
// beyond the edge), so a point's coordinates halve exactly.
std::vector<float> Halve(const std::vector<float>& c, int w, int h, int* hw, int* hh) {
  *hw = (w + 1) / 2, *hh = (h + 1) / 2;
  std::vector<float> out(std::size_t(*hw) * std::size_t(*hh) * 4, 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int ch = 0; ch < 4; ++ch)
        out[(std::size_t(y / 2) * std::size_t(*hw) + std::size_t(x / 2)) * 4 + std::size_t(ch)] +=
            0.25f * c[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 4 + std::size_t(ch)];
  return out;
}

// The binomial kernel (1 6 15 20 15 6 1) / 64, a Gaussian of about 1.2
// pixels, separable, transparent beyond the edge: exact weights, no libm,
// so every compiler bakes the same bits.
std::vector<float> Blur(const std::vector<float>& c, int w, int h) {
  constexpr int r = 3;
  constexpr float k[2 * r + 1] = {1 / 64.0f, 6 / 64.0f, 15 / 64.0f, 20 / 64.0f, 15 / 64.0f, 6 / 64.0f, 1 / 64.0f};
  std::vector<float> tmp(c.size(), 0.0f), out(c.size(), 0.0f);
  auto at = [w](int x, int y, int ch) {
    return (std::size_t(y) * std::size_t(w) + std::size_t(x)) * 4 + std::size_t(ch);
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int i = -r; i <= r; ++i) {
        if (x + i < 0 || x + i >= w) continue;
        for (int ch = 0; ch < 4; ++ch) tmp[at(x, y, ch)] += k[i + r] * c[at(x + i, y, ch)];
      }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int i = -r; i <= r; ++i) {
        if (y + i < 0 || y + i >= h) continue;
        for (int ch = 0; ch < 4; ++ch) out[at(x, y, ch)] += k[i + r] * tmp[at(x, y + i, ch)];
      }
  return out;
}

Level MakeLevel(std::vector<float> c, int w, int h, bool blur) {
  Level l;
  l.width = w, l.height = h;
  l.c = blur ? Blur(c, w, h) : std::move(c);
  l.gx.assign(l.c.size(), 0.0f);
  l.gy.assign(l.c.size(), 0.0f);
  auto value = [&](int x, int y, int ch) -> float {
    if (x < 0 || y < 0 || x >= w || y >= h) return 0.0f;
    return l.c[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 4 + std::size_t(ch)];
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int ch = 0; ch < 4; ++ch) {
        const std::size_t at = (std::size_t(y) * std::size_t(w) + std::size_t(x)) * 4 + std::size_t(ch);
        l.gx[at] = 0.5f * (value(x + 1, y, ch) - value(x - 1, y, ch));
        l.gy[at] = 0.5f * (value(x, y + 1, ch) - value(x, y - 1, ch));
      }
  return l;
}

// levels[0] full resolution ... levels[n - 1] the coarsest; blurred when asked.
std::vector<Level> Pyramid(const AlignmentImage& image, int n, bool blur) {
  std::vector<Level> out;
  std::vector<float> c = image.rgba;
  int w = image.width, h = image.height;
  for (int l = 0; l < n; ++l) {
    out.push_back(MakeLevel(c, w, h, blur));
    int hw = 0, hh = 0;
    c = Halve(c, w, h, &hw, &hh);
    w = hw, h = hh;
  }
  return out;
}

// A pixel of the reference inside pose 0's mesh: its triangle, its
// barycentric coordinates there, and the reference colour.
struct Sample {
  std::uint32_t triangle;
  double b[3];
  double colour[4];
};

// A matched region's centre: a point of pose 0's mesh (its triangle and
// barycentric coordinates) that should land on `target` in pose k
// (full-resolution pixels), with its weight.
struct Landmark {
  std::uint32_t triangle;
  double b[3];
  Vec2 target;
  double weight;
};

// p's barycentric coordinates in the triangle (a, b, c) of doubled signed
// area `area`: false when p lies outside it.
bool Barycentric(const Vec2& a, const Vec2& b, const Vec2& c, double area, const Vec2& p, double l[3]) {
  l[1] = ((p - a).x() * (c - a).y() - (p - a).y() * (c - a).x()) / area;
  l[2] = ((b - a).x() * (p - a).y() - (b - a).y() * (p - a).x()) / area;
  l[0] = 1 - l[1] - l[2];
  return !(l[0] < -1e-9 || l[1] < -1e-9 || l[2] < -1e-9);
}

// Where in pose 0's mesh a point lies: false when in no triangle.
bool Locate(const Triangles& triangles, const Points& mesh, const Vec2& p, std::uint32_t* triangle, double b[3]) {
  for (std::uint32_t t = 0; t < triangles.size(); ++t) {
    const Vec2 &a = mesh[triangles[t][0]], &u = mesh[triangles[t][1]], &v = mesh[triangles[t][2]];
    const double area = (u - a).x() * (v - a).y() - (u - a).y() * (v - a).x();
    if (!(std::abs(area) > 1e-12) || !Barycentric(a, u, v, area, p, b)) continue;
    *triangle = t;
    return true;
  }
  return false;
}

// Every pixel centre of `level` inside a triangle of `mesh` (scaled by
// `scale` into the level's pixels), each once.
std::vector<Sample> Samples(const Level& level, const Triangles& triangles, const Points& mesh, double scale) {
  std::vector<Sample> out;
  std::vector<unsigned char> taken(std::size_t(level.width) * std::size_t(level.height), 0);
  for (std::uint32_t t = 0; t < triangles.size(); ++t) {
    const Vec2 a = mesh[triangles[t][0]] * scale, b = mesh[triangles[t][1]] * scale, c = mesh[triangles[t][2]] * scale;
    const double area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    if (!(std::abs(area) > 1e-12)) continue;
    const int x0 = std::max(0, int(std::floor(std::min({a.x(), b.x(), c.x()}))));
    const int x1 = std::min(level.width - 1, int(std::ceil(std::max({a.x(), b.x(), c.x()}))));
    const int y0 = std::max(0, int(std::floor(std::min({a.y(), b.y(), c.y()}))));
    const int y1 = std::min(level.height - 1, int(std::ceil(std::max({a.y(), b.y(), c.y()}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const std::size_t at = std::size_t(y) * std::size_t(level.width) + std::size_t(x);
        if (taken[at]) continue;
        Sample s{t, {}, {}};
        if (!Barycentric(a, b, c, area, Vec2(x + 0.5, y + 0.5), s.b)) continue;
        taken[at] = 1;
        for (int ch = 0; ch < 4; ++ch) s.colour[ch] = level.c[at * 4 + std::size_t(ch)];
        out.push_back(s);
      }
  }
  return out;
}

// The cosine of a triangle's smallest angle (the largest of its corners'
// cosines): square roots only, the check every trial step makes.
double SmallestAngleCosine(const Vec2& a, const Vec2& b, const Vec2& c) {
  auto cosine = [](const Vec2& p, const Vec2& q, const Vec2& r) {
    const Vec2 u = q - p, v = r - p;
    const double n = std::sqrt(u.squaredNorm() * v.squaredNorm());
    return n > 0 ? u.dot(v) / n : 1.0;
  };
  return std::max({cosine(a, b, c), cosine(b, c, a), cosine(c, a, b)});
}

double SmallestAngle(const Vec2& a, const Vec2& b, const Vec2& c) {
  auto angle = [](const Vec2& p, const Vec2& q, const Vec2& r) {
    const Vec2 u = q - p, v = r - p;
    return std::atan2(std::abs(u.x() * v.y() - u.y() * v.x()), u.dot(v));
  };
  return std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)});
}

// Sample s's point in a pose's mesh x, in level pixels.
Vec2 Where(const Sample& s, const Triangles& triangles, const Points& x, double scale) {
  const auto& t = triangles[s.triangle];
  return (s.b[0] * x[t[0]] + s.b[1] * x[t[1]] + s.b[2] * x[t[2]]) * scale;
}

// The pose's drawing there less the reference colour, per channel.
void Residual(const Level& level, const Sample& s, const Triangles& triangles, const Points& x, double scale,
              double r[4]) {
  const Vec2 y = Where(s, triangles, x, scale);
  level.Sample(y.x(), y.y(), r);
  for (int ch = 0; ch < 4; ++ch) r[ch] -= s.colour[ch];
}

// Mean absolute difference over the samples and channels, pose k's drawing
// through `mesh` (level pixels = mesh * scale) against the reference.
double MeanDifference(const Level& level, const std::vector<Sample>& samples, const Triangles& triangles,
                      const Points& mesh, double scale) {
  if (samples.empty()) return 0;
  double sum = 0;
  for (const Sample& s : samples) {
    double r[4];
    Residual(level, s, triangles, mesh, scale, r);
    for (double c : r) sum += std::abs(c);
  }
  return sum / (4.0 * double(samples.size()));
}

using Solver = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>;

// Pose k's alignment at one level: Gauss-Newton steps on the free vertices.
struct LevelSolve {
  const Level& level;
  const std::vector<Sample>& samples;
  const Triangles& triangles;
  const std::vector<int>& index;           // free vertex -> unknown pair, or -1
  const Points& rest;                      // the mapping's mesh of pose k (full-resolution pixels)
  const std::vector<double>& max_cosine;   // per triangle, the cosine of the least smallest angle allowed
  const std::vector<double>& orientation;  // per triangle, the sign of its area in `rest`
  const std::vector<Landmark>& landmarks;  // matched regions
  double scale;                            // level pixels per full-resolution pixel
  double rigidity;
  // Per triangle, a factor on its ARAP weight: a triangle that stops a step
  // at its angle limit gets stiffer, so the next step bends the others.
  std::vector<double>& stiffness;
  Solver* solver;  // the level's sparse LDLT
  bool* analysed;  // whether its pattern is analysed

  std::vector<Eigen::Matrix2d> Rotations(const Points& x) const {
    std::vector<Eigen::Matrix2d> R(triangles.size());
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      Eigen::Matrix2d M = Eigen::Matrix2d::Zero();
      for (int e = 0; e < 3; ++e) {
        const std::uint32_t a = triangles[t][std::size_t(e)], b = triangles[t][std::size_t((e + 1) % 3)];
        M += (x[a] - x[b]) * (rest[a] - rest[b]).transpose();
      }
      // The rotation closest to M: its angle's cosine and sine, by a square root only.
      const double c = M(0, 0) + M(1, 1), s = M(1, 0) - M(0, 1), n = std::sqrt(c * c + s * s);
      if (n > 0)
        R[t] << c / n, -s / n, s / n, c / n;
      else
        R[t].setIdentity();
    }
    return R;
  }

  Vec2 LandmarkPoint(const Landmark& m, const Points& x) const {
    const auto& t = triangles[m.triangle];
    return m.b[0] * x[t[0]] + m.b[1] * x[t[1]] + m.b[2] * x[t[2]];
  }

  double Energy(const Points& x, const std::vector<Eigen::Matrix2d>& R) const {
    double e = 0;
    for (const Sample& s : samples) {
      double r[4];
      Residual(level, s, triangles, x, scale, r);
      for (double c : r) e += c * c;
    }
    for (std::size_t t = 0; t < triangles.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = triangles[t][std::size_t(k)], b = triangles[t][std::size_t((k + 1) % 3)];
        e += rigidity * stiffness[t] * (((x[a] - x[b]) - R[t] * (rest[a] - rest[b])) * scale).squaredNorm();
      }
    for (const Landmark& m : landmarks) e += m.weight * (LandmarkPoint(m, x) - m.target).squaredNorm() * scale * scale;
    return e;
  }

  bool Acceptable(const Points& x) const {
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      const Vec2 &a = x[triangles[t][0]], &b = x[triangles[t][1]], &c = x[triangles[t][2]];
      if (!(SignedArea(x, triangles[t]) * orientation[t] > 0)) return false;
      if (!(SmallestAngleCosine(a, b, c) <= max_cosine[t])) return false;
    }
    return true;
  }

  // One step; false when no step lowers the energy within the limits. A
  // step stopped by triangles at their angle limits (or turning over) is
  // tried again with those triangles ten times stiffer, a few times.
  bool Step(Points& x, double* moved) const {
    const std::size_t n = 2 * std::size_t(*std::max_element(index.begin(), index.end()) + 1);
    const std::vector<Eigen::Matrix2d> R = Rotations(x);
    const ColourTerm colour = Colour(x, n);
    for (int attempt = 0; attempt < 6; ++attempt) {
      std::vector<std::uint32_t> blocking;
      if (TryStep(x, R, colour, moved, &blocking)) return true;
      if (blocking.empty()) return false;
      for (std::uint32_t t : blocking) stiffness[t] = std::min(stiffness[t] * 10, 1e6);
    }
    return false;
  }

  // The colour term at x, gathered per triangle: JᵀJ blocks and Jᵀr.
  struct ColourTerm {
    Eigen::VectorXd g;
    std::vector<std::array<Eigen::Matrix2d, 6>> blocks;
  };
  ColourTerm Colour(const Points& x, std::size_t n) const {
    ColourTerm c;
    c.g = Eigen::VectorXd::Zero(Eigen::Index(n));
    c.blocks.resize(triangles.size());
    Eigen::VectorXd& g = c.g;
    auto& blocks = c.blocks;
    for (auto& b : blocks)
      for (auto& m : b) m.setZero();
    for (const Sample& s : samples) {
      const auto& t = triangles[s.triangle];
      const Vec2 y = Where(s, triangles, x, scale);
      double v[4], dx[4], dy[4];
      level.Sample(y.x(), y.y(), v, dx, dy);
      Eigen::Matrix2d G = Eigen::Matrix2d::Zero();
      Vec2 gr = Vec2::Zero();
      for (int ch = 0; ch < 4; ++ch) {
        const Vec2 d(dx[ch], dy[ch]);
        G += d * d.transpose();
        gr += (v[ch] - s.colour[ch]) * d;
      }
      // Unknowns are level pixels: d y / d u_i = b_i.
      int m = 0;
      for (int i = 0; i < 3; ++i)
        for (int j = i; j < 3; ++j) blocks[s.triangle][std::size_t(m++)] += s.b[i] * s.b[j] * G;
      for (int i = 0; i < 3; ++i) {
        const int u = index[t[std::size_t(i)]];
        if (u >= 0) g.segment<2>(2 * u) += s.b[i] * gr;
      }
    }
    return c;
  }

  bool TryStep(Points& x, const std::vector<Eigen::Matrix2d>& R, const ColourTerm& colour, double* moved,
               std::vector<std::uint32_t>* blocking) const {
    const std::size_t n = std::size_t(colour.g.size());
    Eigen::VectorXd g = colour.g;
    const auto& blocks = colour.blocks;
    std::vector<Eigen::Triplet<double>> h;
    auto add = [&](int u, int w, const Eigen::Matrix2d& m) {
      for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) h.emplace_back(2 * u + r, 2 * w + c, m(r, c));  // zeros too: one pattern every step
    };
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      int m = 0;
      for (int i = 0; i < 3; ++i)
        for (int j = i; j < 3; ++j, ++m) {
          const int u = index[triangles[t][std::size_t(i)]], w = index[triangles[t][std::size_t(j)]];
          if (u < 0 || w < 0) continue;
          add(u, w, blocks[t][std::size_t(m)]);
          if (i != j) add(w, u, blocks[t][std::size_t(m)].transpose());
        }
      // The ARAP term, rotations held.
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = triangles[t][std::size_t(k)], b = triangles[t][std::size_t((k + 1) % 3)];
        const Vec2 r = ((x[a] - x[b]) - R[t] * (rest[a] - rest[b])) * scale;
        const int ua = index[a], ub = index[b];
        const double w = rigidity * stiffness[t];
        const Eigen::Matrix2d I = w * Eigen::Matrix2d::Identity();
        if (ua >= 0) g.segment<2>(2 * ua) += w * r, add(ua, ua, I);
        if (ub >= 0) g.segment<2>(2 * ub) -= w * r, add(ub, ub, I);
        if (ua >= 0 && ub >= 0) add(ua, ub, -I), add(ub, ua, -I);
      }
    }
    // The matched regions: w |sum_i b_i x_i - target|^2 in level pixels.
    for (const Landmark& m : landmarks) {
      const auto& t = triangles[m.triangle];
      const Vec2 r = (LandmarkPoint(m, x) - m.target) * scale;
      for (int i = 0; i < 3; ++i) {
        const int u = index[t[std::size_t(i)]];
        if (u < 0) continue;
        g.segment<2>(2 * u) += m.weight * m.b[i] * r;
        for (int j = 0; j < 3; ++j) {
          const int w = index[t[std::size_t(j)]];
          if (w >= 0) add(u, w, m.weight * m.b[i] * m.b[j] * Eigen::Matrix2d::Identity());
        }
      }
    }
    Eigen::SparseMatrix<double> H(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
    H.setFromTriplets(h.begin(), h.end());
    // The matrix's pattern is the same every step of a level: its ordering
    // is found once.
    Solver& ldlt = *solver;
    if (!*analysed) ldlt.analyzePattern(H), *analysed = true;
    ldlt.factorize(H);
    if (ldlt.info() != Eigen::Success) return false;
    const Eigen::VectorXd delta = ldlt.solve(-g);
    if (ldlt.info() != Eigen::Success || !delta.allFinite()) return false;
    const double e0 = Energy(x, R);
    Points trial = x;
    for (double alpha = 1; alpha >= 1.0 / 64; alpha *= 0.5) {
      double longest = 0;
      for (std::size_t v = 0; v < x.size(); ++v) {
        if (index[v] < 0) continue;
        const Vec2 d = alpha * delta.segment<2>(2 * index[v]) / scale;
        trial[v] = x[v] + d;
        longest = std::max(longest, d.norm());
      }
      if (Acceptable(trial) && Energy(trial, R) < e0) {
        x = trial;
        *moved = longest;
        return true;
      }
    }
    // The shortest step tried: which triangles it would spoil.
    for (std::uint32_t t = 0; t < triangles.size(); ++t) {
      const Vec2 &a = trial[triangles[t][0]], &b = trial[triangles[t][1]], &c = trial[triangles[t][2]];
      if (!(SignedArea(trial, triangles[t]) * orientation[t] > 0) || !(SmallestAngleCosine(a, b, c) <= max_cosine[t]))
        blocking->push_back(t);
    }
    return false;
  }
};

}  // namespace

AlignmentImage AlignmentImageFromRgba(const unsigned char* rgba, int width, int height, int halvings) {
  const int f = 1 << std::max(0, halvings);
  AlignmentImage image;
  image.width = (width + f - 1) / f, image.height = (height + f - 1) / f;
  image.rgba.assign(std::size_t(image.width) * std::size_t(image.height) * 4, 0.0f);
  const float share = 1.0f / float(f * f);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const unsigned char* p = rgba + (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4;
      float* q = &image.rgba[(std::size_t(y / f) * std::size_t(image.width) + std::size_t(x / f)) * 4];
      const float a = float(p[3]) / 255.0f;
      for (int ch = 0; ch < 3; ++ch) q[ch] += share * a * float(p[ch]) / 255.0f;
      q[3] += share * a;
    }
  return image;
}

int AlignmentHalvings(int width, int height) {
  int h = 0;
  while ((std::max(width, height) >> h) > kAlignmentMaxSide) ++h;
  return h;
}

void AlignInteriors(const std::vector<AlignmentImage>& images, const Triangles& triangles,
                    const std::vector<bool>& fixed, std::vector<Points>& vertices,
                    const AlignmentParameters& parameters, AlignmentReport* report) {
  const auto start = std::chrono::steady_clock::now();
  const std::size_t N = vertices.size();
  AlignmentReport r;
  r.difference_before.assign(N, 0.0);
  r.difference_after.assign(N, 0.0);
  r.max_move.assign(N, 0.0);
  r.regions_found.assign(N, 0);
  r.regions_matched.assign(N, 0);
  std::vector<int> index(fixed.size(), -1);
  int free = 0;
  for (std::size_t v = 0; v < fixed.size(); ++v)
    if (!fixed[v]) index[v] = free++;
  const int levels = std::max(1, parameters.levels);
  if (N > 1 && free > 0) {
    const std::vector<Level> reference = Pyramid(images[0], levels, true);
    const Level raw_reference = MakeLevel(images[0].rgba, images[0].width, images[0].height, false);
    std::vector<std::vector<Sample>> samples;
    for (int l = 0; l < levels; ++l)
      samples.push_back(Samples(reference[std::size_t(l)], triangles, vertices[0], std::ldexp(1.0, -l)));
    const std::vector<Sample> raw_samples = Samples(raw_reference, triangles, vertices[0], 1.0);
    std::vector<InteriorRegion> reference_regions;
    double shape_area = 0;
    if (parameters.match_regions) {
      reference_regions = FindInteriorRegions(images[0]);
      shape_area = OpaqueArea(images[0]);
      r.regions_found[0] = int(reference_regions.size());
    }
    // The mesh's smallest angle before, over every pose, or the floor if that
    // is less: no triangle goes below it (unless it already was).
    double least = M_PI;
    for (const Points& mesh : vertices)
      for (const auto& t : triangles) least = std::min(least, SmallestAngle(mesh[t[0]], mesh[t[1]], mesh[t[2]]));
    for (std::size_t k = 1; k < N; ++k) {
      const std::vector<Level> pyramid = Pyramid(images[k], levels, true);
      const Level raw = MakeLevel(images[k].rgba, images[k].width, images[k].height, false);
      const Points rest = vertices[k];
      std::vector<double> max_cosine(triangles.size()), orientation(triangles.size());
      for (std::size_t t = 0; t < triangles.size(); ++t) {
        const Vec2 &a = rest[triangles[t][0]], &b = rest[triangles[t][1]], &c = rest[triangles[t][2]];
        orientation[t] = SignedArea(rest, triangles[t]) > 0 ? 1.0 : -1.0;
        const double own = SmallestAngle(a, b, c);
        const double floor = std::min(least, parameters.min_angle_floor_degrees * M_PI / 180);
        // Its own cosine when that is the limit: a triangle at it may stay.
        const double limit = std::max(parameters.angle_keep * own, floor);
        max_cosine[t] = limit >= own ? SmallestAngleCosine(a, b, c) : std::cos(limit);
      }
      r.difference_before[k] = MeanDifference(raw, raw_samples, triangles, rest, 1.0);
      // The regions: pose 0's mapped through the meshes as the outlines left
      // them, paired with pose k's.
      std::vector<Landmark> landmarks;
      if (parameters.match_regions && !reference_regions.empty()) {
        const std::vector<InteriorRegion> regions = FindInteriorRegions(images[k]);
        r.regions_found[k] = int(regions.size());
        std::vector<Vec2> predicted;
        std::vector<Landmark> located;
        for (const InteriorRegion& region : reference_regions) {
          Landmark m{0, {0, 0, 0}, Vec2::Zero(), 0};
          if (Locate(triangles, vertices[0], region.centre, &m.triangle, m.b)) {
            const auto& t = triangles[m.triangle];
            predicted.push_back(m.b[0] * rest[t[0]] + m.b[1] * rest[t[1]] + m.b[2] * rest[t[2]]);
          } else {
            predicted.push_back(Vec2::Constant(std::numeric_limits<double>::quiet_NaN()));
          }
          located.push_back(m);
        }
        for (const RegionMatch& match : MatchInteriorRegions(reference_regions, predicted, regions, shape_area)) {
          Landmark m = located[match.reference];
          m.target = match.to;
          m.weight = parameters.region_weight * match.area;
          landmarks.push_back(m);
        }
        r.regions_matched[k] = int(landmarks.size());
      }
      Points x = rest;
      std::vector<double> stiffness(triangles.size(), 1.0);
      for (int l = levels - 1; l >= 0; --l) {
        Solver solver;
        bool analysed = false;
        const LevelSolve solve{pyramid[std::size_t(l)],
                               samples[std::size_t(l)],
                               triangles,
                               index,
                               rest,
                               max_cosine,
                               orientation,
                               landmarks,
                               std::ldexp(1.0, -l),
                               parameters.rigidity,
                               stiffness,
                               &solver,
                               &analysed};
        for (int it = 0; it < parameters.iterations; ++it) {
          double moved = 0;
          if (!solve.Step(x, &moved)) break;
          ++r.steps;
          if (moved < 0.01) break;
        }
      }
      r.difference_after[k] = MeanDifference(raw, raw_samples, triangles, x, 1.0);
      for (std::size_t v = 0; v < x.size(); ++v) r.max_move[k] = std::max(r.max_move[k], (x[v] - rest[v]).norm());
      vertices[k] = std::move(x);
    }
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (report) *report = std::move(r);
}

}  // namespace posemorph::bake::mapping
