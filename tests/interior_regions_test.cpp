// SPDX-License-Identifier: MIT
// Interior regions (interior_regions.h): what counts as a drawn patch (an
// eye with its pupil is one region, a band of a smooth gradient or a patch
// on the outline is none), and the matching that the local descent cannot
// do: a face slid by half its eye spacing pairs each eye with itself, not
// with its neighbour.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "posemorph/bake/mapping/interior_regions.h"

namespace pm = posemorph::bake::mapping;
using Vec2 = Eigen::Vector2d;

namespace {

constexpr int kCanvasSize = 160;

// An opaque body disc of radius 70 at (80, 80), tan, premultiplied.
pm::AlignmentImage Body() {
  pm::AlignmentImage image;
  image.width = image.height = kCanvasSize;
  image.rgba.assign(std::size_t(kCanvasSize) * kCanvasSize * 4, 0.0f);
  for (int y = 0; y < kCanvasSize; ++y)
    for (int x = 0; x < kCanvasSize; ++x) {
      if (std::hypot(x + 0.5 - 80, y + 0.5 - 80) > 70) continue;
      float* p = &image.rgba[(std::size_t(y) * kCanvasSize + std::size_t(x)) * 4];
      p[0] = 0.9f, p[1] = 0.6f, p[2] = 0.3f, p[3] = 1.0f;
    }
  return image;
}

void Disc(pm::AlignmentImage& image, const Vec2& centre, double radius, float r, float g, float b) {
  for (int y = 0; y < kCanvasSize; ++y)
    for (int x = 0; x < kCanvasSize; ++x) {
      if ((Vec2(x + 0.5, y + 0.5) - centre).norm() > radius) continue;
      float* p = &image.rgba[(std::size_t(y) * kCanvasSize + std::size_t(x)) * 4];
      p[0] = r, p[1] = g, p[2] = b, p[3] = 1.0f;
    }
}

// Two eyes (white, a dark pupil off centre) at `left` and `left + (40, 0)`,
// and a dark mouth below them.
pm::AlignmentImage Face(const Vec2& left, double gaze) {
  pm::AlignmentImage image = Body();
  for (const Vec2& eye : {left, Vec2(left + Vec2(40, 0))}) {
    Disc(image, eye, 9, 1, 1, 1);
    Disc(image, eye + Vec2(gaze, 0), 4, 0.1f, 0.1f, 0.1f);
  }
  Disc(image, left + Vec2(20, 30), 6, 0.5f, 0.1f, 0.1f);
  return image;
}

}  // namespace

TEST_CASE("interior regions: an eye with its pupil is one region centred on the eye, the body and edges are none") {
  const pm::AlignmentImage image = Face(Vec2(60, 70), 3);
  const std::vector<pm::InteriorRegion> regions = pm::FindInteriorRegions(image);
  // The two eyes (the pupils lie in their holes) and the mouth; the body is
  // too large a share of the shape.
  REQUIRE(regions.size() == 3);
  int eyes = 0;
  for (const pm::InteriorRegion& r : regions) {
    CAPTURE(r.centre);
    const bool white = r.colour[0] > 0.95;
    if (white) {
      ++eyes;
      // The eye's centre, not shifted by the pupil looking aside.
      const Vec2 expected = r.centre.x() < 80 ? Vec2(60, 70) : Vec2(100, 70);
      CHECK((r.centre - expected).norm() < 0.25);
      CHECK(r.area == doctest::Approx(M_PI * 81).epsilon(0.08));
    } else {
      CHECK((r.centre - Vec2(80, 100)).norm() < 0.25);
    }
  }
  CHECK(eyes == 2);
  CHECK(pm::OpaqueArea(image) == doctest::Approx(M_PI * 70 * 70).epsilon(0.01));

  // A patch on the outline is not inside the shape; a smooth gradient's bands
  // have no sharp edge.
  pm::AlignmentImage edge = Body();
  Disc(edge, Vec2(80, 12), 8, 0.2f, 0.2f, 0.6f);
  for (int y = 0; y < kCanvasSize; ++y)
    for (int x = 0; x < kCanvasSize; ++x) {
      float* p = &edge.rgba[(std::size_t(y) * kCanvasSize + std::size_t(x)) * 4];
      if (p[3] > 0 && y > 40) p[1] = float(0.2 + 0.6 * (y - 40) / 110.0);
    }
  CHECK(pm::FindInteriorRegions(edge).empty());
}

TEST_CASE("interior regions: a face slid by half its eye spacing pairs each eye with itself") {
  const pm::AlignmentImage rest = Face(Vec2(60, 70), 0), moved = Face(Vec2(40, 70), 2);
  const std::vector<pm::InteriorRegion> a = pm::FindInteriorRegions(rest), b = pm::FindInteriorRegions(moved);
  REQUIRE(a.size() == 3);
  REQUIRE(b.size() == 3);
  // The outlines did not move, so the mapping predicts every region where it
  // was: the left eye of `rest` is 20 px from both eyes of `moved`.
  std::vector<Vec2> predicted;
  for (const pm::InteriorRegion& r : a) predicted.push_back(r.centre);
  const std::vector<pm::RegionMatch> m = pm::MatchInteriorRegions(a, predicted, b, pm::OpaqueArea(rest));
  REQUIRE(m.size() == 3);
  for (const pm::RegionMatch& p : m) {
    CAPTURE(p.from);
    CHECK((p.to - p.from - Vec2(-20, 0)).norm() < 0.5);
    CHECK(p.from == a[p.reference].centre);
  }
  // Unlike colours do not pair: a green mouth is left alone, the eyes pair.
  pm::AlignmentImage recoloured = Face(Vec2(40, 70), 2);
  Disc(recoloured, Vec2(60, 100), 6, 0.1f, 0.5f, 0.1f);
  const std::vector<pm::RegionMatch> n =
      pm::MatchInteriorRegions(a, predicted, pm::FindInteriorRegions(recoloured), pm::OpaqueArea(rest));
  REQUIRE(n.size() == 2);
  for (const pm::RegionMatch& p : n) CHECK(a[p.reference].colour[0] > 0.95);
  // One eye alone (the other outside the first pose's mesh, NaN) proves no
  // shift: either eye of the moved face could be it, so it is not paired.
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].colour[0] > 0.95 && a[i].centre.x() < 80) predicted[i] = Vec2::Constant(std::nan(""));
  CHECK(pm::MatchInteriorRegions(a, predicted, pm::FindInteriorRegions(recoloured), pm::OpaqueArea(rest)).empty());
}
