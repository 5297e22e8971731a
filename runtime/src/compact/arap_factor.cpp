// SPDX-License-Identifier: MIT
#include "arap_factor.h"

#include <cmath>
#include <cstdio>
#include <cstring>

#include "posemorph/rig_format.h"

namespace posemorph::detail {
namespace {

constexpr std::uint32_t kNone = 0xFFFFFFFFu;

bool Fail(Error* err, ErrorCode code, const char* message, unsigned long long a, unsigned long long b = 0) {
  if (err) {
    err->code = code;
    std::snprintf(err->message, sizeof(err->message), message, a, b);
  }
  return false;
}

// The triangle's rest geometry: M = area * G^T (3x2, row k pulls vertex k)
// and G = E^-T D (2x3), E = [p_a - p_c, p_b - p_c].
struct RestTriangle {
  double area;
  double G[2][3];
};

bool Rest(const double* p, const std::uint32_t* tri, std::uint64_t t, RestTriangle* out, Error* err) {
  const double* a = p + 2 * std::size_t(tri[0]);
  const double* b = p + 2 * std::size_t(tri[1]);
  const double* c = p + 2 * std::size_t(tri[2]);
  const double e00 = a[0] - c[0], e10 = a[1] - c[1], e01 = b[0] - c[0], e11 = b[1] - c[1];
  const double det = e00 * e11 - e01 * e10;
  if (!(det > 0) || !std::isfinite(det))
    return Fail(err, ErrorCode::kBadValue,
                "section QPOS: triangle %llu is not counter-clockwise with positive area in pose 0",
                (unsigned long long)t);
  // E^-T = [[e11, -e10], [-e01, e00]] / det; D = [[1, 0, -1], [0, 1, -1]].
  const double i00 = e11 / det, i01 = -e10 / det, i10 = -e01 / det, i11 = e00 / det;
  out->area = 0.5 * det;
  out->G[0][0] = i00;
  out->G[1][0] = i10;
  out->G[0][1] = i01;
  out->G[1][1] = i11;
  out->G[0][2] = -(i00 + i01);
  out->G[1][2] = -(i10 + i11);
  return true;
}

// K's upper part (column by column, rows in the fill-reducing order), the
// gradients and the vertex masses.
bool AssembleStiffness(const double* positions, std::uint64_t V, const std::uint32_t* triangles, std::uint64_t T,
                       std::uint64_t n, const ArapFactorBuffers& b, Error* err) {
  std::memset(b.vertex_masses, 0, V * sizeof(double));
  std::memset(b.entry_start, 0, (n + 1) * sizeof(std::uint32_t));
  double total_area = 0;
  for (std::uint64_t t = 0; t < T; ++t) {
    const std::uint32_t* tri = triangles + 3 * t;
    RestTriangle r;
    if (!Rest(positions, tri, t, &r, err)) return false;
    for (int k = 0; k < 3; ++k) {
      b.gradients[6 * t + 2 * k] = r.area * r.G[0][k];
      b.gradients[6 * t + 2 * k + 1] = r.area * r.G[1][k];
      b.vertex_masses[tri[k]] += r.area / 3;
    }
    total_area += r.area;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        if (tri[i] == 0 || tri[j] == 0) continue;
        const std::uint32_t p = b.position[tri[i] - 1], q = b.position[tri[j] - 1];
        if (p <= q) ++b.entry_start[q + 1];
      }
  }
  if (!(total_area > 0) || !std::isfinite(total_area))
    return Fail(err, ErrorCode::kBadValue, "section QPOS: the rest pose has no finite area", 0);
  for (std::uint64_t v = 0; v < V; ++v) b.vertex_masses[v] /= total_area;
  for (std::uint64_t k = 0; k < n; ++k) b.entry_start[k + 1] += b.entry_start[k];
  std::memcpy(b.fill, b.entry_start, n * sizeof(std::uint32_t));
  for (std::uint64_t t = 0; t < T; ++t) {
    const std::uint32_t* tri = triangles + 3 * t;
    const double* M = b.gradients + 6 * t;
    RestTriangle r;
    Rest(positions, tri, t, &r, nullptr);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        if (tri[i] == 0 || tri[j] == 0) continue;
        const std::uint32_t p = b.position[tri[i] - 1], q = b.position[tri[j] - 1];
        if (p > q) continue;
        const std::uint32_t slot = b.fill[q]++;
        b.entry_row[slot] = p;
        b.entry_value[slot] = M[2 * i] * r.G[0][j] + M[2 * i + 1] * r.G[1][j];  // (M G)(i, j)
      }
  }
  return true;
}

