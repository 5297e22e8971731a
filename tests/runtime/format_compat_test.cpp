// SPDX-License-Identifier: MIT
// Rigs baked before format 1.2 keep loading and keep their frames: their
// weight grid has no cell centres and its cells are split on one diagonal,
// as they were baked. tests/runtime/rigs/small-format-1.1.pmrig was written
// by the bake before 1.2 (from small.json).
#include <cmath>
#include <string>
#include <utility>

#include "posemorph/jobs.h"
#include "posemorph/rig_format.h"
#include "runtime_support.h"

using namespace posemorph;
using namespace posemorph::test;

namespace {

Rig LoadCommitted(const std::string& name) {
  const std::vector<unsigned char> bytes =
      ReadFileBytes(std::string(POSEMORPH_SOURCE_DIR) + "/tests/runtime/rigs/" + name);
  Rig rig;
  Error err;
  REQUIRE_MESSAGE(LoadRig(bytes.data(), bytes.size(), &rig, &err), name << ": " << err.message);
  return rig;
}

// A committed older file and the build's rig of the same description: the
// bytes of each and each loaded.
struct OldAndNow {
  std::vector<unsigned char> old_bytes, now_bytes;
  Rig old, now;
};
OldAndNow LoadOldAndNow(const std::string& committed, const std::string& build_rig) {
  OldAndNow r;
  r.old_bytes = ReadFileBytes(std::string(POSEMORPH_SOURCE_DIR) + "/tests/runtime/rigs/" + committed);
  r.now_bytes = TestRigBytes(build_rig);
  r.old = LoadCommitted(committed);
  r.now = LoadTestRig(build_rig);
  return r;
}

// An older compact file and today's of the same description decode to the
// same triangles and positions and give the same frames, bit for bit.
void CheckDecodesAlike(const Rig& old, const Rig& now) {
  REQUIRE(old.pose_count() == now.pose_count());
  REQUIRE(old.triangles().size == now.triangles().size);
  for (std::size_t k = 0; k < now.triangles().size; ++k) CHECK(old.triangles()[k] == now.triangles()[k]);
  for (std::uint32_t i = 0; i < now.pose_count(); ++i) {
    REQUIRE(old.pose_positions(i).size == now.pose_positions(i).size);
    for (std::size_t k = 0; k < now.pose_positions(i).size; ++k)
      CHECK(old.pose_positions(i)[k] == now.pose_positions(i)[k]);
  }
  for (double x : {-0.5, 0.0, 0.3, 1.0, 1.7}) {
    CAPTURE(x);
    CHECK(MorphAt(old, x, 0.2) == MorphAt(now, x, 0.2));
  }
}

}  // namespace

TEST_CASE("a format 1.1 rig loads and interpolates its grid as it was baked") {
  const std::vector<unsigned char> bytes =
      ReadFileBytes(std::string(POSEMORPH_SOURCE_DIR) + "/tests/runtime/rigs/small-format-1.1.pmrig");
  Rig rig;
  Error err;
  REQUIRE_MESSAGE(LoadRig(bytes.data(), bytes.size(), &rig, &err), err.message);
  CHECK(rig.format_major() == 1);
  CHECK(rig.format_minor() == 1);
  const PoseSpaceGrid& g = rig.grid();
  CHECK(g.centre_weights.empty());
  const std::uint32_t n = rig.pose_count();
  for (double y : {-0.3, 0.1, 0.25, 0.7})
    for (double x : {-0.4, 0.0, 0.33, 0.5, 0.9, 1.2}) {
      CAPTURE(x);
      CAPTURE(y);
      const Weights w = WeightsAt(rig, x, y);
      // The diagonal split, written out: the bits must be the same.
      const double u = (x - g.origin_x) / g.cell, v = (y - g.origin_y) / g.cell;
      const std::uint32_t i = std::uint32_t(u), j = std::uint32_t(v);
      const double fx = u - i, fy = v - j;
      const std::size_t row = g.cells_x + 1;
      const double* w00 = g.weights.data + (j * row + i) * n;
      const double *w10 = w00 + n, *w01 = w00 + row * n, *w11 = w01 + n;
      for (std::uint32_t k = 0; k < n; ++k) {
        const double expected = fx >= fy ? (1 - fx) * w00[k] + (fx - fy) * w10[k] + fy * w11[k]
                                         : (1 - fy) * w00[k] + (fy - fx) * w01[k] + fx * w11[k];
        CHECK(w.raw[k] == expected);
      }
    }
}

TEST_CASE("a rig baked now is format 1.14 with a centre per grid cell and its drawings' folder") {
  const Rig rig = LoadTestRig("small");
  CHECK(rig.format_minor() == format::kVersionMinor);
  CHECK(format::kVersionMinor == 14);
  // Baked by the CLI from tests/runtime/rigs/small.json into the build's rig
  // folder: the folder of the description, relative to the rig.
  const std::string folder(rig.drawing_folder().data, rig.drawing_folder().size);
  const std::string tail = "tests/runtime/rigs";
  CAPTURE(folder);
  CHECK(folder.size() > tail.size());
  CHECK(folder.compare(folder.size() - tail.size(), tail.size(), tail) == 0);
  CHECK(LoadCommitted("small-format-1.4.pmrig").drawing_folder().size == 0);
  CHECK(rig.texture_filter() == TextureFilter::kLinear);  // small.json gives no filter
  const PoseSpaceGrid& g = rig.grid();
  CHECK(g.centre_weights.size == std::size_t(g.cells_x) * g.cells_y * rig.pose_count());
  // At a cell centre the weights are the centre's row.
  const std::uint32_t n = rig.pose_count();
  const Weights w = WeightsAt(rig, g.origin_x + 1.5 * g.cell, g.origin_y + 2.5 * g.cell);
  const double* c = g.centre_weights.data + (2 * g.cells_x + 1) * n;
  for (std::uint32_t k = 0; k < n; ++k) CHECK(w.raw[k] == doctest::Approx(c[k]).epsilon(1e-14));
}

