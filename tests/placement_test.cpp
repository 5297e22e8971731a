// SPDX-License-Identifier: MIT
// Where a character stands and which way it faces (format 1.11, PLCE;
// issue 40): the description's "anchor" and "facing" bake into the rig (the
// anchor given in the first drawing's pixels or in rig units), the default
// without them, Transform2D::Place putting the anchor at a world point and
// mirroring about it, the pad's range, the loader's refusals of a bad
// PLCE, and the description's errors.
#include <cmath>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bad_input_support.h"
#include "posemorph/bake/bake.h"
#include "posemorph/bake/rig_description.h"
#include "posemorph/draw_list.h"
#include "posemorph/posemorph.h"
#include "posemorph/rig.h"
#include "posemorph/rig_format.h"

using namespace posemorph;
using namespace posemorph::test;

namespace {

Rig PlacedRig(const json& j, std::vector<unsigned char>* bytes = nullptr, const LoadOptions& options = LoadOptions()) {
  bake::RigDescription d = bake::ParseRigDescription(j.dump(), "rig.json", ".");
  std::vector<unsigned char> b = bake::BakeRig(d);
  Rig rig;
  Error err;
  REQUIRE_MESSAGE(LoadRig(b.data(), b.size(), &rig, &err, options), err.message);
  if (bytes) *bytes = std::move(b);
  return rig;
}

// Where a transform sends a point.
void PlaceApply(const Transform2D& t, double x, double y, double* ox, double* oy) { t.Apply(x, y, ox, oy); }

}  // namespace

TEST_CASE("placement: without anchor or facing, the bottom centre of pose 0, facing right, and no PLCE") {
  std::vector<unsigned char> bytes;
  const Rig rig = PlacedRig(ValidDescription(), &bytes);
  CHECK(rig.format_minor() == 14);
  CHECK_FALSE(rig.anchor_given());
  CHECK_FALSE(rig.facing_left());
  // The bottom centre of pose 0 as loaded (the unit square, within the compact encoding's step).
  const Span<const double> p = rig.pose_positions(0);
  double x0 = p[0], x1 = p[0], y0 = p[1];
  for (std::size_t i = 0; i < p.size; i += 2)
    x0 = std::fmin(x0, p[i]), x1 = std::fmax(x1, p[i]), y0 = std::fmin(y0, p[i + 1]);
  CHECK(rig.anchor_x() == (x0 + x1) / 2);
  CHECK(rig.anchor_y() == y0);
  CHECK(rig.anchor_x() == doctest::Approx(0.5).epsilon(1e-4));
  RigSection sections[32];
  std::uint32_t n = 0;
  Error err;
  REQUIRE(ReadRigSections(bytes.data(), bytes.size(), sections, 32, &n, &err));
  for (std::uint32_t s = 0; s < n && s < 32; ++s) CHECK(sections[s].tag != format::kPlacement);
}

TEST_CASE("placement: the description's anchor and facing bake into PLCE and read back") {
  json j = ValidDescription();
  j["anchor"] = {0.25, -0.5};
  j["facing"] = "left";
  std::vector<unsigned char> bytes;
  const Rig rig = PlacedRig(j, &bytes);
  CHECK(rig.anchor_given());
  CHECK(rig.facing_left());
  CHECK(rig.anchor_x() == 0.25);  // poses given as vertices: rig units
  CHECK(rig.anchor_y() == -0.5);
  // The same rig without them: 24 bytes of record and a 16-byte section entry fewer.
  CHECK(bake::BakeRig(bake::ParseRigDescription(ValidDescription().dump(), "rig.json", ".")).size() + 24 + 8 + 16 ==
        bytes.size());
  // facing alone: the default anchor, stored.
  json f = ValidDescription();
  f["facing"] = "left";
  const Rig left = PlacedRig(f);
  CHECK(left.facing_left());
  CHECK(left.anchor_x() == doctest::Approx(0.5).epsilon(1e-4));  // from the bake's exact pose 0
  CHECK(left.anchor_y() == doctest::Approx(0).epsilon(1e-4));
}

TEST_CASE("placement: a drawn rig's anchor is given in its first drawing's pixels") {
  const std::string folder = std::string(POSEMORPH_DRAWN_SAMPLES) + "/sprites/slime";
  json j = json::parse(std::ifstream(folder + "/slime.json"));
  for (json& pose : j["poses"]) pose["origin"] = {16, 29};  // the rig origin at pixel (16, 29)
  j["anchor"] = {20, 25};
  bake::RigDescription d = bake::ParseRigDescription(j.dump(), folder + "/slime.json", folder);
  const std::vector<unsigned char> bytes = bake::BakeRig(d);
  Rig rig;
  Error err;
  REQUIRE_MESSAGE(LoadRig(bytes.data(), bytes.size(), &rig, &err), err.message);
  CHECK(rig.pose_canvas(0).pivot_x == 16);
  CHECK(rig.anchor_x() == 4);  // x right
  CHECK(rig.anchor_y() == 4);  // y down in the drawing, up in the rig
}

