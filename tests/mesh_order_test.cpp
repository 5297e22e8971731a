// SPDX-License-Identifier: MIT
// The drawn mesh's numbering for the compact encoding (mesh_order.h): a
// depth-first walk over the triangles, each triangle after the first of a
// piece joined by an edge to one before it, the vertices numbered as the
// walk first meets them, the same triangles, turned the same way; and the
// triangles' vertex indices, coded as QTRI codes them, in about half the
// bits of a numbering in no order (at most 55%).
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <vector>

#include "posemorph/bake/bake.h"
#include "posemorph/bake/mesh_order.h"
#include "posemorph/rig_format.h"

namespace {

using posemorph::bake::Triangles;
using Tri = std::array<std::uint32_t, 3>;

// A triangle turned so that its smallest index comes first (its orientation kept).
Tri Turned(const Tri& t) {
  const std::size_t r = std::size_t(std::min_element(t.begin(), t.end()) - t.begin());
  return {t[r], t[(r + 1) % 3], t[(r + 2) % 3]};
}

// The bits of QTRI's codes for `triangles`: each index less the same corner
// of the triangle before, zigzagged, Exp-Golomb coded at the best order.
std::uint64_t TriangleCodeBits(const Triangles& triangles) {
  std::vector<std::uint64_t> codes;
  Tri previous{0, 0, 0};
  for (const Tri& t : triangles) {
    for (std::size_t c = 0; c < 3; ++c) {
      const std::int64_t r = std::int64_t(t[c]) - std::int64_t(previous[c]);
      codes.push_back(r >= 0 ? std::uint64_t(r) * 2 : std::uint64_t(-r) * 2 - 1);
    }
    previous = t;
  }
  std::uint64_t best = ~std::uint64_t(0);
  for (unsigned k = 0; k < 24; ++k) {
    std::uint64_t bits = 0;
    for (std::uint64_t u : codes) bits += 2 * std::uint64_t(std::floor(std::log2(double((u >> k) + 1)))) + 1 + k;
    best = std::min(best, bits);
  }
  return best;
}

// Whether every triangle after the first shares an edge with one before it.
bool EachJoinsAnEarlierOne(const Triangles& triangles) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    bool joined = t == 0;
    for (std::size_t e = 0; e < 3; ++e) {
      const std::uint32_t a = triangles[t][e], b = triangles[t][(e + 1) % 3];
      joined = joined || edges.count({std::min(a, b), std::max(a, b)}) > 0;
    }
    if (!joined) return false;
    for (std::size_t e = 0; e < 3; ++e) {
      const std::uint32_t a = triangles[t][e], b = triangles[t][(e + 1) % 3];
      edges.insert({std::min(a, b), std::max(a, b)});
    }
  }
  return true;
}

// Whether the vertices are numbered as the triangles first meet them.
bool NumberedAsFirstMet(const Triangles& triangles) {
  std::uint32_t next = 0;
  for (const Tri& t : triangles)
    for (std::uint32_t v : t) {
      if (v > next) return false;
      if (v == next) ++next;
    }
  return true;
}

// y up: a body with a head, its arm hanging beside it, then held out.
std::vector<Eigen::Vector2d> ArmHangingOutline() {
  return {{0, 0},   {40, 0},  {40, 50}, {42, 50}, {42, 26}, {50, 26}, {50, 58},
          {40, 58}, {40, 60}, {32, 60}, {32, 84}, {8, 84},  {8, 60},  {0, 60}};
}
std::vector<Eigen::Vector2d> ArmHeldOutOutline() {
  return {{0, 0},   {40, 0},  {40, 50}, {74, 50}, {74, 58}, {40, 58},
          {40, 60}, {32, 60}, {32, 84}, {8, 84},  {8, 60},  {0, 60}};
}

}  // namespace