// small-format-1.12-compact.pmrig: small.json as the 1.12 bake wrote it
// (compact, at commit 8444392), each pose's positions coded alone. 1.13
// codes the poses after the first against pose 0, the same integers: the
// build's small.compact.pmrig decodes to the same arrays and frames, bit for
// bit, in fewer bytes.
TEST_CASE("a format 1.12 compact rig loads to the positions and frames of today's, coded against pose 0") {
  const OldAndNow r = LoadOldAndNow("small-format-1.12-compact.pmrig", "small.compact");
  CHECK(r.old.format_minor() == 12);
  CHECK(r.now.format_minor() == format::kVersionMinor);
  MESSAGE("small.compact: " << r.old_bytes.size() << " bytes at 1.12, " << r.now_bytes.size() << " now");
  CHECK(r.now_bytes.size() < r.old_bytes.size());
  CheckDecodesAlike(r.old, r.now);
}

// arm-format-1.13-compact.pmrig: tests/runtime/rigs/arm.json as the 1.13
// bake wrote it (compact, at commit 77adb28), each vertex predicted by the
// previous one. 1.14 predicts it by the mean of its earlier neighbours in
// the mesh, the same integers: the build's arm.compact.pmrig decodes to the
// same arrays and frames, bit for bit, with a shorter QPOS.
TEST_CASE("a format 1.13 compact rig loads to the positions and frames of today's, predicted from neighbours") {
  const OldAndNow r = LoadOldAndNow("arm-format-1.13-compact.pmrig", "arm.compact");
  CHECK(r.old.format_minor() == 13);
  CHECK(r.now.format_minor() == 14);
  auto qpos_size = [](const std::vector<unsigned char>& bytes) { return SectionSize(bytes, format::kQuantPositions); };
  MESSAGE("arm.compact QPOS: " << qpos_size(r.old_bytes) << " bytes at 1.13, " << qpos_size(r.now_bytes) << " at 1.14");
  CHECK(qpos_size(r.now_bytes) < qpos_size(r.old_bytes));
  CheckDecodesAlike(r.old, r.now);
}

// small-format-1.2.pmrig: small.json baked with --precision exact and the
// header's minor version set back to 2 (the header lies outside the CRC):
// what the 1.2 bake wrote, whose exact sections 1.3 and 1.4 did not change.
// small-format-1.3-compact.pmrig: small.json as the 1.3 bake wrote it
// (compact). small-format-1.4.pmrig and small-format-1.4-compact.pmrig:
// small.json as the 1.4 bake wrote it (exact, compact) at commit 03c561f,
// before the weights inside the pose points' hull became the thin-plate
// spline (the files keep that grid). 1.4 added only the texture-filter flag:
// the older files load, sample linear, and give the 1.4 files' arrays and
// frames bit for bit.
TEST_CASE("a format 1.3 compact rig loads and gives the frames of the 1.4 compact file") {
  const Rig old = LoadCommitted("small-format-1.3-compact.pmrig");
  CHECK(old.format_minor() == 3);
  CHECK(old.texture_filter() == TextureFilter::kLinear);
  const Rig now = LoadCommitted("small-format-1.4-compact.pmrig");
  CHECK(now.format_minor() == 4);
  for (double x : {-0.5, 0.0, 0.3, 1.0, 1.7}) {
    CAPTURE(x);
    CHECK(MorphAt(old, x, 0.2) == MorphAt(now, x, 0.2));
  }
}

TEST_CASE("a format 1.2 rig loads to the arrays of the 1.4 exact file") {
  const Rig old = LoadCommitted("small-format-1.2.pmrig");
  CHECK(old.format_minor() == 2);
  const Rig now = LoadCommitted("small-format-1.4.pmrig");
  REQUIRE(old.grid().weights.size == now.grid().weights.size);
  for (std::size_t k = 0; k < now.grid().weights.size; ++k) CHECK(old.grid().weights[k] == now.grid().weights[k]);
  for (std::size_t k = 0; k < now.angles().size; ++k) CHECK(old.angles()[k] == now.angles()[k]);
  const std::vector<double> a = MorphAt(old, 0.3, 0.2), b = MorphAt(now, 0.3, 0.2);
  CHECK(a == b);
}

TEST_CASE("today's bake keeps the 1.4 file's angles and poses, the weight grid moved") {
  // The thin-plate spline changed the stored weights, not the geometry: the
  // same angles, and at the pose points the same poses.
  const Rig before = LoadCommitted("small-format-1.4.pmrig");
  const Rig now = LoadTestRig("small");
  REQUIRE(before.angles().size == now.angles().size);
  for (std::size_t k = 0; k < now.angles().size; ++k) CHECK(before.angles()[k] == now.angles()[k]);
  REQUIRE(before.grid().weights.size == now.grid().weights.size);
  double changed = 0;
  for (std::size_t k = 0; k < now.grid().weights.size; ++k)
    changed = std::max(changed, std::abs(before.grid().weights[k] - now.grid().weights[k]));
  MESSAGE("largest change of a stored grid weight: " << changed);
  CHECK(changed > 1e-3);
  for (const auto& p : {std::pair<double, double>{0, 0}, {1, 0.5}}) {
    const std::vector<double> a = MorphAt(before, p.first, p.second), b = MorphAt(now, p.first, p.second);
    REQUIRE(a.size() == b.size());
    for (std::size_t k = 0; k < a.size(); ++k) CHECK(std::abs(a[k] - b[k]) <= 1e-14);
  }
}
