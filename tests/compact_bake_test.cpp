// SPDX-License-Identifier: MIT
// The bake's compact encoding: a 1035-vertex, 8-pose plate within 100 KB at
// the default budget, the bake's own measurement within budget, the same
// bytes twice, and --precision exact unchanged; the bake's steps hand each
// other sections, which WriteRig lays out as the loader reads them.
#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "posemorph/bake/bake.h"
#include "posemorph/bake/pose_space_samples.h"
#include "posemorph/rig.h"
#include "posemorph/rig_format.h"
#include "strip_rig.h"

using namespace posemorph;

TEST_CASE("a 1035-vertex, 8-pose rig bakes compact within 100 KB and within the budget") {
  bake::RigDescription desc = samples::PlateRig(22, 8);
  desc.file = "plate";
  // Given as vertices: the default scale (the rig's size counts as 1024 pixels).
  bake::RigDescription copy = desc;
  bake::BakeReport report;
  const std::vector<unsigned char> bytes = bake::BakeRig(desc, &report);
  CHECK(report.vertices == 1035);
  CHECK(report.poses == 8);
  CHECK(report.compact);
  MESSAGE("plate: " << bytes.size() << " bytes compact, " << report.exact_bytes << " exact; max vertex error "
                    << report.compact_report.max_error_px << " px over " << report.compact_report.samples << " frames");
  CHECK(bytes.size() <= 100 * 1024);
  if (const char* dump = std::getenv("POSEMORPH_DUMP_PLATE")) {
    FILE* f = std::fopen(dump, "wb");
    std::fwrite(bytes.data(), 1, bytes.size(), f);
    std::fclose(f);
  }
  CHECK(report.compact_report.max_error_px <= 0.01);
  CHECK(report.compact_report.pose_error_px <= 0.01);
  CHECK(bake::BakeRig(copy) == bytes);  // deterministic
  Rig rig;
  Error err;
  REQUIRE_MESSAGE(LoadRig(bytes.data(), bytes.size(), &rig, &err), err.message);
  CHECK(rig.format_minor() == format::kVersionMinor);
}

namespace {

// A 10 x 10 plate of 5 poses, baked and loaded into `rig`; its pose-space samples.
std::vector<Eigen::Vector2d> BakedPlate(Rig& rig) {
  bake::RigDescription desc = samples::PlateRig(10, 5);
  desc.file = "plate";
  const std::vector<unsigned char> bytes = bake::BakeRig(desc);
  Error err;
  REQUIRE_MESSAGE(LoadRig(bytes.data(), bytes.size(), &rig, &err), err.message);
  std::vector<Eigen::Vector2d> at;
  for (const bake::PoseSpaceSample& s : bake::SamplePoseSpace(rig, bake::PoseSpaceSampling{})) at.push_back(s.at);
  return at;
}

}  // namespace

TEST_CASE("frames evaluated in batches, as the compact search and the fold check do, are EvaluateFrame's bits") {
  Rig rig;
  std::vector<Eigen::Vector2d> at = BakedPlate(rig);
  at.push_back({3.5, -2.0});  // far outside the pose points: limited weights differ from raw ones
  REQUIRE(at.size() > 2 * bake::kFrameBatch);
  const std::size_t frame = 2 * std::size_t(rig.vertex_count());
  bake::FrameBuffers buffers;
  std::vector<double> one;
  // A whole batch, then batches of 5 frames (a partial group), the buffers reused.
  for (std::size_t first = 0, count = 0; first < at.size(); first += count) {
    count = std::min<std::size_t>(first == 0 ? bake::kFrameBatch : 5, at.size() - first);
    REQUIRE(bake::EvaluateFrames(rig, at, first, count, buffers));
    REQUIRE(buffers.positions.size() == count * frame);
    for (std::size_t k = 0; k < count; ++k) {
      CAPTURE(first + k);
      REQUIRE(bake::EvaluateFrame(rig, at[first + k], one));
      CHECK(std::memcmp(one.data(), buffers.positions.data() + k * frame, frame * sizeof(double)) == 0);
    }
  }
}

