// SPDX-License-Identifier: MIT
// The compact encoding (format 1.3): each sample's compact rig against its
// exact rig (both baked by this build into rigs/), measured here
// independently of the bake's own measurement and more densely; the size
// targets; and hostile compact sections, with the checksum recomputed so
// that every mutation reaches the decoder.
#include <cmath>
#include <cstring>
#include <random>

#include "posemorph/compact_codec.h"
#include "posemorph/path.h"
#include "posemorph/rig_format.h"
#include "runtime_support.h"

using namespace posemorph;
using namespace posemorph::test;

namespace {

// Drawing pixels per rig unit, as the bake counts them: 1 for drawn rigs,
// else the rig's size taken as 1024 pixels.
double PixelsPerUnit(const Rig& rig) {
  return rig.pose_canvas(0).width > 0 ? 1.0 : 1024.0 / rig.bounding_box_diagonal();
}

// The pose points, a 41 x 41 grid over the bounding box of the pose points
// kept where it lies inside their convex hull (or on its edges), and each
// path at 257 times.
std::vector<std::pair<double, double>> DenseSamples(const Rig& rig) {
  const std::uint32_t N = rig.pose_count();
  const double* p = rig.pose_points().data;
  std::vector<std::pair<double, double>> out;
  double x0 = p[0], x1 = p[0], y0 = p[1], y1 = p[1];
  for (std::uint32_t i = 0; i < N; ++i) {
    out.push_back({p[2 * i], p[2 * i + 1]});
    x0 = std::min(x0, p[2 * i]), x1 = std::max(x1, p[2 * i]);
    y0 = std::min(y0, p[2 * i + 1]), y1 = std::max(y1, p[2 * i + 1]);
  }
  // Inside the hull: a convex combination exists; test by the sign of every
  // pose-point triangle fan is not enough for a general set, so use the
  // half-planes of all pairs that have every point on one side.
  auto inside = [&](double x, double y) {
    for (std::uint32_t a = 0; a < N; ++a)
      for (std::uint32_t b = 0; b < N; ++b) {
        if (a == b) continue;
        const double ax = p[2 * a], ay = p[2 * a + 1], bx = p[2 * b], by = p[2 * b + 1];
        bool all_left = true;
        for (std::uint32_t c = 0; c < N; ++c)
          all_left = all_left && (bx - ax) * (p[2 * c + 1] - ay) - (by - ay) * (p[2 * c] - ax) >= -1e-12;
        if (all_left && (bx - ax) * (y - ay) - (by - ay) * (x - ax) < -1e-12) return false;
      }
    return true;
  };
  for (int iy = 0; iy <= 40; ++iy)
    for (int ix = 0; ix <= 40; ++ix) {
      const double x = x0 + (x1 - x0) * ix / 40, y = y0 + (y1 - y0) * iy / 40;
      if (inside(x, y)) out.push_back({x, y});
    }
  for (std::uint32_t k = 0; k < rig.path_count(); ++k) {
    const PathView path = rig.path(k);
    const double t0 = path.start_time(), t1 = path.end_time();
    for (int j = 0; j <= 256; ++j) {
      double x, y;
      if (SamplePath(path, t0 + (t1 - t0) * j / 256, &x, &y)) out.push_back({x, y});
    }
  }
  return out;
}

struct Section {
  std::uint64_t offset = 0, size = 0;
};

Section FindSection(const std::vector<unsigned char>& bytes, std::uint32_t tag) {
  std::uint32_t count;
  std::memcpy(&count, bytes.data() + format::kOffSectionCount, 4);
  for (std::uint32_t i = 0; i < count; ++i) {
    const unsigned char* e = bytes.data() + format::kHeaderSize + i * format::kSectionEntrySize;
    std::uint32_t t;
    std::memcpy(&t, e, 4);
    if (t != tag) continue;
    Section s;
    std::memcpy(&s.offset, e + 8, 8);
    std::memcpy(&s.size, e + 16, 8);
    return s;
  }
  FAIL("no such section");
  return {};
}

void Reseal(std::vector<unsigned char>& bytes) {
  const std::uint32_t crc = format::Crc32(bytes.data() + format::kHeaderSize, bytes.size() - format::kHeaderSize);
  std::memcpy(bytes.data() + format::kOffChecksum, &crc, 4);
}

template <typename T>
void Poke(std::vector<unsigned char>& bytes, std::uint64_t at, T value) {
  std::memcpy(bytes.data() + at, &value, sizeof(T));
  Reseal(bytes);
}

std::string LoadMessage(const std::vector<unsigned char>& bytes) {
  Rig rig;
  Error err;
  if (LoadRig(bytes.data(), bytes.size(), &rig, &err)) return "loaded";
  return err.message;
}

// Loads; when it loads, every frame at a few points must be finite.
bool LoadAndCheckFinite(const std::vector<unsigned char>& bytes) {
  Rig rig;
  Error err;
  if (!LoadRig(bytes.data(), bytes.size(), &rig, &err)) {
    CHECK(std::strlen(err.message) > 0);
    return false;
  }
  for (const auto& at : {std::pair<double, double>{0, 0}, {0.5, 0.5}, {-3, 2}, {1e6, -1e6}}) {
    const Weights w = WeightsAt(rig, at.first, at.second);
    const std::vector<double> x = Morph(rig, w.raw, w.limited);
    for (double v : x) REQUIRE(std::isfinite(v));
    for (float uv : std::vector<float>(rig.uvs(0).data, rig.uvs(0).data + rig.uvs(0).size)) REQUIRE(std::isfinite(uv));
  }
  return true;
}

}  // namespace

