// SPDX-License-Identifier: MIT
#include "posemorph/bake/compact_rig.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <stdexcept>

#include <Eigen/Dense>

#include "posemorph/bake/error.h"
#include "posemorph/bake/pose_space_samples.h"
#include "posemorph/compact_codec.h"
#include "posemorph/jobs.h"
#include "posemorph/path.h"
#include "posemorph/rig.h"
#include "posemorph/rig_format.h"
#include "rig_writer.h"

namespace posemorph::bake {
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

// The Exp-Golomb order (0..20) that codes these values in the fewest bits.
unsigned BestOrder(const std::vector<std::uint64_t>& codes) {
  unsigned best = 0;
  std::uint64_t best_bits = ~std::uint64_t(0);
  for (unsigned k = 0; k <= 20; ++k) {
    std::uint64_t bits = 0;
    for (std::uint64_t u : codes) bits += GolombBits(u, k);
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

std::map<std::uint32_t, std::vector<unsigned char>> RawSections(const std::vector<unsigned char>& bytes) {
  std::map<std::uint32_t, std::vector<unsigned char>> out;
  RigSection table[fmt::kMaxSections];
  std::uint32_t count = 0;
  Error err;
  if (!ReadRigSections(bytes.data(), bytes.size(), table, fmt::kMaxSections, &count, &err))
    throw std::logic_error(std::string("compact encoding: the exact rig's sections: ") + err.message);
  for (std::uint32_t i = 0; i < count; ++i)
    out[table[i].tag].assign(bytes.begin() + std::ptrdiff_t(table[i].offset),
                             bytes.begin() + std::ptrdiff_t(table[i].offset + table[i].size));
  return out;
}

std::string TagText(std::uint32_t tag) {
  std::string s(4, ' ');
  for (int i = 0; i < 4; ++i) s[std::size_t(i)] = char((tag >> (8 * i)) & 0xFFu);
  return s;
}

// Frames sampled where the rig is used: the pose points, a grid over the
// convex hull of the pose points and its edges, and every path.
std::vector<Eigen::Vector2d> SamplePoints(const Rig& rig) {
  std::vector<Eigen::Vector2d> out;
  for (const PoseSpaceSample& s : SamplePoseSpace(rig, PoseSpaceSampling{})) out.push_back(s.at);
  return out;
}

struct Encoder {
  const Rig& exact;
  double uv_tolerance_px;
  double pixels_per_unit;
  std::map<std::uint32_t, std::vector<unsigned char>> raw;
  std::vector<std::int32_t> turns;  // T x N, filled after a first load
  bool derive_last_pose = false;

  std::vector<unsigned char> Encode(double position_step, double weight_step, CompactReport* report,
                                    const fmt::CompactInfo* info = nullptr) const {
    const std::uint64_t V = exact.vertex_count(), T = exact.triangle_count(), N = exact.pose_count(), n = V - 1;
    std::vector<CompactSection> sections;
    auto note = [&](std::uint32_t tag, std::size_t bytes, std::string what) {
      sections.push_back({TagText(tag), bytes, std::move(what)});
    };
    fmt::Meta meta = fmt::DecodeRecord<fmt::Meta>(raw.at(fmt::kMeta).data());
    meta.flags |= fmt::kMetaFlagCompact;
    const std::vector<unsigned char> meta_bytes = RecordBytes(meta);

    RigWriter w;
    w.Add(fmt::kMeta, meta_bytes);
    note(fmt::kMeta, meta_bytes.size(), "counts and grid geometry");
    // Positions: per pose its lower-left corner, then step * q.
    std::vector<unsigned char> qpos;
    std::vector<std::uint64_t> q(2 * N * V);
    std::uint64_t qmax = 0;
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
        q[2 * i * V + v] = std::uint64_t(value);
        qmax = std::max<std::uint64_t>(qmax, std::uint64_t(value));
      }
    }
    if (qmax >= (std::uint64_t(1) << 40)) return {};
    // Each vertex's integers as differences from the previous vertex's.
    std::vector<std::uint64_t> pos_codes;
    for (std::uint64_t i = 0; i < N; ++i)
      for (std::uint64_t v = 0; v < V; ++v)
        for (int d = 0; d < 2; ++d) {
          const std::uint64_t k = 2 * (i * V + v) + d;
          const std::int64_t previous = v > 0 ? std::int64_t(q[k - 2]) : 0;
          pos_codes.push_back(fmt::ZigZag(std::int64_t(q[k]) - previous));
        }
    const unsigned pos_k = BestOrder(pos_codes);
    fmt::QuantPositionsHeader qpos_header{};
    qpos_header.step = position_step;
    qpos_header.code_order = pos_k;
    AppendRecord(qpos, qpos_header);
    for (std::uint64_t i = 0; i < N; ++i) AppendRecord(qpos, fmt::Point{origins[2 * i], origins[2 * i + 1]});
    {
      BitWriter bw;
      for (std::uint64_t u : pos_codes) bw.Golomb(u, pos_k);
      qpos.insert(qpos.end(), bw.bytes().begin(), bw.bytes().end());
    }
    note(fmt::kQuantPositions, qpos.size(), "positions, step " + std::to_string(position_step) + ", delta coded");
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
        std::uint64_t bits1 = 0, bits2 = 0;
        for (std::uint64_t u : by_order[0]) bits1 += GolombBits(u, k1);
        for (std::uint64_t u : by_order[1]) bits2 += GolombBits(u, k2);
        const unsigned corner_order = bits2 < bits1 ? 2 : 1;
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
        note(fmt::kUVs, raw.at(fmt::kUVs).size(), "f32 uvs (not affine in any pose's positions)");
        w.Add(fmt::kUVs, raw.at(fmt::kUVs));
      }
      if (report) report->affine_uvs = affine;
    }
    for (std::uint32_t tag : {fmt::kPosePoints, fmt::kStrings, fmt::kPaths, fmt::kPathKeys, fmt::kCanvases, fmt::kParts,
                              fmt::kPartPoseOrders}) {
      const auto it = raw.find(tag);
      if (it == raw.end()) continue;
      w.Add(tag, it->second);
      note(tag, it->second.size(), "as in the exact rig");
    }
    if (info) {
      const std::vector<unsigned char> qinf = RecordBytes(*info);
      note(fmt::kCompactInfo, qinf.size(), "error budget and the error reached");
      w.Add(fmt::kCompactInfo, qinf);
    }
    if (report) report->sections = sections;
    return w.Finish();
  }
};

