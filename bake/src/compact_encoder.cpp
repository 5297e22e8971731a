// SPDX-License-Identifier: MIT
// The compact encoding's writer (compact_encoder.h): quantised positions,
// delta-coded triangles, the packed order, whole turns, the predicted
// weight grid, affine uvs, the sections kept as they are.
#include "compact_encoder.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "posemorph/compact_codec.h"
#include "posemorph/rig_format.h"
#include "rig_writer.h"

namespace posemorph::bake::compact {
namespace {

namespace fmt = format;

// Bits packed least significant first, as the runtime's BitReader reads them.
class BitWriter {
 public:
  void Put(std::uint64_t value, unsigned width) {
    for (unsigned i = 0; i < width; ++i) {
      if (bits_ % 8 == 0) bytes_.push_back(0);
      if ((value >> i) & 1u) bytes_.back() |= static_cast<unsigned char>(1u << (bits_ % 8));
      ++bits_;
    }
  }
  // Order-k Exp-Golomb: w = u + 2^k with highest bit at `width`: width - k
  // zeros, a one, then the width bits below the highest.
  void Golomb(std::uint64_t u, unsigned k) {
    const std::uint64_t w = u + (std::uint64_t(1) << k);
    unsigned width = 0;
    while ((w >> (width + 1)) != 0) ++width;
    Put(0, width - k);
    Put(1, 1);
    const std::uint64_t m = w - (std::uint64_t(1) << width);
    if (width > 32) {
      Put(m >> 32, width - 32);
      Put(m & 0xFFFFFFFFu, 32);
    } else {
      Put(m, width);
    }
  }
  const std::vector<unsigned char>& bytes() const { return bytes_; }