TEST_CASE("compact sample rigs stay within 0.01 drawing pixels of the exact rigs, at their promised sizes") {
  struct Target {
    const char* name;
    double max_fraction_of_exact;  // compact bytes / exact bytes
    std::uint64_t max_bytes;
  };
  // Pip: no larger than its five drawings (55,769 bytes of PNG); the other
  // samples: at most 1/6 of the exact encoding.
  const Target targets[] = {{"pip", 1.0, 55769},           {"sprout", 1.0 / 6, ~0ull},
                            {"snake", 1.0 / 6, ~0ull},     {"gingerbread", 1.0 / 6, ~0ull},
                            {"worm-line", 1.0 / 6, ~0ull}, {"small", 1.0, ~0ull}};
  for (const Target& target : targets) {
    const std::string name = target.name;
    CAPTURE(name);
    const std::vector<unsigned char> exact_bytes = TestRigBytes(name), compact_bytes = TestRigBytes(name + ".compact");
    const Rig exact = LoadTestRig(name), compact = LoadTestRig(name + ".compact");
    CHECK(compact.format_minor() == format::kVersionMinor);
    CHECK(compact_bytes.size() <= target.max_bytes);
    CHECK(double(compact_bytes.size()) <= target.max_fraction_of_exact * double(exact_bytes.size()));
    REQUIRE(compact.vertex_count() == exact.vertex_count());
    const double ppu = PixelsPerUnit(exact);
    double worst = 0, worst_pose = 0;
    const auto samples = DenseSamples(exact);
    for (std::size_t s = 0; s < samples.size(); ++s) {
      const std::vector<double> a = MorphAt(exact, samples[s].first, samples[s].second);
      const std::vector<double> b = MorphAt(compact, samples[s].first, samples[s].second);
      double e = 0;
      for (std::size_t v = 0; v < a.size() / 2; ++v)
        e = std::max(e, std::hypot(a[2 * v] - b[2 * v], a[2 * v + 1] - b[2 * v + 1]));
      worst = std::max(worst, e * ppu);
      if (s < exact.pose_count()) worst_pose = std::max(worst_pose, e * ppu);
    }
    MESSAGE(name << ": " << compact_bytes.size() << " bytes (exact " << exact_bytes.size() << "), max vertex error "
                 << worst << " px over " << samples.size() << " frames, at the pose points " << worst_pose << " px");
    CHECK(worst <= 0.01);
    CHECK(worst_pose <= 0.01);
    // Uvs follow their vertices: within 0.01 px of the exact uvs in the drawing.
    for (std::uint32_t i = 0; i < exact.pose_count(); ++i) {
      const DrawingCanvas c = exact.pose_canvas(i);
      if (exact.uvs(i).empty() || c.width <= 0) continue;
      for (std::size_t k = 0; k < exact.uvs(i).size; ++k)
        CHECK(std::fabs(exact.uvs(i)[k] - compact.uvs(i)[k]) * (k % 2 ? c.height : c.width) <= 0.01);
    }
  }
}