// Whether the grid sums to 1 at every node (so the last pose need not be stored).
bool GridSumsToOne(const Rig& exact) {
  const std::uint64_t N = exact.pose_count();
  double worst_sum = 0;
  for (const Span<const double>& w : {exact.grid().weights, exact.grid().centre_weights})
    for (std::size_t g = 0; g < w.size / N; ++g) {
      double sum = 0;
      for (std::size_t i = 0; i < N; ++i) sum += w[g * N + i];
      worst_sum = std::max(worst_sum, std::fabs(sum - 1));
    }
  return worst_sum <= 1e-9;
}

// Largest distance a vertex travels between poses (centroids aligned): how
// far a weight error moves it.
double WeightReach(const Rig& exact) {
  const std::uint64_t V = exact.vertex_count(), N = exact.pose_count();
  double reach = 0;
  for (std::uint64_t i = 1; i < N; ++i) {
    const Span<const double> p = exact.pose_positions(std::uint32_t(i)), r = exact.pose_positions(0);
    const double* c = exact.pose_centroids().data;
    for (std::uint64_t v = 0; v < V; ++v)
      reach = std::max(reach, std::hypot((p[2 * v] - c[2 * i]) - (r[2 * v] - c[0]),
                                         (p[2 * v + 1] - c[2 * i + 1]) - (r[2 * v + 1] - c[1])));
  }
  return std::max(reach, 0.05 * exact.bounding_box_diagonal());
}

struct Trial {
  bool ok = false;
  double error = 0, pose_error = 0;
  std::vector<unsigned char> bytes;
  std::vector<std::int32_t> turns;
};

// Encodes at a position step and a weight step, loads the result with the
// runtime and measures every sample frame against the exact rig's.
struct Trials {
  const Rig& exact;
  Encoder& enc;
  const std::vector<Eigen::Vector2d>& samples;
  const std::vector<std::vector<double>>& reference;
  double accept;  // the error a trial may reach
  CompactReport& rep;

