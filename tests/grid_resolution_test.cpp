// SPDX-License-Identifier: MIT
// The pose-space grid adapts to the sprite (grid_resolution.h, issue 36
// point 5): a small sprite left at the default gets a coarser grid, whose
// frames stay within kGridTolerancePx of the default grid's everywhere in
// the pose hull (measured here with the runtime, against the bake's bound);
// a large drawing keeps the default; a given resolution is kept.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "posemorph/bake/bake.h"
#include "posemorph/bake/grid_resolution.h"
#include "posemorph/bake/pose_space_weights.h"
#include "posemorph/bake/pose_space_samples.h"
#include "posemorph/bake/rig_description.h"
#include "posemorph/rig.h"

namespace pb = posemorph::bake;

namespace {

std::string Drawn(const std::string& path) { return std::string(POSEMORPH_DRAWN_SAMPLES) + "/" + path; }

posemorph::Rig Load(const std::vector<unsigned char>& bytes) {
  posemorph::Rig rig;
  posemorph::Error err;
  REQUIRE_MESSAGE(posemorph::LoadRig(bytes.data(), bytes.size(), &rig, &err), err.message);
  return rig;
}

}  // namespace

TEST_CASE("grid resolution: a small sprite gets a coarser grid whose frames stay within the tolerance in the hull") {
  const std::string json = Drawn("sprites/slime/slime.json");
  REQUIRE_MESSAGE(std::filesystem::exists(json), "the build rasterises the sprites");
  pb::RigDescription automatic = pb::ReadRigDescription(json);
  REQUIRE(automatic.poses.size() == 4);
  REQUIRE_FALSE(automatic.parameters.grid_resolution_given);
  automatic.parameters.compact = false;  // exact doubles: only the grids differ
  pb::RigDescription fine = automatic;
  fine.parameters.grid_resolution = 64;
  fine.parameters.grid_resolution_given = true;

  pb::BakeReport a_report, f_report;
  const std::vector<unsigned char> a_bytes = pb::BakeRig(automatic, &a_report);
  const std::vector<unsigned char> f_bytes = pb::BakeRig(fine, &f_report);
  CHECK(std::max(f_report.grid_cells_x, f_report.grid_cells_y) == 64);
  CHECK_FALSE(f_report.grid_coarsened);  // given: kept
  CHECK(f_report.grid_move_px == 0);
  const std::uint32_t cells = std::max(a_report.grid_cells_x, a_report.grid_cells_y);
  CHECK(cells < 64);
  CHECK(std::find(std::begin(pb::kCoarseGridResolutions), std::end(pb::kCoarseGridResolutions), int(cells)) !=
        std::end(pb::kCoarseGridResolutions));
  CHECK(a_report.grid_coarsened);
  CHECK(a_report.grid_move_px > 0);
  CHECK(a_report.grid_move_px <= pb::kGridTolerancePx);
  // The same mesh (the mapping does not depend on the grid).
  REQUIRE(a_report.vertices == f_report.vertices);
  CHECK(a_report.triangles == f_report.triangles);

  // Frames of both rigs over the hull (grid, edges, every two poses): no
  // vertex further apart than the bound the bake printed (drawn: 1 pixel per
  // rig unit), which is within the tolerance.
  const posemorph::Rig a = Load(a_bytes), f = Load(f_bytes);
  pb::PoseSpaceSampling sampling;
  sampling.grid = 32;
  sampling.per_pair = 16;
  double worst = 0;
  std::size_t frames = 0;
  std::vector<double> pa, pf;
  for (const pb::PoseSpaceSample& s : pb::SamplePoseSpace(f, sampling)) {
    if (!s.in_hull) continue;
    REQUIRE(pb::EvaluateFrame(a, s.at, pa));
    REQUIRE(pb::EvaluateFrame(f, s.at, pf));
    REQUIRE(pa.size() == pf.size());
    for (std::size_t v = 0; v + 1 < pa.size(); v += 2)
      worst = std::max(worst, std::hypot(pa[v] - pf[v], pa[v + 1] - pf[v + 1]));
    ++frames;
  }
  MESSAGE("slime: grid " << cells << " cells, " << a_bytes.size() << " bytes against " << f_bytes.size()
                         << " with 64; frames apart by at most " << worst << " px over " << frames
                         << " hull points (the bake's bound " << a_report.grid_move_px << " px)");
  CHECK(frames > 100);
  CHECK(worst > 0);  // the grids do differ
  CHECK(worst <= a_report.grid_move_px);
  CHECK(a_bytes.size() < f_bytes.size());
}