TEST_CASE("a compact rig's derived arrays match the exact rig's") {
  const Rig exact = LoadTestRig("pip"), compact = LoadTestRig("pip.compact");
  // Same factor structure (the same order); angles and stretches differ by
  // what moving each vertex by half a position step (0.0025 px) turns a
  // triangle: measured as the change times the triangle's smallest altitude.
  REQUIRE(compact.factor().value.size == exact.factor().value.size);
  for (std::size_t k = 0; k < exact.factor().row.size; ++k) REQUIRE(compact.factor().row[k] == exact.factor().row[k]);
  for (std::size_t k = 0; k < exact.factor().col_start.size; ++k)
    REQUIRE(compact.factor().col_start[k] == exact.factor().col_start[k]);
  const std::uint32_t N = exact.pose_count();
  const double* r = exact.pose_positions(0).data;
  double angle_px = 0, stretch_px = 0, mass = 0;
  for (std::uint32_t t = 0; t < exact.triangle_count(); ++t) {
    const std::uint32_t* v = exact.triangles().data + 3 * t;
    double longest = 0;
    for (int k = 0; k < 3; ++k)
      longest = std::max(longest,
                         std::hypot(r[2 * v[k]] - r[2 * v[(k + 1) % 3]], r[2 * v[k] + 1] - r[2 * v[(k + 1) % 3] + 1]));
    const double area = 0.5 * std::fabs((r[2 * v[1]] - r[2 * v[0]]) * (r[2 * v[2] + 1] - r[2 * v[0] + 1]) -
                                        (r[2 * v[2]] - r[2 * v[0]]) * (r[2 * v[1] + 1] - r[2 * v[0] + 1]));
    const double altitude = 2 * area / longest;
    for (std::uint32_t i = 0; i < N; ++i) {
      angle_px = std::max(angle_px, altitude * std::fabs(exact.angles()[t * N + i] - compact.angles()[t * N + i]));
      for (int k = 0; k < 3; ++k)
        stretch_px = std::max(stretch_px, altitude * std::fabs(exact.stretches()[3 * (t * N + i) + k] -
                                                               compact.stretches()[3 * (t * N + i) + k]));
    }
  }
  for (std::size_t k = 0; k < exact.vertex_masses().size; ++k)
    mass += std::fabs(exact.vertex_masses()[k] - compact.vertex_masses()[k]);
  MESSAGE("pip: angle change x altitude " << angle_px << " px, stretch change x altitude " << stretch_px
                                          << " px, masses moved " << mass << " of 1");
  CHECK(angle_px < 0.05);
  CHECK(stretch_px < 0.05);
  CHECK(mass < 1e-3);
}

TEST_CASE("a vertex's earlier neighbours are the corners before it, in triangle order, at most 16") {
  // A fan: ring vertices 0..19 around the centre, vertex 20.
  std::vector<std::uint32_t> tris;
  for (std::uint32_t i = 0; i < 20; ++i) tris.insert(tris.end(), {i, (i + 1) % 20, 20});
  const std::uint64_t V = 21, T = 20;
  std::vector<std::uint32_t> start(V + 1), fill(V), list(3 * T);
  format::EarlierNeighbours(tris.data(), T, V, start.data(), fill.data(), list.data());
  auto of = [&](std::uint32_t v) {
    return std::vector<std::uint32_t>(list.begin() + start[v], list.begin() + start[v + 1]);
  };
  CHECK(of(0).empty());
  CHECK(of(1) == std::vector<std::uint32_t>{0});
  CHECK(of(19) == std::vector<std::uint32_t>{18, 0});
  // The centre: each ring edge's two ends, the first 16 of 40.
  CHECK(of(20) == std::vector<std::uint32_t>{0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6, 7, 7, 8});
  // Predictions: the mean rounded down; the previous vertex's without
  // neighbours; 0 for vertex 0.
  std::vector<std::int64_t> q(V);
  for (std::uint32_t v = 0; v < V; ++v) q[v] = 10 * v + 3;
  CHECK(format::NeighbourPrediction(q.data(), 1, 0, start.data(), list.data()) == 0);
  CHECK(format::NeighbourPrediction(q.data(), 1, 19, start.data(), list.data()) == (183 + 3) / 2);
  CHECK(format::NeighbourPrediction(q.data(), 1, 20, start.data(), list.data()) == (10 * 64 + 3 * 16) / 16);
  tris = {0, 1, 2};  // vertex 3 in no triangle: the previous vertex's
  format::EarlierNeighbours(tris.data(), 1, 4, start.data(), fill.data(), list.data());
  CHECK(format::NeighbourPrediction(q.data(), 1, 3, start.data(), list.data()) == 23);
  CHECK(format::NeighbourPrediction(q.data(), 1, 2, start.data(), list.data()) == (3 + 13) / 2);
}

