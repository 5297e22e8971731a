// SPDX-License-Identifier: MIT
// Interior alignment by the drawings (interior_alignment.h, docs/DESIGN.md section 7).
#include "posemorph/bake/mapping/interior_alignment.h"

#include "alignment_image.h"
#include "posemorph/bake/mapping/interior_regions.h"
#include "posemorph/bake/run_each.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

namespace posemorph::bake::mapping {
namespace {

using namespace alignment;  // NOLINT(google-build-using-namespace): the alignment's own sampling

// A matched region's centre: a point of pose 0's mesh (its triangle and
// barycentric coordinates) that should land on `target` in pose k
// (full-resolution pixels), with its weight.
struct Landmark {
  std::uint32_t triangle;
  double b[3];
  Vec2 target;
  double weight;
};

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
      if (!(bake::SignedArea(x, triangles[t]) * orientation[t] > 0)) return false;
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
      if (!(bake::SignedArea(trial, triangles[t]) * orientation[t] > 0) ||
          !(SmallestAngleCosine(a, b, c) <= max_cosine[t]))
        blocking->push_back(t);
    }
    return false;
  }
};

}  // namespace

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
    // Each pose aligns to pose 0 alone: the poses are shared out over the
    // cores (each writes only its own mesh and report entries, so the
    // outcome is the same bits on any number of threads).
    std::vector<int> steps(N, 0);
    RunEach(N - 1, 0, [&](std::size_t j) {
      const std::size_t k = j + 1;
      const std::vector<Level> pyramid = Pyramid(images[k], levels, true);
      const Level raw = MakeLevel(images[k].rgba, images[k].width, images[k].height, false);
      const Points rest = vertices[k];
      std::vector<double> max_cosine(triangles.size()), orientation(triangles.size());
      for (std::size_t t = 0; t < triangles.size(); ++t) {
        const Vec2 &a = rest[triangles[t][0]], &b = rest[triangles[t][1]], &c = rest[triangles[t][2]];
        orientation[t] = bake::SignedArea(rest, triangles[t]) > 0 ? 1.0 : -1.0;
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
          ++steps[k];
          if (moved < 0.01) break;
        }
      }
      r.difference_after[k] = MeanDifference(raw, raw_samples, triangles, x, 1.0);
      for (std::size_t v = 0; v < x.size(); ++v) r.max_move[k] = std::max(r.max_move[k], (x[v] - rest[v]).norm());
      vertices[k] = std::move(x);
    });
    for (int s : steps) r.steps += s;
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (report) *report = std::move(r);
}

}  // namespace posemorph::bake::mapping
