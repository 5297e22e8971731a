// SPDX-License-Identifier: MIT
#include "compact_rig.h"

#include <cmath>
#include <cstdio>
#include <cstring>

#include "bit_reader.h"
#include "../load_error.h"
#include "polar_angle.h"
#include "posemorph/compact_codec.h"
#include "posemorph/rig_format.h"

namespace posemorph::detail {
namespace {

namespace fmt = format;

constexpr auto Fail = LoadFail;

// A packed array's header (QPRM: PackedArrayHeader).
bool PackedHeader(const char* tag, const SectionBytes& s, std::uint64_t count, unsigned* width, Error* err) {
  if (!s.data) return Fail(err, ErrorCode::kBadLayout, "missing section %s", tag);
  fmt::PackedArrayHeader header{};
  if (!fmt::ReadRecord(s.data, s.size, 0, &header))
    return Fail(err, ErrorCode::kBadLayout, "section %s is %llu bytes, shorter than its header", tag,
                (unsigned long long)s.size);
  *width = header.width;
  if (*width < 1 || *width > 32 || header.reserved != 0)
    return Fail(err, ErrorCode::kBadValue, "section %s: bit width %u outside 1..32 or reserved field set", tag, *width);
  const std::uint64_t expected = fmt::PackedArrayHeader::kSize + PackedBytes(count, *width);
  if (s.size != expected)
    return Fail(err, ErrorCode::kBadLayout, "section %s is %llu bytes, the counts imply %llu", tag,
                (unsigned long long)s.size, (unsigned long long)expected);
  return true;
}

bool FiniteWithin(double v, double limit) { return std::isfinite(v) && std::fabs(v) <= limit; }

constexpr std::int64_t kMaxPositionCode = std::int64_t(1) << 40;

// The bytes of QPOS before its stream: the header and the N pose origins.
std::uint64_t PositionsPreamble(std::uint64_t N) { return fmt::QuantPositionsHeader::kSize + fmt::Point::kSize * N; }

// QPOS: a QuantPositionsHeader, N Points (each pose's origin), then per pose
// and vertex the x and y integers as codes of their residuals (zigzag, order
// k) against the previous vertex's integers or, from 1.14 where the
// header's prediction has kPositionsFromNeighbours, against the mean of the
// vertex's earlier neighbours (compact_codec.h); from 1.13, where it has
// kPositionsAgainstPose0, the poses after the first code those residuals
// less pose 0's, each pose after its own order (5 bits).
bool ReadPositionsHeader(const SectionBytes& qpos, const CompactCounts& c, CompactLayout& L, Error* err) {
  if (!qpos.data) return Fail(err, ErrorCode::kBadLayout, "missing section QPOS");
  if (qpos.size < PositionsPreamble(c.N))
    return Fail(err, ErrorCode::kBadLayout, "section QPOS is shorter than its header");
  const auto header = fmt::DecodeRecord<fmt::QuantPositionsHeader>(qpos.data);
  L.position_step = header.step;
  L.position_k = header.code_order;
  L.position_prediction = header.prediction;
  if (!(L.position_step > 0) || !FiniteWithin(L.position_step, fmt::kMaxMagnitude))
    return Fail(err, ErrorCode::kBadValue, "section QPOS: step %g is not finite and positive", L.position_step);
  if (L.position_k > 20) return Fail(err, ErrorCode::kBadValue, "section QPOS: code order %u above 20", L.position_k);
  const std::uint32_t known = c.minor >= 14   ? fmt::kPositionsAgainstPose0 | fmt::kPositionsFromNeighbours
                              : c.minor >= 13 ? fmt::kPositionsAgainstPose0
                                              : 0;
  if ((header.prediction & ~known) != 0)
    return Fail(err, ErrorCode::kBadValue,
                "section QPOS: prediction field %u has a bit outside %u (format 1.%u: 1 from 1.13, 2 from 1.14)",
                header.prediction, known, unsigned(c.minor));
  for (std::uint64_t i = 0; i < c.N; ++i) {
    const auto origin = fmt::DecodeEntry<fmt::Point>(qpos.data + fmt::QuantPositionsHeader::kSize, i);
    if (!FiniteWithin(origin.x, fmt::kMaxMagnitude) || !FiniteWithin(origin.y, fmt::kMaxMagnitude))
      return Fail(err, ErrorCode::kBadValue, "section QPOS: origin of pose %llu is not finite or beyond %g",
                  (unsigned long long)i, fmt::kMaxMagnitude);
  }
  if ((qpos.size - PositionsPreamble(c.N)) * 8 < 2 * c.N * c.V)
    return Fail(err, ErrorCode::kBadLayout, "section QPOS is too short for %llu vertices in %llu poses",
                (unsigned long long)c.V, (unsigned long long)c.N);
  L.positions = qpos;
  return true;
}

// QTRI: a CodedTrianglesHeader, then each vertex index as the code of its
// difference from the same corner of the previous triangle (zigzag, order k).
bool ReadTrianglesHeader(const SectionBytes& qtri, const SectionBytes& qprm, const CompactCounts& c, CompactLayout& L,
                         Error* err) {
  if (!qtri.data) return Fail(err, ErrorCode::kBadLayout, "missing section QTRI");
  fmt::CodedTrianglesHeader header{};
  if (!fmt::ReadRecord(qtri.data, qtri.size, 0, &header))
    return Fail(err, ErrorCode::kBadLayout, "section QTRI is shorter than its header");
  L.triangle_k = header.code_order;
  if (L.triangle_k > 20 || header.reserved != 0)
    return Fail(err, ErrorCode::kBadValue, "section QTRI: code order %u above 20 or reserved field set", L.triangle_k);
  if ((qtri.size - fmt::CodedTrianglesHeader::kSize) * 8 < 3 * c.T)
    return Fail(err, ErrorCode::kBadLayout, "section QTRI is too short for %llu triangles", (unsigned long long)c.T);
  if (!PackedHeader("QPRM", qprm, c.n, &L.permutation_bits, err)) return false;
  L.triangles = qtri;
  L.permutation = qprm;
  return true;
}

// QTRN: a TurnsHeader, then TN packed values: turn = base + value.
bool ReadTurnsHeader(const SectionBytes& qtrn, const CompactCounts& c, CompactLayout& L, Error* err) {
  if (!qtrn.data) return Fail(err, ErrorCode::kBadLayout, "missing section QTRN");
  fmt::TurnsHeader header{};
  if (!fmt::ReadRecord(qtrn.data, qtrn.size, 0, &header))
    return Fail(err, ErrorCode::kBadLayout, "section QTRN is shorter than its header");
  L.turn_base = header.base;
  L.turn_bits = header.width;
  if (L.turn_bits > 32) return Fail(err, ErrorCode::kBadValue, "section QTRN: bit width %u above 32", L.turn_bits);
  const std::uint64_t turn_expected = fmt::TurnsHeader::kSize + PackedBytes(c.T * c.N, L.turn_bits);
  if (qtrn.size != turn_expected)
    return Fail(err, ErrorCode::kBadLayout, "section QTRN is %llu bytes, the counts imply %llu",
                (unsigned long long)qtrn.size, (unsigned long long)turn_expected);
  L.turns = qtrn;
  return true;
}

// The bytes of QGRD before its stream: the header and a GridPoseCode per coded pose.
std::uint64_t GridPreamble(std::uint32_t coded) {
  return fmt::GridHeader::kSize + fmt::GridPoseCode::kSize * std::uint64_t(coded);
}

// QGRD: a GridHeader (coded poses: N, or N - 1 with the last pose 1 minus
// the others), a GridPoseCode per coded pose, then the Exp-Golomb stream.
bool ReadGridHeader(const SectionBytes& qgrd, const CompactCounts& c, CompactLayout& L, Error* err) {
  if (!qgrd.data) return Fail(err, ErrorCode::kBadLayout, "missing section QGRD");
  fmt::GridHeader grid{};
  if (!fmt::ReadRecord(qgrd.data, qgrd.size, 0, &grid))
    return Fail(err, ErrorCode::kBadLayout, "section QGRD is shorter than its header");
  L.grid_step = grid.step;
  L.grid_coded_poses = grid.coded_poses;
  if (!(L.grid_step > 0) || !FiniteWithin(L.grid_step, fmt::kMaxGridWeight))
    return Fail(err, ErrorCode::kBadValue, "section QGRD: step %g is not finite and positive", L.grid_step);
  if ((L.grid_coded_poses != c.N && L.grid_coded_poses + 1 != c.N) || grid.reserved != 0)
    return Fail(err, ErrorCode::kBadValue, "section QGRD: %u coded poses for %llu poses, or reserved field set",
                L.grid_coded_poses, (unsigned long long)c.N);
  const std::uint64_t header = GridPreamble(L.grid_coded_poses);
  if (qgrd.size < header) return Fail(err, ErrorCode::kBadLayout, "section QGRD is shorter than its header");
  for (std::uint32_t i = 0; i < L.grid_coded_poses; ++i) {
    const auto k = fmt::DecodeEntry<fmt::GridPoseCode>(qgrd.data + fmt::GridHeader::kSize, i);
    if (k.corner_order > 20 || k.centre_order > 20 || (k.prediction_order != 1 && k.prediction_order != 2))
      return Fail(err, ErrorCode::kBadValue, "section QGRD: code parameters of pose %u out of range", i);
  }
  const std::uint64_t nodes = (c.cells_x + 1) * (c.cells_y + 1) + (c.grid_centres ? c.cells_x * c.cells_y : 0);
  // Every code is at least one bit: a stream shorter than that cannot hold the grid.
  if ((qgrd.size - header) * 8 < nodes * L.grid_coded_poses)
    return Fail(err, ErrorCode::kBadLayout, "section QGRD is too short for a %llux%llu grid",
                (unsigned long long)c.cells_x, (unsigned long long)c.cells_y);
  L.grid = qgrd;
  return true;
}

// QUVA (optional): per pose an AffineUvEntry: uv = M (x, y, 1).
bool ReadAffineUvs(const SectionBytes& quva, const CompactCounts& c, CompactLayout& L, Error* err) {
  const unsigned long long expected = fmt::AffineUvEntry::kSize * static_cast<unsigned long long>(c.N);
  if (quva.size != expected)
    return Fail(err, ErrorCode::kBadLayout, "section QUVA is %llu bytes, the counts imply %llu",
                (unsigned long long)quva.size, expected);
  for (std::uint64_t i = 0; i < c.N; ++i) {
    const auto e = fmt::DecodeEntry<fmt::AffineUvEntry>(quva.data, i);
    if (e.source_pose >= c.N || e.reserved != 0)
      return Fail(err, ErrorCode::kBadValue, "section QUVA: pose %llu names source pose %u of %llu",
                  (unsigned long long)i, e.source_pose, (unsigned long long)c.N);
    for (int k = 0; k < 6; ++k)
      if (!FiniteWithin(e.map[k], fmt::kMaxMagnitude))
        return Fail(err, ErrorCode::kBadValue, "section QUVA: coefficient %d of pose %llu is not finite", k,
                    (unsigned long long)i);
  }
  L.affine_uvs = quva;
  L.has_affine_uvs = true;
  return true;
}

}  // namespace

bool ReadCompactLayout(const SectionBytes& qpos, const SectionBytes& qtri, const SectionBytes& qprm,
                       const SectionBytes& qtrn, const SectionBytes& qgrd, const SectionBytes& quva,
                       const CompactCounts& c, CompactLayout* out, Error* err) {
  CompactLayout L;
  if (!ReadPositionsHeader(qpos, c, L, err) || !ReadTrianglesHeader(qtri, qprm, c, L, err) ||
      !ReadTurnsHeader(qtrn, c, L, err) || !ReadGridHeader(qgrd, c, L, err))
    return false;
  if (quva.data && !ReadAffineUvs(quva, c, L, err)) return false;
  if (c.nnz > std::uint64_t(fmt::kMaxCompactNonzerosPerByte) * c.file_size)
    return Fail(err, ErrorCode::kTooLarge,
                "META: %llu factor nonzeros for a compact file of %llu bytes (at most %u per byte)",
                (unsigned long long)c.nnz, (unsigned long long)c.file_size, fmt::kMaxCompactNonzerosPerByte);
  *out = L;
  return true;
}

namespace {

// Triangles: differences from the previous triangle, each index checked.
bool DecodeTriangles(const CompactLayout& L, const CompactCounts& c, const CompactOutputs& o, Error* err) {
  const std::uint64_t V = c.V, T = c.T;
  BitReader r(L.triangles.data + fmt::CodedTrianglesHeader::kSize, L.triangles.size - fmt::CodedTrianglesHeader::kSize);
  for (std::uint64_t k = 0; k < 3 * T; ++k) {
    const std::int64_t previous = k >= 3 ? std::int64_t(o.triangles[k - 3]) : 0;
    const std::int64_t value = previous + fmt::UnZigZag(r.ReadGolomb(L.triangle_k, fmt::kMaxGolombZeros));
    if (r.overrun || value < 0 || value >= std::int64_t(V))
      return Fail(err, ErrorCode::kBadValue,
                  "section QTRI: triangle %llu has a vertex index outside 0..%llu or runs past the section",
                  (unsigned long long)(k / 3), (unsigned long long)(V - 1));
    o.triangles[k] = std::uint32_t(value);
  }
  if ((r.position() + 7) / 8 != r.size_bits() / 8)
    return Fail(err, ErrorCode::kBadLayout, "section QTRI has bytes after its codes");
  for (std::uint64_t t = 0; t < T; ++t) {
    const std::uint32_t a = o.triangles[3 * t], b = o.triangles[3 * t + 1], d = o.triangles[3 * t + 2];
    if (a >= V || b >= V || d >= V)
      return Fail(err, ErrorCode::kBadValue, "section QTRI: triangle %llu has a vertex index >= %llu",
                  (unsigned long long)t, (unsigned long long)V);
    if (a == b || b == d || a == d)
      return Fail(err, ErrorCode::kBadValue, "section QTRI: triangle %llu repeats a vertex", (unsigned long long)t);
  }
  return true;
}

// The fill-reducing order: bit-packed, checked to be a permutation.
bool DecodePermutation(const CompactLayout& L, const CompactCounts& c, const CompactOutputs& o, Error* err) {
  const std::uint64_t n = c.n;
  const BitReader r(L.permutation.data + fmt::PackedArrayHeader::kSize,
                    L.permutation.size - fmt::PackedArrayHeader::kSize);
  std::memset(o.seen, 0, n);
  for (std::uint64_t k = 0; k < n; ++k) {
    const std::uint32_t v = r.At(k * L.permutation_bits, L.permutation_bits);
    if (v >= n || o.seen[v])
      return Fail(err, ErrorCode::kBadValue, "section QPRM: not a permutation (entry %llu)", (unsigned long long)k);
    o.seen[v] = 1;
    o.order[k] = v;
  }
  return true;
}

// Positions: origin + step * q, pose by pose. Where the poses after the
// first are coded against pose 0, a second reader goes over pose 0's codes
// again beside each of them (pose 0's residuals, exactly as coded; nothing
// stored). The integers of the pose at hand are kept in o.position_codes for
// the predictions; the earlier neighbours' lists are built from the
// triangles, decoded before.
bool DecodePositions(const CompactLayout& L, const CompactCounts& c, const CompactOutputs& o, Error* err) {
  const std::uint64_t V = c.V, N = c.N;
  const unsigned char* origins = L.positions.data + fmt::QuantPositionsHeader::kSize;
  const unsigned char* stream = L.positions.data + PositionsPreamble(N);
  const std::uint64_t stream_bytes = L.positions.size - PositionsPreamble(N);
  const bool against = (L.position_prediction & fmt::kPositionsAgainstPose0) != 0;
  const bool neighbours = (L.position_prediction & fmt::kPositionsFromNeighbours) != 0;
  if (neighbours) fmt::EarlierNeighbours(o.triangles, c.T, V, o.neighbour_start, o.neighbour_fill, o.neighbour_list);
  std::int64_t* q = o.position_codes;
  BitReader r(stream, stream_bytes);
  for (std::uint64_t i = 0; i < N; ++i) {
    const auto origin = fmt::DecodeEntry<fmt::Point>(origins, i);
    const double ox = origin.x, oy = origin.y;
    const bool predicted = i > 0 && against;
    const unsigned order = predicted ? r.Read(5) : L.position_k;
    if (order > 20)
      return Fail(err, ErrorCode::kBadValue, "section QPOS: code order %u of pose %llu above 20", order,
                  (unsigned long long)i);
    BitReader pose0(stream, stream_bytes);
    for (std::uint64_t v = 0; v < V; ++v) {
      const std::uint64_t k = 2 * (i * V + v);
      std::int64_t qx = fmt::UnZigZag(r.ReadGolomb(order, fmt::kMaxGolombZeros));
      std::int64_t qy = fmt::UnZigZag(r.ReadGolomb(order, fmt::kMaxGolombZeros));
      if (predicted) {
        qx += fmt::UnZigZag(pose0.ReadGolomb(L.position_k, fmt::kMaxGolombZeros));
        qy += fmt::UnZigZag(pose0.ReadGolomb(L.position_k, fmt::kMaxGolombZeros));
      }
      if (neighbours) {
        qx += fmt::NeighbourPrediction(q, 2, v, o.neighbour_start, o.neighbour_list);
        qy += fmt::NeighbourPrediction(q + 1, 2, v, o.neighbour_start, o.neighbour_list);
      } else if (v > 0) {
        qx += q[2 * (v - 1)];
        qy += q[2 * (v - 1) + 1];
      }
      if (r.overrun || pose0.overrun || qx < 0 || qy < 0 || qx > kMaxPositionCode || qy > kMaxPositionCode)
        return Fail(err, ErrorCode::kBadValue,
                    "section QPOS: vertex %llu of pose %llu: code runs past the section or out of range",
                    (unsigned long long)v, (unsigned long long)i);
      q[2 * v] = qx;
      q[2 * v + 1] = qy;
      o.positions[k] = ox + L.position_step * double(qx);
      o.positions[k + 1] = oy + L.position_step * double(qy);
      if (!FiniteWithin(o.positions[k], fmt::kMaxMagnitude) || !FiniteWithin(o.positions[k + 1], fmt::kMaxMagnitude))
        return Fail(err, ErrorCode::kBadValue, "section QPOS: vertex %llu of pose %llu is beyond %g",
                    (unsigned long long)v, (unsigned long long)i, fmt::kMaxMagnitude);
    }
  }
  if ((r.position() + 7) / 8 != r.size_bits() / 8)
    return Fail(err, ErrorCode::kBadLayout, "section QPOS has bytes after its codes");
  return true;
}

// Centroids: the mass-weighted mean of each pose.
void ComputeCentroids(const CompactCounts& c, const CompactOutputs& o) {
  const std::uint64_t V = c.V, N = c.N;
  for (std::uint64_t i = 0; i < N; ++i) {
    double cx = 0, cy = 0;
    for (std::uint64_t v = 0; v < V; ++v) {
      cx += o.factor.vertex_masses[v] * o.positions[2 * (i * V + v)];
      cy += o.factor.vertex_masses[v] * o.positions[2 * (i * V + v) + 1];
    }
    o.centroids[2 * i] = cx;
    o.centroids[2 * i + 1] = cy;
  }
}

// Angles and stretches: the polar split of A = E_i E_0^-1, plus whole turns.
bool ComputeAnglesAndStretches(const CompactLayout& L, const CompactCounts& c, const CompactOutputs& o, Error* err) {
  const std::uint64_t V = c.V, T = c.T, N = c.N;
  const double kTwoPi = 6.283185307179586232;
  const BitReader turns(L.turns.data + fmt::TurnsHeader::kSize, L.turns.size - fmt::TurnsHeader::kSize);
  for (std::uint64_t t = 0; t < T; ++t) {
    const std::uint32_t* tri = o.triangles + 3 * t;
    const double* p0 = o.positions;
    const double e00 = p0[2 * tri[0]] - p0[2 * tri[2]], e10 = p0[2 * tri[0] + 1] - p0[2 * tri[2] + 1];
    const double e01 = p0[2 * tri[1]] - p0[2 * tri[2]], e11 = p0[2 * tri[1] + 1] - p0[2 * tri[2] + 1];
    const double det0 = e00 * e11 - e01 * e10;  // > 0: checked by BuildArapFactor
    const double i00 = e11 / det0, i01 = -e01 / det0, i10 = -e10 / det0, i11 = e00 / det0;  // E_0^-1
    for (std::uint64_t i = 0; i < N; ++i) {
      const double* p = o.positions + 2 * i * V;
      const double f00 = p[2 * tri[0]] - p[2 * tri[2]], f10 = p[2 * tri[0] + 1] - p[2 * tri[2] + 1];
      const double f01 = p[2 * tri[1]] - p[2 * tri[2]], f11 = p[2 * tri[1] + 1] - p[2 * tri[2] + 1];
      const double det = f00 * f11 - f01 * f10;
      if (!(det > 0) || !std::isfinite(det))
        return Fail(err, ErrorCode::kBadValue, "section QPOS: triangle %llu is inverted or degenerate in pose %llu",
                    (unsigned long long)t, (unsigned long long)i);
      const double a = f00 * i00 + f01 * i10, b = f00 * i01 + f01 * i11;
      const double cc = f10 * i00 + f11 * i10, d = f10 * i01 + f11 * i11;
      const PolarParts s = PolarSplit(a, b, cc, d);
      const std::uint64_t k = t * N + i;
      const std::int64_t turn = std::int64_t(L.turn_base) + std::int64_t(turns.At(k * L.turn_bits, L.turn_bits));
      o.angles[k] = s.alpha + kTwoPi * double(turn);
      o.stretches[3 * k] = s.s11;
      o.stretches[3 * k + 1] = s.s12;
      o.stretches[3 * k + 2] = s.s22;
    }
  }
  return true;
}

// Weight grid: per coded pose, corners predicted from their left, lower and
// lower-left neighbours, centres from the rounded mean of their corners.
bool DecodeWeightGrid(const CompactLayout& L, const CompactCounts& c, const CompactOutputs& o, Error* err) {
  const std::uint64_t N = c.N;
  const std::uint64_t cx = c.cells_x, cy = c.cells_y, row = cx + 1;
  const std::uint32_t coded = L.grid_coded_poses;
  const std::uint64_t header = GridPreamble(coded);
  BitReader r(L.grid.data + header, L.grid.size - header);
  const std::int64_t kLimit = std::int64_t(1) << 40;
  auto next = [&](unsigned k, std::int64_t pred, std::int64_t* q) {
    const std::uint64_t u = r.ReadGolomb(k, fmt::kMaxGolombZeros);
    *q = pred + fmt::UnZigZag(u);
    return !r.overrun && *q <= kLimit && *q >= -kLimit;
  };
  for (std::uint32_t i = 0; i < coded; ++i) {
    const auto code = fmt::DecodeEntry<fmt::GridPoseCode>(L.grid.data + fmt::GridHeader::kSize, i);
    const unsigned k_corner = code.corner_order, k_centre = code.centre_order, order = code.prediction_order;
    std::int64_t* q = o.grid_scratch;
    for (std::uint64_t y = 0; y <= cy; ++y)
      for (std::uint64_t x = 0; x <= cx; ++x) {
        std::int64_t pred;
        const std::int64_t* at = q + y * row + x;
        if (x >= order && y >= order) {  // inside: the formulas written out (the same integers)
          pred = order == 1 ? at[-1] + at[-std::int64_t(row)] - at[-std::int64_t(row) - 1]
                            : 2 * at[-1] - at[-2] + 2 * at[-std::int64_t(row)] - 4 * at[-std::int64_t(row) - 1] +
                                  2 * at[-std::int64_t(row) - 2] - at[-2 * std::int64_t(row)] +
                                  2 * at[-2 * std::int64_t(row) - 1] - at[-2 * std::int64_t(row) - 2];
        } else {
          pred = fmt::GridCornerPrediction(q, row, x, y, order);
        }
        if (!next(k_corner, pred, &q[y * row + x]))
          return Fail(err, ErrorCode::kBadValue,
                      "section QGRD: pose %u, corner (%llu, %llu): code runs past the section or out of range", i,
                      (unsigned long long)x, (unsigned long long)y);
        o.grid_corners[(y * row + x) * N + i] = L.grid_step * double(q[y * row + x]);
      }
    if (!o.grid_centres) continue;
    for (std::uint64_t y = 0; y < cy; ++y)
      for (std::uint64_t x = 0; x < cx; ++x) {
        const std::int64_t pred = fmt::GridCentrePrediction(q[y * row + x], q[y * row + x + 1], q[(y + 1) * row + x],
                                                            q[(y + 1) * row + x + 1]);
        std::int64_t value;
        if (!next(k_centre, pred, &value))
          return Fail(err, ErrorCode::kBadValue,
                      "section QGRD: pose %u, centre (%llu, %llu): code runs past the section or out of range", i,
                      (unsigned long long)x, (unsigned long long)y);
        o.grid_centres[(y * cx + x) * N + i] = L.grid_step * double(value);
      }
  }
  if ((r.position() + 7) / 8 != r.size_bits() / 8)
    return Fail(err, ErrorCode::kBadLayout, "section QGRD has %llu bytes after its codes",
                (unsigned long long)(r.size_bits() / 8 - (r.position() + 7) / 8));
  if (coded + 1 == N) {
    auto complete = [&](double* w, std::uint64_t nodes) {
      for (std::uint64_t g = 0; g < nodes; ++g) {
        double sum = 0;
        for (std::uint64_t i = 0; i + 1 < N; ++i) sum += w[g * N + i];
        w[g * N + N - 1] = 1 - sum;
      }
    };
    complete(o.grid_corners, (cx + 1) * (cy + 1));
    if (o.grid_centres) complete(o.grid_centres, cx * cy);
  }
  return true;
}

// Uvs: each pose's as an affine map of one pose's decoded positions.
bool DecodeUvs(const CompactLayout& L, const CompactCounts& c, const CompactOutputs& o, Error* err) {
  const std::uint64_t V = c.V, N = c.N;
  if (o.uvs) {
    for (std::uint64_t i = 0; i < N; ++i) {
      const auto e = fmt::DecodeEntry<fmt::AffineUvEntry>(L.affine_uvs.data, i);
      const double* p = o.positions + 2 * std::uint64_t(e.source_pose) * V;
      const double* m = e.map;
      for (std::uint64_t v = 0; v < V; ++v) {
        const double u = m[0] * p[2 * v] + m[1] * p[2 * v + 1] + m[2];
        const double w = m[3] * p[2 * v] + m[4] * p[2 * v + 1] + m[5];
        if (!(std::fabs(u) <= 1e30) || !(std::fabs(w) <= 1e30))  // a float holds it
          return Fail(err, ErrorCode::kBadValue, "section QUVA: uv of vertex %llu in pose %llu is beyond 1e30",
                      (unsigned long long)v, (unsigned long long)i);
        o.uvs[2 * (i * V + v)] = float(u);
        o.uvs[2 * (i * V + v) + 1] = float(w);
      }
    }
  }
  return true;
}

}  // namespace

bool DecodeCompact(const CompactLayout& L, const CompactCounts& c, const CompactOutputs& o, Error* err) {
  const std::uint64_t V = c.V, T = c.T;
  if (!DecodeTriangles(L, c, o, err)) return false;
  if (!DecodePermutation(L, c, o, err)) return false;
  if (!DecodePositions(L, c, o, err)) return false;
  // Gradients, masses and the factor from the rest pose.
  if (!BuildArapFactor(o.positions, V, o.triangles, T, o.order, c.nnz, o.factor, err)) return false;
  ComputeCentroids(c, o);
  if (!ComputeAnglesAndStretches(L, c, o, err)) return false;
  if (!DecodeWeightGrid(L, c, o, err)) return false;
  if (!DecodeUvs(L, c, o, err)) return false;
  return true;
}

}  // namespace posemorph::detail