// Elimination tree and column counts of L: row k of L is the set of nodes
// met walking up the tree from each row index of K's column k, up to k.
bool FactorPattern(std::uint64_t n, std::uint64_t nnz, const ArapFactorBuffers& b, Error* err) {
  std::uint64_t found = 0;
  std::memset(b.col_start, 0, (n + 1) * sizeof(std::uint32_t));
  for (std::uint64_t k = 0; k < n; ++k) {
    b.parent[k] = kNone;
    b.flag[k] = std::uint32_t(k);
    for (std::uint32_t e = b.entry_start[k]; e < b.entry_start[k + 1]; ++e) {
      for (std::uint32_t i = b.entry_row[e]; b.flag[i] != k; i = b.parent[i]) {
        if (b.parent[i] == kNone) b.parent[i] = std::uint32_t(k);
        ++b.col_start[i + 1];
        b.flag[i] = std::uint32_t(k);
        if (++found > nnz)
          return Fail(err, ErrorCode::kBadValue,
                      "section QPRM: the factor has more nonzeros than the %llu META declares",
                      (unsigned long long)nnz);
      }
    }
  }
  if (found != nnz)
    return Fail(err, ErrorCode::kBadValue, "section QPRM: the factor has %llu nonzeros, META declares %llu",
                (unsigned long long)found, (unsigned long long)nnz);
  std::uint64_t work = 0;
  for (std::uint64_t k = 0; k < n; ++k) {
    const std::uint64_t c = b.col_start[k + 1];
    work += c * c;
    b.col_start[k + 1] += b.col_start[k];
  }
  if (work > format::kMaxCompactFactorWork)
    return Fail(err, ErrorCode::kTooLarge,
                "section QPRM: factoring this rig takes %llu operations, above the limit of %llu",
                (unsigned long long)work, (unsigned long long)format::kMaxCompactFactorWork);
  return true;
}

// Up-looking LDL^T: row k of L solves L(0:k, 0:k) D l = K(0:k, k) over the
// row's pattern, visited in the tree's topological order.
bool FactorValues(std::uint64_t n, const ArapFactorBuffers& b, Error* err) {
  std::memcpy(b.fill, b.col_start, n * sizeof(std::uint32_t));
  std::memset(b.work, 0, n * sizeof(double));
  for (std::uint64_t k = 0; k < n; ++k) b.flag[k] = kNone;
  for (std::uint64_t k = 0; k < n; ++k) {
    std::uint64_t top = n;
    b.flag[k] = std::uint32_t(k);
    for (std::uint32_t e = b.entry_start[k]; e < b.entry_start[k + 1]; ++e) {
      std::uint32_t i = b.entry_row[e];
      b.work[i] += b.entry_value[e];
      std::uint64_t len = 0;
      for (; b.flag[i] != k; i = b.parent[i]) {
        b.path[len++] = i;
        b.flag[i] = std::uint32_t(k);
      }
      while (len > 0) b.stack[--top] = b.path[--len];
    }
    double d = b.work[k];
    b.work[k] = 0;
    for (std::uint64_t s = top; s < n; ++s) {
      const std::uint32_t j = b.stack[s];
      const double yj = b.work[j];
      b.work[j] = 0;
      for (std::uint32_t q = b.col_start[j]; q < b.fill[j]; ++q) b.work[b.row[q]] -= b.value[q] * yj;
      const double l = yj / b.pivot[j];
      d -= l * yj;
      const std::uint32_t slot = b.fill[j]++;
      b.row[slot] = std::uint32_t(k);
      b.value[slot] = l;
    }
    if (!(d > 0) || !std::isfinite(d))
      return Fail(err, ErrorCode::kBadValue,
                  "section QPOS: the ARAP system is not positive definite at pivot %llu (a mesh in separate pieces?)",
                  (unsigned long long)k);
    b.pivot[k] = d;
    b.inv_diagonal[k] = 1 / d;
  }
  return true;
}

}  // namespace

bool BuildArapFactor(const double* positions, std::uint64_t V, const std::uint32_t* triangles, std::uint64_t T,
                     const std::uint32_t* order, std::uint64_t nnz, const ArapFactorBuffers& b, Error* err) {
  const std::uint64_t n = V - 1;
  for (std::uint64_t k = 0; k < n; ++k) b.position[order[k]] = std::uint32_t(k);
  return AssembleStiffness(positions, V, triangles, T, n, b, err) && FactorPattern(n, nnz, b, err) &&
         FactorValues(n, b, err);
}

}  // namespace posemorph::detail