TEST_CASE("hostile compact sections are refused with the section named") {
  const std::vector<unsigned char> good = TestRigBytes("pip.compact");
  REQUIRE(LoadMessage(good) == "loaded");
  const Section qpos = FindSection(good, format::kQuantPositions), qtri = FindSection(good, format::kQuantTriangles),
                qprm = FindSection(good, format::kQuantPermutation), qgrd = FindSection(good, format::kQuantGrid),
                quva = FindSection(good, format::kAffineUVs), qtrn = FindSection(good, format::kQuantTurns),
                meta = FindSection(good, format::kMeta);
  auto expect = [&](auto mutate, const std::string& fragment) {
    std::vector<unsigned char> bad = good;
    mutate(bad);
    const std::string message = LoadMessage(bad);
    CAPTURE(fragment);
    CHECK_MESSAGE(message.find(fragment) != std::string::npos, message);
  };
  for (double step : {0.0, -1.0, std::nan(""), HUGE_VAL})
    expect([&](auto& b) { Poke(b, qpos.offset, step); }, "section QPOS: step");
  expect([&](auto& b) { Poke(b, qpos.offset + 8, std::uint32_t(33)); }, "section QPOS: code order 33 above 20");
  // 1.13: the poses after the first coded against pose 0; 1.14: each vertex
  // predicted by its earlier neighbours (Pip's are both).
  std::uint32_t prediction = 0;
  std::memcpy(&prediction, good.data() + qpos.offset + 12, 4);
  REQUIRE(prediction == (format::kPositionsAgainstPose0 | format::kPositionsFromNeighbours));
  expect([&](auto& b) { Poke(b, qpos.offset + 12, std::uint32_t(4)); },
         "section QPOS: prediction field 4 has a bit outside 3");
  auto with_minor = [](std::vector<unsigned char>& b, std::uint16_t minor) {
    std::memcpy(b.data() + format::kOffVersionMinor, &minor, 2);  // the header is outside the checksum
  };
  expect([&](auto& b) { with_minor(b, 13); },
         "section QPOS: prediction field 3 has a bit outside 1 (format 1.13: 1 from 1.13, 2 from 1.14)");
  expect([&](auto& b) { with_minor(b, 12); }, "section QPOS: prediction field 3 has a bit outside 0 (format 1.12");
  {
    // Pose 1's own order, the 5 bits after pose 0's codes, set to 31: where
    // they start is summed from pose 0's integers as the loader decoded
    // them, each the residual of its earlier neighbours' mean.
    const Rig rig = LoadTestRig("pip.compact");
    double step = 0, origin[2] = {0, 0};
    std::uint32_t k = 0;
    std::memcpy(&step, good.data() + qpos.offset, 8);
    std::memcpy(&k, good.data() + qpos.offset + 8, 4);
    std::memcpy(origin, good.data() + qpos.offset + 16, 16);
    const Span<const double> p = rig.pose_positions(0);
    const std::uint64_t V = rig.vertex_count(), T = rig.triangle_count();
    std::vector<std::int64_t> q(p.size);
    for (std::size_t c = 0; c < p.size; ++c) q[c] = std::llround((p[c] - origin[c % 2]) / step);
    std::vector<std::uint32_t> start(V + 1), fill(V), list(3 * T);
    format::EarlierNeighbours(rig.triangles().data, T, V, start.data(), fill.data(), list.data());
    std::uint64_t bits = 0;
    for (std::size_t c = 0; c < p.size; ++c) {
      const std::int64_t e = format::NeighbourPrediction(q.data() + c % 2, 2, c / 2, start.data(), list.data());
      const std::uint64_t w = format::ZigZag(q[c] - e) + (std::uint64_t(1) << k);
      unsigned width = 0;
      while ((w >> (width + 1)) != 0) ++width;
      bits += 2 * width - k + 1;
    }
    const std::uint64_t stream = qpos.offset + 16 + 16 * std::uint64_t(rig.pose_count());
    expect(
        [&](auto& b) {
          for (std::uint64_t i = bits; i < bits + 5; ++i)
            b[stream + i / 8] |= static_cast<unsigned char>(1u << (i % 8));
          Reseal(b);
        },
        "section QPOS: code order 31 of pose 1 above 20");
  }
  expect([&](auto& b) { Poke(b, qpos.offset + 16 + 16 * 5, std::uint64_t(0)); },
         "section QPOS: vertex 0 of pose 0: code runs past");
  expect([&](auto& b) { Poke(b, qpos.offset + 16, std::nan("")); }, "section QPOS: origin of pose 0");
  expect([&](auto& b) { Poke(b, qtri.offset + 8, std::uint64_t(0)); },
         "section QTRI: triangle 0 has a vertex index outside 0.." +
             std::to_string(LoadTestRig("pip.compact").vertex_count() - 1));
  expect([&](auto& b) { Poke(b, qtri.offset, std::uint32_t(21)); }, "section QTRI: code order 21 above 20");
  expect(
      [&](auto& b) {
        std::uint32_t w;
        std::memcpy(&w, b.data() + qprm.offset + 8, 4);
        const std::uint32_t first = w & 0x1FF;
        Poke(b, qprm.offset + 8, std::uint32_t((w & ~(0x1FFu << 9)) | (first << 9)));  // entry 1 = entry 0
      },
      "section QPRM: not a permutation");
  expect([&](auto& b) { Poke(b, qtrn.offset + 4, std::uint32_t(40)); }, "section QTRN: bit width 40");
  expect([&](auto& b) { Poke(b, qtrn.offset, std::int32_t(2000)); }, "angles[0] is");
  for (double step : {0.0, std::nan(""), -HUGE_VAL})
    expect([&](auto& b) { Poke(b, qgrd.offset, step); }, "section QGRD: step");
  expect([&](auto& b) { Poke(b, qgrd.offset + 8, std::uint32_t(2)); }, "section QGRD: 2 coded poses for 5 poses");
  expect([&](auto& b) { Poke(b, qgrd.offset + 16, std::uint32_t(21)); }, "section QGRD: code parameters of pose 0");
  expect([&](auto& b) { Poke(b, qgrd.offset + 32, std::uint64_t(0)); }, "section QGRD: pose 0, corner");
  expect(
      [&](auto& b) {
        for (std::uint64_t k = qgrd.offset + 32; k < qgrd.offset + qgrd.size; ++k)
          b[k] = 0xFF;  // every code a single bit
        Reseal(b);
      },
      "section QGRD has");
  expect([&](auto& b) { Poke(b, quva.offset, std::uint32_t(5)); }, "section QUVA: pose 0 names source pose 5 of 5");
  expect([&](auto& b) { Poke(b, quva.offset + 8, HUGE_VAL); }, "section QUVA: coefficient 0 of pose 0");
  expect(
      [&](auto& b) {
        Poke(b, quva.offset + 8, 1e15);
        Poke(b, quva.offset + 16, 1e15);
        Poke(b, qpos.offset + 16, 9e14);  // pose 0's origin
        Poke(b, qpos.offset + 24, 9e14);
      },
      "section QUVA: uv of vertex");
  expect(
      [&](auto& b) {
        std::uint32_t nnz;
        std::memcpy(&nnz, b.data() + meta.offset + 24, 4);
        Poke(b, meta.offset + 24, nnz + 1);
      },
      "META declares");
  expect([&](auto& b) { Poke(b, meta.offset + 24, std::uint32_t(1u << 27)); }, "factor nonzeros for a compact file");
  // A pose count the other sections do not have.
  expect([&](auto& b) { Poke(b, meta.offset + 8, std::uint32_t(64)); }, "section PPNT is");
  // Every vertex at its pose's origin (a step too small to move it): no area.
  expect([&](auto& b) { Poke(b, qpos.offset, 1e-300); },
         "section QPOS: triangle 0 is not counter-clockwise with positive area in pose 0");
}

TEST_CASE("mutated compact rigs with a valid checksum load safely or are refused") {
  for (const char* name : {"small.compact", "sprout.compact"}) {
    const std::vector<unsigned char> good = TestRigBytes(name);
    std::mt19937_64 random(20261122);
    const int trials = std::string(name) == "small.compact" ? 6000 : 600;
    int loaded = 0;
    for (int t = 0; t < trials; ++t) {
      std::vector<unsigned char> bad = good;
      const int changes = 1 + int(random() % 4);
      for (int c = 0; c < changes; ++c) {
        const std::size_t at = format::kHeaderSize + random() % (bad.size() - format::kHeaderSize);
        bad[at] = static_cast<unsigned char>(t % 3 == 0 ? random() : bad[at] ^ (1u << (random() % 8)));
      }
      Reseal(bad);
      loaded += LoadAndCheckFinite(bad);
    }
    MESSAGE(std::string(name) << ": " << trials << " mutated rigs with a valid checksum, " << loaded
                              << " loaded and gave finite frames");
  }
}