TEST_CASE("a mesh numbered in no order is walked: the same triangles, joined edge to edge, in about half the bits") {
  // A 20 x 20 grid of squares, two triangles each, counter-clockwise; then
  // its vertices numbered at random, its triangles shuffled and turned.
  constexpr std::uint32_t n = 20, row = n + 1;
  Triangles grid;
  for (std::uint32_t y = 0; y < n; ++y)
    for (std::uint32_t x = 0; x < n; ++x) {
      const std::uint32_t a = y * row + x, b = a + 1, c = a + row, d = c + 1;
      grid.push_back({a, b, d});
      grid.push_back({a, d, c});
    }
  const std::uint32_t V = row * row + 1;  // and one vertex that no triangle uses: numbered last
  std::mt19937 random(7);
  std::vector<std::uint32_t> name(V);
  for (std::uint32_t v = 0; v < V; ++v) name[v] = v;
  std::shuffle(name.begin(), name.end(), random);
  Triangles shuffled;
  for (const Tri& t : grid) {
    const std::size_t r = random() % 3;
    shuffled.push_back({name[t[r]], name[t[(r + 1) % 3]], name[t[(r + 2) % 3]]});
  }
  std::shuffle(shuffled.begin(), shuffled.end(), random);

  std::vector<std::uint32_t> vertex_order;
  Triangles walked;
  posemorph::bake::WalkOrder(shuffled, V, &vertex_order, &walked);
  // A numbering of every vertex once, the unused one last.
  REQUIRE(vertex_order.size() == V);
  std::vector<std::uint32_t> sorted = vertex_order;
  std::sort(sorted.begin(), sorted.end());
  for (std::uint32_t v = 0; v < V; ++v) REQUIRE(sorted[v] == v);
  CHECK(vertex_order.back() == name[V - 1]);
  // The same triangles, each once, turned the same way.
  REQUIRE(walked.size() == shuffled.size());
  std::multiset<Tri> before, after;
  for (const Tri& t : shuffled) before.insert(Turned(t));
  for (const Tri& t : walked) after.insert(Turned({vertex_order[t[0]], vertex_order[t[1]], vertex_order[t[2]]}));
  CHECK(before == after);
  CHECK(EachJoinsAnEarlierOne(walked));
  CHECK(NumberedAsFirstMet(walked));
  const double bits_before = double(TriangleCodeBits(shuffled)) / double(shuffled.size());
  const double bits_after = double(TriangleCodeBits(walked)) / double(walked.size());
  MESSAGE("QTRI's codes: " << bits_before << " bits a triangle in no order, " << bits_after << " walked");
  CHECK(bits_after < 0.55 * bits_before);  // 30.1 -> 14.3 on this grid
}

TEST_CASE("a drawn rig's triangles are walked, and QTRI codes them in under 20 bits a triangle") {
  // A figure holding its arm out, drawn as outlines: the mapping's
  // refinement makes a few hundred triangles, numbered as made.
  posemorph::bake::RigDescription rig;
  rig.file = "walked.json";
  const std::vector<std::vector<Eigen::Vector2d>> outlines = {ArmHangingOutline(), ArmHeldOutOutline()};
  for (std::size_t i = 0; i < outlines.size(); ++i) {
    posemorph::bake::PoseDescription pose;
    pose.name = "pose" + std::to_string(i);
    pose.point = Eigen::Vector2d(double(i), 0);
    pose.drawn = true;
    pose.outline = outlines[i];
    pose.landmarks = {Eigen::Vector2d(20, 0)};
    rig.poses.push_back(pose);
  }
  posemorph::bake::BakeReport report;
  const posemorph::bake::BakedRig baked = posemorph::bake::BakeOne(rig, &report);
  REQUIRE(report.compact);
  Triangles triangles;
  const posemorph::Span<const std::uint32_t> t = baked.rig.triangles();
  for (std::size_t k = 0; k + 2 < t.size; k += 3) triangles.push_back({t[k], t[k + 1], t[k + 2]});
  REQUIRE(triangles.size() > 100);
  CHECK(EachJoinsAnEarlierOne(triangles));
  CHECK(NumberedAsFirstMet(triangles));
  const std::vector<unsigned char>* qtri = baked.sections.Find(posemorph::format::kQuantTriangles);
  REQUIRE(qtri != nullptr);
  const double bits = 8.0 * double(qtri->size()) / double(triangles.size());
  MESSAGE(triangles.size() << " triangles, QTRI " << qtri->size() << " bytes: " << bits << " bits a triangle");
  CHECK(bits < 20);
}