TEST_CASE("frames evaluated in runs on several threads are EvaluateFrame's bits, and a visit stops them all") {
  Rig rig;
  std::vector<Eigen::Vector2d> at = BakedPlate(rig);
  const std::size_t frame = 2 * std::size_t(rig.vertex_count());
  const std::size_t groups = (at.size() + bake::kFrameBatch - 1) / bake::kFrameBatch;
  REQUIRE(groups > 8);
  std::vector<double> one;
  for (unsigned threads : {1u, 2u, 3u, 8u, 64u}) {
    CAPTURE(threads);
    const std::size_t runs = bake::FrameRunCount(at.size(), threads);
    CHECK(runs == std::min<std::size_t>(threads, 8));
    std::vector<bake::FrameBuffers> parts;
    std::vector<std::vector<double>> frames(at.size());
    std::vector<std::size_t> run_of(at.size(), runs), last(runs, 0);
    std::vector<int> in_order(runs, 1);  // each run writes its own
    std::atomic<bool> bad_run{false};
    REQUIRE(bake::EvaluateFramesOnEachCore(
        rig, at, parts,
        [&](std::size_t run, std::size_t first, std::size_t count, const double* positions) {
          if (run >= runs) {
            bad_run = true;
            return false;
          }
          in_order[run] = in_order[run] && first >= last[run] && count <= bake::kFrameBatch;
          last[run] = first + count;
          for (std::size_t k = 0; k < count; ++k) {
            frames[first + k].assign(positions + k * frame, positions + (k + 1) * frame);
            run_of[first + k] = run;
          }
          return true;
        },
        threads));
    CHECK(!bad_run);
    CHECK(std::count(in_order.begin(), in_order.end(), 1) == std::ptrdiff_t(runs));
    CHECK(parts.size() == runs);
    for (std::size_t i = 0; i < at.size(); ++i) {
      CAPTURE(i);
      REQUIRE(run_of[i] < runs);
      CHECK((i == 0 || run_of[i] >= run_of[i - 1]));  // each run a contiguous stretch, in order
      REQUIRE(bake::EvaluateFrame(rig, at[i], one));
      REQUIRE(frames[i].size() == frame);
      CHECK(std::memcmp(one.data(), frames[i].data(), frame * sizeof(double)) == 0);
    }
    // A visit that says stop: on one thread nothing after that group is
    // visited; on several, each run stops by its next group.
    std::atomic<std::size_t> visited{0};
    std::vector<bake::FrameBuffers> again;
    REQUIRE(bake::EvaluateFramesOnEachCore(
        rig, at, again,
        [&](std::size_t, std::size_t, std::size_t, const double*) {
          ++visited;
          return false;
        },
        threads));
    CHECK(visited.load() >= 1);
    CHECK(visited.load() <= runs);
  }
}

TEST_CASE("--precision exact keeps the exact encoding") {
  bake::RigDescription desc = samples::SnakeRig();
  desc.parameters.compact = false;
  bake::BakeReport report;
  const std::vector<unsigned char> bytes = bake::BakeRig(desc, &report);
  CHECK_FALSE(report.compact);
  CHECK(bytes.size() == report.exact_bytes);
  CHECK(report.max_reproduction_error <= 1e-9);
}

TEST_CASE("a budget no compact encoding reaches gives the exact encoding, and the report says so") {
  bake::RigDescription desc = samples::SnakeRig();
  desc.parameters.max_error_px = 1e-6;
  desc.parameters.pixels_per_unit = 1e6;  // a budget of 1e-12 rig units: beyond 40-bit positions
  bake::BakeReport report;
  const std::vector<unsigned char> bytes = bake::BakeRig(desc, &report);
  CHECK(report.compact_report.fell_back);
  CHECK_FALSE(report.compact);
  CHECK(bytes.size() == report.exact_bytes);
  CHECK(report.max_reproduction_error <= 1e-9);
}

TEST_CASE("the bake hands sections, not bytes: WriteRig lays them out as the loader reads them") {
  for (const bool compact : {false, true}) {
    CAPTURE(compact);
    bake::RigDescription desc = samples::SnakeRig();
    desc.parameters.compact = compact;
    bake::BakeReport report;
    const bake::BakedRig baked = bake::BakeOne(desc, &report);
    REQUIRE(!baked.sections.sections.empty());
    // The file is WriteRig of the sections, and RigFileSize says its size without writing it.
    CHECK(bake::WriteRig(baked.sections) == baked.bytes);
    CHECK(bake::RigFileSize(baked.sections) == baked.bytes.size());
    CHECK(report.bytes == baked.bytes.size());
    // The loader's table holds each section in order, aligned, byte for byte.
    RigSection table[format::kMaxSections];
    std::uint32_t count = 0;
    Error err;
    REQUIRE_MESSAGE(ReadRigSections(baked.bytes.data(), baked.bytes.size(), table, format::kMaxSections, &count, &err),
                    err.message);
    REQUIRE(count == baked.sections.sections.size());
    for (std::uint32_t k = 0; k < count; ++k) {
      const bake::RigSections::Section& s = baked.sections.sections[k];
      CHECK(table[k].tag == s.tag);
      CHECK(table[k].offset % format::kSectionAlignment == 0);
      REQUIRE(table[k].size == s.bytes.size());
      CHECK(std::equal(s.bytes.begin(), s.bytes.end(), baked.bytes.begin() + std::ptrdiff_t(table[k].offset)));
      CHECK(baked.sections.Find(s.tag) == &s.bytes);
    }
    CHECK(baked.sections.Find(format::kChannels) == nullptr);
    // The compact encoding's sections are the quantised ones.
    CHECK((baked.sections.Find(format::kQuantPositions) != nullptr) == compact);
    CHECK((baked.sections.Find(format::kPosePositions) != nullptr) == !compact);
    // And the verification's rig is those bytes, loaded.
    CHECK(baked.rig.vertex_count() == report.vertices);
  }
}