TEST_CASE("Transform2D::Place puts the anchor at the point and mirrors about it") {
  json j = ValidDescription();
  j["anchor"] = {0.5, 0};
  const Rig right = PlacedRig(j);
  j["facing"] = "left";
  const Rig left = PlacedRig(j);
  double x, y;
  // The anchor lands on the point, whatever the rotation, scale and facing.
  for (bool face_left : {false, true}) {
    PlaceApply(Transform2D::Place(right, 10, 20, 0.3, 2, face_left), 0.5, 0, &x, &y);
    CHECK(x == doctest::Approx(10).epsilon(1e-6));
    CHECK(y == doctest::Approx(20).epsilon(1e-6));
  }
  // Facing the way the drawings face: no mirror; the other way: mirrored about the anchor.
  PlaceApply(Transform2D::Place(right, 10, 20, 0, 2, false), 1, 0, &x, &y);
  CHECK(x == doctest::Approx(11));
  CHECK_FALSE(Transform2D::Place(right, 10, 20, 0, 2, false).mirrors());
  PlaceApply(Transform2D::Place(right, 10, 20, 0, 2, true), 1, 0, &x, &y);
  CHECK(x == doctest::Approx(9));
  CHECK(Transform2D::Place(right, 10, 20, 0, 2, true).mirrors());
  CHECK_FALSE(Transform2D::Place(left, 10, 20, 0, 2, true).mirrors());  // drawn facing left, asked left
  CHECK(Transform2D::Place(left, 10, 20, 0, 2, false).mirrors());
  // Non-finite input: the identity.
  const Transform2D bad = Transform2D::Place(right, NAN, 0);
  CHECK(bad.a == 1);
  CHECK(bad.tx == 0);
  // The C API gives the same bits.
  pm_rig* crig = nullptr;
  pm_error cerr;
  std::vector<unsigned char> bytes;
  PlacedRig(j, &bytes);
  REQUIRE(pm_rig_load(bytes.data(), bytes.size(), &crig, &cerr) == PM_OK);
  pm_transform t;
  pm_transform_place(crig, 3, 4, 0.5, 1.5, 0, &t);
  const Transform2D expected = Transform2D::Place(left, 3, 4, 0.5, 1.5, false);
  CHECK(std::memcmp(&t, &expected, sizeof t) == 0);
  double ax = 0, ay = 0;
  int facing = 0;
  REQUIRE(pm_rig_placement(crig, &ax, &ay, &facing) == PM_OK);
  CHECK(ax == 0.5);
  CHECK(facing == 1);
  pm_bounds pad;
  REQUIRE(pm_channel_pad_range(crig, 0, &pad) == PM_OK);
  CHECK(pad.min_x == left.pad_range().min_x);
  CHECK(pm_channel_pad_range(crig, 1, &pad) == PM_ERROR_INVALID_ARGUMENT);
  pm_rig_free(crig);
}

TEST_CASE("the pad's range holds every pose point, with a margin, within the weight grid") {
  const Rig rig = PlacedRig(ValidDescription());
  const PadRange r = rig.pad_range();
  const PoseSpaceGrid& g = rig.grid();
  for (std::uint32_t i = 0; i < rig.pose_count(); ++i) {
    const double px = rig.pose_points()[2 * i], py = rig.pose_points()[2 * i + 1];
    CHECK(r.min_x <= px);
    CHECK(px <= r.max_x);
    CHECK(r.min_y <= py);
    CHECK(py <= r.max_y);
  }
  CHECK(r.min_x < 0);  // a margin beyond the points (0, 0) and (1, 0)
  CHECK(r.max_x > 1);
  CHECK(r.min_x >= g.origin_x);
  CHECK(r.max_x <= g.origin_x + g.cell * g.cells_x);
}

TEST_CASE("the loader refuses a bad PLCE: a non-finite or far anchor, unknown flags, in an attachment") {
  json j = ValidDescription();
  j["anchor"] = {0.25, -0.5};
  std::vector<unsigned char> bytes;
  PlacedRig(j, &bytes);
  RigSection sections[32];
  std::uint32_t n = 0;
  Error err;
  REQUIRE(ReadRigSections(bytes.data(), bytes.size(), sections, 32, &n, &err));
  std::uint64_t at = 0;
  for (std::uint32_t s = 0; s < n; ++s)
    if (sections[s].tag == format::kPlacement) at = sections[s].offset;
  REQUIRE(at > 0);
  LoadOptions unchecked;
  unchecked.verify_checksum = false;  // the structural checks alone
  auto refused = [&](std::size_t offset, const void* value, std::size_t size, const char* expected) {
    std::vector<unsigned char> b = bytes;
    std::memcpy(b.data() + at + offset, value, size);
    Rig rig;
    Error e;
    CHECK_FALSE(LoadRig(b.data(), b.size(), &rig, &e, unchecked));
    CHECK(std::string(e.message).find(expected) != std::string::npos);
  };
  const double nan = NAN, far = 2e9;
  const std::uint32_t flags = 6, reserved = 1;
  refused(0, &nan, 8, "PLCE: the anchor");
  refused(8, &far, 8, "PLCE: the anchor");
  refused(16, &flags, 4, "PLCE: unknown flags");
  refused(20, &reserved, 4, "reserved");
}

TEST_CASE("a description's bad anchor or facing fails the bake with one line naming the key") {
  json j = ValidDescription();
  j["anchor"] = {1, "up"};
  ExpectFailure(j.dump(), "anchor[1]");
  j = ValidDescription();
  j["anchor"] = {1e10, 0};
  ExpectFailure(j.dump(), "anchor: expected a point within +-1e9");
  j = ValidDescription();
  j["facing"] = "up";
  ExpectFailure(j.dump(), "facing: expected \"left\" or \"right\"");
}