 private:
  std::vector<unsigned char> bytes_;
  std::uint64_t bits_ = 0;
};

unsigned GolombBits(std::uint64_t u, unsigned k) {
  const std::uint64_t w = u + (std::uint64_t(1) << k);
  unsigned width = 0;
  while ((w >> (width + 1)) != 0) ++width;
  return 2 * width - k + 1;
}

// The bits these values take as order-k Exp-Golomb codes.
std::uint64_t CodedBits(const std::vector<std::uint64_t>& codes, unsigned k) {
  std::uint64_t bits = 0;
  for (std::uint64_t u : codes) bits += GolombBits(u, k);
  return bits;
}

// The Exp-Golomb order (0..20) that codes these values in the fewest bits.
unsigned BestOrder(const std::vector<std::uint64_t>& codes) {
  unsigned best = 0;
  std::uint64_t best_bits = ~std::uint64_t(0);
  for (unsigned k = 0; k <= 20; ++k) {
    const std::uint64_t bits = CodedBits(codes, k);
    if (bits < best_bits) best_bits = bits, best = k;
  }
  return best;
}

unsigned BitsFor(std::uint64_t max_value) {
  unsigned b = 1;
  while (b < 32 && (max_value >> b) != 0) ++b;
  return b;
}

std::vector<unsigned char> Packed(const std::vector<std::uint32_t>& values, unsigned width) {
  fmt::PackedArrayHeader header{};
  header.width = width;
  std::vector<unsigned char> out = RecordBytes(header);
  BitWriter w;
  for (std::uint32_t v : values) w.Put(v, width);
  out.insert(out.end(), w.bytes().begin(), w.bytes().end());
  return out;
}

// QPOS's codes under one predictor of a vertex's integers (the previous
// vertex's where `start` is null, else the mean of its earlier neighbours):
// each pose alone, or the poses after the first less pose 0's residuals,
// whichever takes fewer bits.
struct PositionCoding {
  std::uint32_t prediction = 0;                   // QuantPositionsHeader::prediction
  unsigned first_k = 0;                           // the order of `first`
  std::vector<std::uint64_t> first;               // pose 0's codes, or every pose's when coded alone
  std::vector<unsigned> later_k;                  // against pose 0: each later pose's order
  std::vector<std::vector<std::uint64_t>> later;  // and its codes
  std::uint64_t bits = 0;
};

PositionCoding CodePositions(const std::vector<std::int64_t>& q, std::uint64_t V, std::uint64_t N,
                             const std::uint32_t* start, const std::uint32_t* list) {
  std::vector<std::int64_t> residual(q.size());
  for (std::uint64_t i = 0; i < N; ++i)
    for (std::uint64_t v = 0; v < V; ++v)
      for (std::uint64_t d = 0; d < 2; ++d) {
        const std::int64_t* pose = q.data() + 2 * i * V + d;
        const std::int64_t prediction =
            start ? fmt::NeighbourPrediction(pose, 2, v, start, list) : (v > 0 ? pose[2 * (v - 1)] : 0);
        residual[2 * (i * V + v) + d] = pose[2 * v] - prediction;
      }
  PositionCoding alone, against;
  for (std::int64_t r : residual) alone.first.push_back(fmt::ZigZag(r));
  alone.first_k = BestOrder(alone.first);
  alone.bits = CodedBits(alone.first, alone.first_k);
  against.prediction = fmt::kPositionsAgainstPose0;
  against.first.assign(alone.first.begin(), alone.first.begin() + std::ptrdiff_t(2 * V));
  against.first_k = BestOrder(against.first);
  against.bits = CodedBits(against.first, against.first_k);
  for (std::uint64_t i = 1; i < N; ++i) {
    std::vector<std::uint64_t> codes;
    for (std::uint64_t k = 0; k < 2 * V; ++k) codes.push_back(fmt::ZigZag(residual[2 * i * V + k] - residual[k]));
    against.later_k.push_back(BestOrder(codes));
    against.bits += 5 + CodedBits(codes, against.later_k.back());
    against.later.push_back(std::move(codes));
  }
  PositionCoding best = N > 1 && against.bits < alone.bits ? std::move(against) : std::move(alone);
  if (start) best.prediction |= fmt::kPositionsFromNeighbours;
  return best;
}

std::string TagText(std::uint32_t tag) {
  std::string s(4, ' ');
  for (int i = 0; i < 4; ++i) s[std::size_t(i)] = char((tag >> (8 * i)) & 0xFFu);
  return s;
}

// A section SerialiseRig always writes.
const std::vector<unsigned char>& ExactSection(const RigSections& exact, std::uint32_t tag) {
  const std::vector<unsigned char>* bytes = exact.Find(tag);
  if (!bytes) throw std::logic_error("the exact rig has no section " + TagText(tag));
  return *bytes;
}

}  // namespace

RigSections Encoder::Encode(double position_step, double weight_step, CompactReport* report,
                            const fmt::CompactInfo* info) const {
  const std::uint64_t V = exact.vertex_count(), T = exact.triangle_count(), N = exact.pose_count(), n = V - 1;
  std::vector<CompactSection> sections;
  auto note = [&](std::uint32_t tag, std::size_t bytes, std::string what) {
    sections.push_back({TagText(tag), bytes, std::move(what)});
  };
  fmt::Meta meta = fmt::DecodeRecord<fmt::Meta>(ExactSection(raw, fmt::kMeta).data());
  meta.flags |= fmt::kMetaFlagCompact;
  const std::vector<unsigned char> meta_bytes = RecordBytes(meta);

  RigSections w;
  w.Add(fmt::kMeta, meta_bytes);
  note(fmt::kMeta, meta_bytes.size(), "counts and grid geometry");
  // Positions: per pose its lower-left corner, then step * q.
  std::vector<unsigned char> qpos;
  std::vector<std::int64_t> q(2 * N * V);  // each in 0..2^40 (checked below)
  std::int64_t qmax = 0;
  std::vector<double> origins;
  for (std::uint64_t i = 0; i < N; ++i) {
    const Span<const double> p = exact.pose_positions(std::uint32_t(i));
    double ox = p[0], oy = p[1];
    for (std::uint64_t v = 0; v < V; ++v) ox = std::min(ox, p[2 * v]), oy = std::min(oy, p[2 * v + 1]);
    origins.push_back(ox);
    origins.push_back(oy);
    for (std::uint64_t v = 0; v < 2 * V; ++v) {
      const double o = v % 2 ? oy : ox;
      const double value = std::llround((p[v] - o) / position_step);
      q[2 * i * V + v] = std::int64_t(value);
      qmax = std::max(qmax, q[2 * i * V + v]);
    }
  }
  if (qmax >= (std::int64_t(1) << 40)) return {};
  // Each vertex's integers as residuals of a prediction: the previous
  // vertex's, or (1.14) the mean of the vertex's earlier neighbours in the
  // mesh (a vertex split from an edge and smoothed sits near it); in the
  // poses after the first, less pose 0's residual there (a limb that moves
  // as a whole moves its neighbouring vertices alike). The choice that codes
  // in the fewest bits is written.
  std::vector<std::uint32_t> start(V + 1), fill(V), list(3 * T);
  fmt::EarlierNeighbours(exact.triangles().data, T, V, start.data(), fill.data(), list.data());
  const PositionCoding by_previous = CodePositions(q, V, N, nullptr, nullptr);
  const PositionCoding by_neighbours = CodePositions(q, V, N, start.data(), list.data());
  const PositionCoding& coding = by_neighbours.bits < by_previous.bits ? by_neighbours : by_previous;
  fmt::QuantPositionsHeader qpos_header{};
  qpos_header.step = position_step;
  qpos_header.code_order = coding.first_k;
  qpos_header.prediction = coding.prediction;
  AppendRecord(qpos, qpos_header);
  for (std::uint64_t i = 0; i < N; ++i) AppendRecord(qpos, fmt::Point{origins[2 * i], origins[2 * i + 1]});
  {
    BitWriter bw;
    for (std::uint64_t u : coding.first) bw.Golomb(u, coding.first_k);
    for (std::size_t i = 0; i < coding.later.size(); ++i) {
      bw.Put(coding.later_k[i], 5);
      for (std::uint64_t u : coding.later[i]) bw.Golomb(u, coding.later_k[i]);
    }
    qpos.insert(qpos.end(), bw.bytes().begin(), bw.bytes().end());
  }
  std::string how = coding.prediction & fmt::kPositionsFromNeighbours ? ", from earlier neighbours" : ", delta coded";
  if (coding.prediction & fmt::kPositionsAgainstPose0) how += ", the poses after the first against pose 0";
  note(fmt::kQuantPositions, qpos.size(), "positions, step " + std::to_string(position_step) + how);
  w.Add(fmt::kQuantPositions, qpos);

  std::vector<std::uint64_t> tri_codes;
  for (std::uint64_t k = 0; k < 3 * T; ++k)
    tri_codes.push_back(
        fmt::ZigZag(std::int64_t(exact.triangles()[k]) - (k >= 3 ? std::int64_t(exact.triangles()[k - 3]) : 0)));
  const unsigned tri_k = BestOrder(tri_codes);
  std::vector<unsigned char> qtri;
  fmt::CodedTrianglesHeader qtri_header{};
  qtri_header.code_order = tri_k;
  AppendRecord(qtri, qtri_header);
  {
    BitWriter bw;
    for (std::uint64_t u : tri_codes) bw.Golomb(u, tri_k);
    qtri.insert(qtri.end(), bw.bytes().begin(), bw.bytes().end());
  }
  note(fmt::kQuantTriangles, qtri.size(), "vertex indices, delta coded");
  w.Add(fmt::kQuantTriangles, qtri);
  std::vector<std::uint32_t> order(exact.factor().order.data, exact.factor().order.data + n);
  const auto qprm = Packed(order, BitsFor(n - 1));
  note(fmt::kQuantPermutation, qprm.size(), std::to_string(BitsFor(n - 1)) + "-bit fill-reducing order");
  w.Add(fmt::kQuantPermutation, qprm);

  // Turns: angle = principal angle + 2 pi turn.
  std::vector<unsigned char> qtrn;
  {
    std::int32_t lo = 0, hi = 0;
    if (!turns.empty())
      lo = *std::min_element(turns.begin(), turns.end()), hi = *std::max_element(turns.begin(), turns.end());
    const unsigned bits = hi == lo ? 0 : BitsFor(std::uint64_t(std::int64_t(hi) - lo));
    AppendRecord(qtrn, fmt::TurnsHeader{lo, bits});
    BitWriter bw;
    for (std::uint64_t k = 0; k < T * N && bits; ++k) bw.Put(std::uint64_t(std::int64_t(turns[k]) - lo), bits);
    qtrn.insert(qtrn.end(), bw.bytes().begin(), bw.bytes().end());
    note(fmt::kQuantTurns, qtrn.size(),
         bits ? std::to_string(bits) + "-bit whole turns" : "no turns (all " + std::to_string(lo) + ")");
  }
  w.Add(fmt::kQuantTurns, qtrn);

  // Weight grid.
  {
    const PoseSpaceGrid& g = exact.grid();
    const std::uint64_t row = g.cells_x + 1, corners = row * (g.cells_y + 1);
    const std::uint32_t coded = std::uint32_t(derive_last_pose ? N - 1 : N);
    std::vector<unsigned char> qgrd;
    fmt::GridHeader qgrd_header{};
    qgrd_header.step = weight_step;
    qgrd_header.coded_poses = coded;
    AppendRecord(qgrd, qgrd_header);
    BitWriter bw;
    std::vector<fmt::GridPoseCode> params;
    for (std::uint32_t i = 0; i < coded; ++i) {
      std::vector<std::int64_t> qc(corners);
      for (std::uint64_t k = 0; k < corners; ++k) qc[k] = std::llround(g.weights[k * N + i] / weight_step);
      // The predictor order that codes this pose's corners in fewer bits.
      std::vector<std::uint64_t> corner_codes, centre_codes, by_order[2];
      for (unsigned o = 1; o <= 2; ++o)
        for (std::uint64_t y = 0; y <= g.cells_y; ++y)
          for (std::uint64_t x = 0; x < row; ++x)
            by_order[o - 1].push_back(
                fmt::ZigZag(qc[y * row + x] - fmt::GridCornerPrediction(qc.data(), row, x, y, o)));
      const unsigned k1 = BestOrder(by_order[0]), k2 = BestOrder(by_order[1]);
      const unsigned corner_order = CodedBits(by_order[1], k2) < CodedBits(by_order[0], k1) ? 2 : 1;
      corner_codes = by_order[corner_order - 1];
      for (std::uint64_t y = 0; y < g.cells_y && !g.centre_weights.empty(); ++y)
        for (std::uint64_t x = 0; x < g.cells_x; ++x) {
          const std::int64_t value = std::llround(g.centre_weights[(y * g.cells_x + x) * N + i] / weight_step);
          const std::int64_t pred = fmt::GridCentrePrediction(qc[y * row + x], qc[y * row + x + 1],
                                                              qc[(y + 1) * row + x], qc[(y + 1) * row + x + 1]);
          centre_codes.push_back(fmt::ZigZag(value - pred));
        }
      const unsigned kc = BestOrder(corner_codes), kz = centre_codes.empty() ? 0 : BestOrder(centre_codes);
      params.push_back(fmt::GridPoseCode{std::uint8_t(kc), std::uint8_t(kz), std::uint16_t(corner_order)});
      for (std::uint64_t u : corner_codes) bw.Golomb(u, kc);
      for (std::uint64_t u : centre_codes) bw.Golomb(u, kz);
    }
    for (const fmt::GridPoseCode& p : params) AppendRecord(qgrd, p);
    qgrd.insert(qgrd.end(), bw.bytes().begin(), bw.bytes().end());
    char what[160];
    std::snprintf(what, sizeof(what), "weights step %.3g, predicted, Exp-Golomb; %u of %llu poses stored%s",
                  weight_step, coded, (unsigned long long)N, derive_last_pose ? " (the last is 1 - the others)" : "");
    note(fmt::kQuantGrid, qgrd.size(), what);
    w.Add(fmt::kQuantGrid, qgrd);
  }

  // Uvs: affine in a pose's decoded positions when that reproduces them.
  if (!exact.uvs(0).empty()) {
    std::vector<unsigned char> quva;
    bool affine = true;
    std::vector<double> decoded(2 * N * V);
    for (std::uint64_t i = 0; i < N; ++i)
      for (std::uint64_t v = 0; v < 2 * V; ++v)
        decoded[2 * i * V + v] = origins[2 * i + v % 2] + position_step * double(q[2 * i * V + v]);
    for (std::uint64_t i = 0; i < N && affine; ++i) {
      const Span<const float> uv = exact.uvs(std::uint32_t(i));
      bool found = false;
      for (std::uint64_t c = 0; c < N && !found; ++c) {
        const std::uint64_t src = c == 0 ? i : (c <= i ? c - 1 : c);
        Eigen::MatrixXd X(V, 3);
        Eigen::MatrixXd Y(V, 2);
        for (std::uint64_t v = 0; v < V; ++v) {
          X(Eigen::Index(v), 0) = decoded[2 * (src * V + v)];
          X(Eigen::Index(v), 1) = decoded[2 * (src * V + v) + 1];
          X(Eigen::Index(v), 2) = 1;
          Y(Eigen::Index(v), 0) = uv[2 * v];
          Y(Eigen::Index(v), 1) = uv[2 * v + 1];
        }
        const Eigen::MatrixXd M = X.colPivHouseholderQr().solve(Y);  // 3 x 2
        double m[6] = {M(0, 0), M(1, 0), M(2, 0), M(0, 1), M(1, 1), M(2, 1)};
        // In pixels of the drawing the uvs address (or of the rig's size
        // for uvs without a canvas): the decoded vertex moved by at most
        // half a step, and its uv follows it.
        const DrawingCanvas canvas = exact.pose_canvas(std::uint32_t(i));
        const double w_px = canvas.width > 0 ? canvas.width : exact.bounding_box_diagonal() * pixels_per_unit;
        const double h_px = canvas.height > 0 ? canvas.height : exact.bounding_box_diagonal() * pixels_per_unit;
        double worst = 0;
        for (std::uint64_t v = 0; v < V; ++v) {
          const double x = decoded[2 * (src * V + v)], y = decoded[2 * (src * V + v) + 1];
          worst = std::max(worst, w_px * std::fabs(double(float(m[0] * x + m[1] * y + m[2])) - uv[2 * v]));
          worst = std::max(worst, h_px * std::fabs(double(float(m[3] * x + m[4] * y + m[5])) - uv[2 * v + 1]));
        }
        if (worst <= uv_tolerance_px && std::isfinite(worst)) {
          found = true;
          fmt::AffineUvEntry entry{};
          entry.source_pose = std::uint32_t(src);
          std::copy(m, m + 6, entry.map);
          AppendRecord(quva, entry);
        }
      }
      affine = found;
    }
    if (affine) {
      note(fmt::kAffineUVs, quva.size(), "uvs as affine maps of a pose's positions");
      w.Add(fmt::kAffineUVs, quva);
    } else {
      note(fmt::kUVs, ExactSection(raw, fmt::kUVs).size(), "f32 uvs (not affine in any pose's positions)");
      w.Add(fmt::kUVs, ExactSection(raw, fmt::kUVs));
    }
    if (report) report->affine_uvs = affine;
  }
  for (std::uint32_t tag : {fmt::kPosePoints, fmt::kStrings, fmt::kPaths, fmt::kPathKeys, fmt::kCanvases,
                            fmt::kPlacement, fmt::kParts, fmt::kPartPoseOrders, fmt::kEvents}) {
    const std::vector<unsigned char>* bytes = raw.Find(tag);
    if (!bytes) continue;
    w.Add(tag, *bytes);
    note(tag, bytes->size(), "as in the exact rig");
  }
  if (info) {
    const std::vector<unsigned char> qinf = RecordBytes(*info);
    note(fmt::kCompactInfo, qinf.size(), "error budget and the error reached");
    w.Add(fmt::kCompactInfo, qinf);
  }
  if (report) report->sections = sections;
  return w;
}

}  // namespace posemorph::bake::compact