TEST_CASE("grid resolution: a 256-pixel drawing keeps the default grid, and a given resolution is kept") {
  const std::string json = Drawn("sprout/sprout.json");
  REQUIRE_MESSAGE(std::filesystem::exists(json), "the build rasterises the drawn samples");
  pb::RigDescription sprout = pb::ReadRigDescription(json);
  sprout.parameters = pb::BakeParameters{};  // as if the description left the "bake" block out
  pb::BakeReport report;
  pb::BakeRig(sprout, &report);
  CHECK(std::max(report.grid_cells_x, report.grid_cells_y) == 64);  // 8 to 32 would move Sprout too far
  CHECK_FALSE(report.grid_coarsened);

  const std::string slime = Drawn("sprites/slime/slime.json");
  pb::RigDescription given = pb::ReadRigDescription(slime);
  given.parameters.grid_resolution = 48;
  given.parameters.grid_resolution_given = true;
  pb::BakeRig(given, &report);
  CHECK(std::max(report.grid_cells_x, report.grid_cells_y) == 48);
  CHECK_FALSE(report.grid_coarsened);
}

TEST_CASE("grid resolution: two poses get the coarsest grid, their weights being linear along the segment") {
  const pb::RigDescription two = pb::ParseRigDescription(R"({
    "posemorph": 1,
    "poses": [
      {"name": "a", "point": [0, 0], "outline": [[0, 0], [40, 0], [40, 40], [0, 40]], "landmarks": [[0, 0], [40, 40]]},
      {"name": "b", "point": [1, 0], "outline": [[0, 0], [40, 0], [50, 40], [10, 40]], "landmarks": [[0, 0], [50, 40]]}
    ]
  })",
                                                         "two.json", ".");
  pb::BakeReport report;
  pb::BakeRig(two, &report);
  CHECK(report.grid_coarsened);
  CHECK(std::max(report.grid_cells_x, report.grid_cells_y) == pb::kCoarseGridResolutions[0]);
  CHECK(report.grid_move_px < 1e-9);  // the same weights along the segment, to rounding
}

TEST_CASE("grid resolution: poses on a line get a grid 8 cells across it, with the frames along the line kept") {
  // Three poses on a vertical line, as init lays out three drawings.
  const std::string text = R"({
    "posemorph": 1,
    "poses": [
      {"name": "a", "point": [0, 0], "outline": [[0, 0], [40, 0], [40, 40], [0, 40]], "landmarks": [[0, 0], [40, 40]]},
      {"name": "b", "point": [0, 1], "outline": [[0, 0], [40, 0], [50, 40], [10, 40]], "landmarks": [[0, 0], [50, 40]]},
      {"name": "c", "point": [0, -1], "outline": [[0, 0], [40, 0], [30, 40], [-10, 40]], "landmarks": [[0, 0], [30, 40]]}
    ]
  })";
  pb::RigDescription line = pb::ParseRigDescription(text, "line.json", ".");
  line.parameters.compact = false;  // exact doubles: only the grids differ
  pb::RigDescription wide = line;   // a given resolution keeps the whole domain
  wide.parameters.grid_resolution = 64;
  wide.parameters.grid_resolution_given = true;
  pb::BakeReport l_report, w_report;
  const std::vector<unsigned char> l_bytes = pb::BakeRig(line, &l_report);
  const std::vector<unsigned char> w_bytes = pb::BakeRig(wide, &w_report);
  CHECK(l_report.grid_cells_x == pb::kLineLayoutCells);
  CHECK(w_report.grid_cells_x > 32);  // the domain's width: the box grown by its length on each side
  CHECK(w_report.grid_cells_y == 64);
  REQUIRE(l_report.vertices == w_report.vertices);
  CHECK(l_bytes.size() < w_bytes.size());

  // Driven along the line (and within its pad range across it), the frames
  // stay within the grid tolerance of the whole domain's.
  const posemorph::Rig l = Load(l_bytes), w = Load(w_bytes);
  const posemorph::PadRange pad = l.pad_range();
  CHECK(pad.min_x < 0);
  CHECK(pad.max_x > 0);
  CHECK(pad.min_x >= l.grid().origin_x);
  CHECK(pad.max_x <= l.grid().origin_x + l.grid().cell * l.grid().cells_x);
  double worst = 0;
  std::vector<double> pl, pw;
  for (int k = 0; k <= 200; ++k)
    for (double across : {pad.min_x, 0.0, pad.max_x}) {
      const Eigen::Vector2d at(across, -1 + k / 100.0);
      REQUIRE(pb::EvaluateFrame(l, at, pl));
      REQUIRE(pb::EvaluateFrame(w, at, pw));
      for (std::size_t v = 0; v + 1 < pl.size(); v += 2)
        worst = std::max(worst, std::hypot(pl[v] - pw[v], pl[v + 1] - pw[v + 1]));
    }
  MESSAGE("line layout: grid " << l_report.grid_cells_x << " x " << l_report.grid_cells_y << ", " << l_bytes.size()
                               << " bytes against " << w_bytes.size() << " across the domain; frames apart by at most "
                               << worst << " px along the line");
  CHECK(worst <= pb::kGridTolerancePx);
}
