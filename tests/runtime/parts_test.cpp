// SPDX-License-Identifier: MIT
// Layered characters in the runtime (format 1.6): the part table, the draw
// sequence, the draw list's parts, the joint shared by two parts, and rigs
// without parts read as one part.
#include <cstring>
#include <set>
#include <string>

#include "posemorph/draw_list.h"
#include "posemorph/path.h"
#include "posemorph/rig_format.h"
#include "runtime_support.h"

namespace posemorph::test {
namespace {

std::string Text(StringView v) { return std::string(v.data ? v.data : "", v.size); }

// The vertices the triangles of part p use.
std::set<std::uint32_t> PartVertices(const Rig& rig, std::uint32_t p) {
  std::set<std::uint32_t> out;
  const PartView part = rig.part(p);
  for (std::uint32_t k = 3 * part.first_triangle; k < 3 * (part.first_triangle + part.triangle_count); ++k)
    out.insert(rig.triangles()[k]);
  return out;
}

double Distance(const std::vector<double>& x, std::uint32_t a, std::uint32_t b) {
  return std::hypot(x[2 * a] - x[2 * b], x[2 * a + 1] - x[2 * b + 1]);
}

}  // namespace

TEST_CASE("parts: the arm rig's table, draw sequence and images, exact and compact") {
  for (const char* name : {"arm", "arm.compact"}) {
    CAPTURE(name);
    const Rig rig = LoadTestRig(name);
    CHECK(rig.format_minor() == format::kVersionMinor);
    REQUIRE(rig.part_count() == 2);
    CHECK(Text(rig.part(0).name) == "body");
    CHECK(Text(rig.part(1).name) == "arm");
    CHECK(rig.part(0).first_triangle == 0);
    CHECK(rig.part(0).triangle_count == 32);
    CHECK(rig.part(1).first_triangle == 32);
    CHECK(rig.part(1).triangle_count == 16);
    CHECK(rig.part(0).draw_order == 0);
    CHECK(rig.part(1).draw_order == 1);
    CHECK(rig.part(2).triangle_count == 0);  // beyond the table: empty
    const Span<const std::uint32_t> sequence = rig.draw_sequence();
    REQUIRE(sequence.size == 2);
    CHECK(sequence[0] == 0);  // the body behind, the arm in front
    CHECK(sequence[1] == 1);
    for (std::uint32_t i = 0; i < rig.pose_count(); ++i) CHECK(rig.part_image(1, i).size == 0);
    CHECK(rig.part_image(0, rig.pose_count()).data == nullptr);
  }
}

TEST_CASE("parts: a rig without parts is one part of every triangle, drawing the poses' images") {
  const Rig rig = LoadTestRig("small");
  REQUIRE(rig.part_count() == 1);
  CHECK(Text(rig.part(0).name).empty());
  CHECK(rig.part(0).first_triangle == 0);
  CHECK(rig.part(0).triangle_count == rig.triangle_count());
  REQUIRE(rig.draw_sequence().size == 1);
  CHECK(rig.draw_sequence()[0] == 0);
  CHECK(Text(rig.part_image(0, 0)) == "a.png");
  CHECK(Text(rig.part_image(0, 0)) == Text(rig.pose_image(0)));
}

TEST_CASE("parts: the glued arm shares one vertex with the body and turns about it, rigidly, along its path") {
  const Rig rig = LoadTestRig("arm");
  const std::set<std::uint32_t> body = PartVertices(rig, 0), arm = PartVertices(rig, 1);
  std::vector<std::uint32_t> shared;
  for (std::uint32_t v : arm)
    if (body.count(v)) shared.push_back(v);
  REQUIRE(shared.size() == 1);  // the joint: one unknown of the solve, in both parts
  const std::uint32_t joint = shared[0];
  // Base poses reproduced (the exact encoding: 1e-9 of the rig's size).
  for (std::uint32_t i = 0; i < rig.pose_count(); ++i) {
    const std::vector<double> x = MorphAt(rig, rig.pose_points()[2 * i], rig.pose_points()[2 * i + 1]);
    const double* pose = rig.pose_positions(i).data;
    double worst = 0;
    for (std::size_t k = 0; k < x.size(); ++k) worst = std::max(worst, std::fabs(x[k] - pose[k]));
    CHECK(worst <= 1e-9 * rig.bounding_box_diagonal());
  }
  // Along the path the arm keeps its length about the joint: it turns, it
  // does not stretch or slide (each arm vertex within 1% of its rest
  // distance from the joint, 0.5 units at the tip).
  const PathView path = rig.path(std::uint32_t(rig.FindPath("raise")));
  const std::vector<double> rest(rig.pose_positions(0).data, rig.pose_positions(0).data + 2 * rig.vertex_count());
  double worst = 0;
  for (int k = 0; k <= 40; ++k) {
    double px = 0, py = 0;
    REQUIRE(SamplePath(path, path.end_time() * k / 40.0, &px, &py));
    const std::vector<double> x = MorphAt(rig, px, py);
    for (std::uint32_t v : arm)
      if (v != joint) worst = std::max(worst, std::fabs(Distance(x, v, joint) / Distance(rest, v, joint) - 1));
  }
  CHECK(worst < 0.01);
}

TEST_CASE("parts: every draw list lists the parts back to front") {
  for (const char* name : {"arm", "small"}) {
    CAPTURE(name);
    const Rig rig = LoadTestRig(name);
    const double points[4] = {0.5, 0, 1.5, 0};
    const CharacterBuffers buffers = CharacterBuffers::For(rig, 2);
    std::vector<double> block((buffers.bytes + sizeof(double) - 1) / sizeof(double));
    DrawListJob job;
    REQUIRE(buffers.Bind(rig, block.data(), block.size() * sizeof(double), &job));
    job.points = {points, 4};
    REQUIRE(job.Run());
    for (std::size_t k = 0; k < 2; ++k) {
      REQUIRE(job.output[k].parts.size == rig.part_count());
      for (std::size_t p = 0; p < rig.part_count(); ++p) CHECK(job.output[k].parts[p] == rig.draw_sequence()[p]);
    }
  }
}

TEST_CASE("parts: the loader refuses a part table that does not tile the triangles, or parts without PART") {
  std::vector<unsigned char> bytes = TestRigBytes("arm");
  RigSection sections[format::kMaxSections];
  std::uint32_t count = 0;
  REQUIRE(ReadRigSections(bytes.data(), bytes.size(), sections, format::kMaxSections, &count));
  std::uint64_t part_at = 0;
  for (std::uint32_t k = 0; k < count; ++k)
    if (sections[k].tag == format::kParts) part_at = sections[k].offset;
  REQUIRE(part_at != 0);
  LoadOptions no_checksum;
  no_checksum.verify_checksum = false;
  auto refused = [&](std::vector<unsigned char> b) {
    Rig rig;
    Error err;
    CHECK_FALSE(LoadRig(b.data(), b.size(), &rig, &err, no_checksum));
    CHECK_FALSE(rig.loaded());
    return std::string(err.message);
  };
  auto put = [](std::vector<unsigned char>& b, std::uint64_t at, std::uint32_t v) { std::memcpy(&b[at], &v, 4); };
  std::vector<unsigned char> gap = bytes;
  put(gap, part_at + 16, 33);  // the arm starts one triangle late
  CHECK(refused(gap).find("parts must tile") != std::string::npos);
  std::vector<unsigned char> empty = bytes;
  put(empty, part_at + 4, 0);  // the body covers nothing
  CHECK(refused(empty).find("parts must tile") != std::string::npos);
  std::vector<unsigned char> reserved = bytes;
  put(reserved, part_at + 12, 1);
  CHECK(refused(reserved).find("reserved") != std::string::npos);
  std::vector<unsigned char> short_cover = bytes;
  put(short_cover, part_at + 16 + 4, 15);  // the last part ends before the last triangle
  CHECK(refused(short_cover).find("cover 47 of 48") != std::string::npos);
  // META without the parts flag, PART still there.
  std::uint64_t meta_at = 0;
  for (std::uint32_t k = 0; k < count; ++k)
    if (sections[k].tag == format::kMeta) meta_at = sections[k].offset;
  std::vector<unsigned char> unflagged = bytes;
  std::uint32_t flags = 0;
  std::memcpy(&flags, &unflagged[meta_at + 28], 4);
  put(unflagged, meta_at + 28, flags & ~format::kMetaFlagParts);
  CHECK(refused(unflagged).find("PART section present") != std::string::npos);
}

}  // namespace posemorph::test