  Trial Attempt(double ps, double ws) {
    const std::uint64_t V = exact.vertex_count(), T = exact.triangle_count(), N = exact.pose_count();
    Error err;
    Trial t;
    ++rep.trials;
    // First without turns, to learn the principal angles the runtime derives.
    enc.turns.clear();
    std::vector<unsigned char> bytes = enc.Encode(ps, ws, nullptr);
    Rig rig;
    if (bytes.empty() || !LoadRig(bytes.data(), bytes.size(), &rig, &err)) return t;
    enc.turns.resize(T * N);
    for (std::uint64_t k = 0; k < T * N; ++k)
      enc.turns[k] = std::int32_t(std::llround((exact.angles()[k] - rig.angles()[k]) / (2 * M_PI)));
    t.bytes = enc.Encode(ps, ws, nullptr);
    t.turns = enc.turns;
    if (!LoadRig(t.bytes.data(), t.bytes.size(), &rig, &err)) return t;
    std::vector<double> x;
    for (std::size_t s = 0; s < samples.size(); ++s) {
      if (!EvaluateFrame(rig, samples[s], x)) return t;
      double worst = 0;
      for (std::uint64_t v = 0; v < V; ++v)
        worst = std::max(worst, std::hypot(x[2 * v] - reference[s][2 * v], x[2 * v + 1] - reference[s][2 * v + 1]));
      t.error = std::max(t.error, worst);
      if (s < N) t.pose_error = std::max(t.pose_error, worst);
    }
    t.ok = t.error <= accept;
    return t;
  }
};

}  // namespace

std::vector<unsigned char> CompactRig(const std::vector<unsigned char>& exact_bytes, const CompactSettings& settings,
                                      const std::string& file, CompactReport* report) {
  Rig exact;
  Error err;
  if (!LoadRig(exact_bytes.data(), exact_bytes.size(), &exact, &err))
    throw BakeError(file, std::string("internal error: the exact rig does not load: ") + err.message);
  if (!(settings.max_error_px > 0) || !(settings.pixels_per_unit > 0))
    throw BakeError(file, "the compact encoding needs a positive error budget and pixels per unit");
  Encoder enc{exact, settings.max_error_px / 2, settings.pixels_per_unit, RawSections(exact_bytes), {}, false};
  enc.derive_last_pose = GridSumsToOne(exact);

  const std::vector<Eigen::Vector2d> samples = SamplePoints(exact);
  std::vector<std::vector<double>> reference(samples.size());
  for (std::size_t s = 0; s < samples.size(); ++s)
    if (!EvaluateFrame(exact, samples[s], reference[s]))
      throw BakeError(file, "internal error: the exact rig does not evaluate");

  const double budget = settings.max_error_px / settings.pixels_per_unit;  // rig units
  const double reach = WeightReach(exact);
  // Accepted at 90% of the budget: frames between the samples may come out
  // slightly worse than the worst sample.
  CompactReport rep;
  Trials trials{exact, enc, samples, reference, 0.9 * budget, rep};
  auto attempt = [&](double ps, double ws) { return trials.Attempt(ps, ws); };
  // Positions first, with a fine grid, to within half the budget; then the
  // coarsest grid step that keeps the whole within budget.
  const double fine_weights = 1e-9;
  double ps = budget / 4;
  Trial best;
  for (int k = 0; k < 12; ++k, ps /= 2) {
    best = attempt(ps, fine_weights);
    if (best.ok && best.error <= budget / 2) break;
  }
  for (int k = 0; k < 4 && best.ok; ++k) {  // coarser while well inside
    Trial coarser = attempt(2 * ps, fine_weights);
    if (!coarser.ok || coarser.error > budget / 2) break;
    ps *= 2;
    best = std::move(coarser);
  }
  if (!best.ok) {
    // Nothing within budget (a sliver that folds under any step tried, say):
    // the exact encoding, and the caller says so.
    rep.fell_back = true;
    if (report) *report = rep;
    return exact_bytes;
  }
  double ws = budget / (4 * reach);
  Trial t = attempt(ps, ws);
  if (t.ok) {
    for (int k = 0; k < 6; ++k) {
      Trial coarser = attempt(ps, 2 * ws);
      if (!coarser.ok) break;
      ws *= 2;
      t = std::move(coarser);
    }
  } else {
    for (int k = 0; k < 12 && !t.ok; ++k) {
      ws /= 2;
      t = attempt(ps, ws);
    }
  }
  if (!t.ok) t = std::move(best), ws = fine_weights;
  rep.max_error_px = t.error * settings.pixels_per_unit;
  rep.pose_error_px = t.pose_error * settings.pixels_per_unit;
  // The measured encoding again, now with its record of budget and error
  // (QINF, which the loader does not read).
  enc.turns = t.turns;
  const fmt::CompactInfo info{settings.max_error_px, rep.max_error_px, rep.pose_error_px, settings.pixels_per_unit};
  t.bytes = enc.Encode(ps, ws, &rep, &info);
  rep.samples = std::uint32_t(samples.size());
  rep.position_step_px = ps * settings.pixels_per_unit;
  rep.weight_step = ws;
  if (report) *report = rep;
  return t.bytes;
}

}  // namespace posemorph::bake
