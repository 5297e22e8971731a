// SPDX-License-Identifier: MIT
// The bake's compact encoding: a 1035-vertex, 8-pose plate within 100 KB at
// the default budget, the bake's own measurement within budget, the same
// bytes twice, and --precision exact unchanged.
#include <doctest/doctest.h>

#include <cstdio>
#include <cstdlib>

#include "posemorph/bake/bake.h"
#include "posemorph/rig.h"
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
  CHECK(rig.format_minor() == 7);
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
