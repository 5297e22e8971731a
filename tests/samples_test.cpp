// SPDX-License-Identifier: MIT
// The bundled samples: committed files match their generator, and bakes are deterministic.
#include <fstream>
#include <sstream>

#include "gingerbread_rig.h"
#include "sample_json.h"
#include "test_support.h"

using namespace posemorph;

namespace {

std::string ReadFile(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  REQUIRE_MESSAGE(f.good(), "cannot open " << path);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("committed sample descriptions are what the generator writes") {
  const std::string dir = POSEMORPH_SOURCE_DIR "/assets/";
  CHECK(ReadFile(dir + "snake/snake.json") == samples::DescriptionJson(samples::SnakeRig()));
  CHECK(ReadFile(dir + "worm-line/worm-line.json") == samples::DescriptionJson(samples::WormLineRig()));
  CHECK(ReadFile(dir + "gingerbread/gingerbread.json") == samples::DescriptionJson(samples::GingerbreadRig()));
}

TEST_CASE("the snake sample has what the README promises, and bakes to the same bytes twice") {
  bake::RigDescription a = bake::ReadRigDescription(POSEMORPH_SOURCE_DIR "/assets/snake/snake.json");
  a.parameters.compact = false;  // the exact encoding: reproduction to 1e-9
  bake::RigDescription b = a;
  CHECK(a.poses.size() >= 4);
  bake::BakeReport report;
  const auto bytes_a = bake::BakeRig(a, &report);
  const auto bytes_b = bake::BakeRig(b);
  CHECK(bytes_a == bytes_b);
  CHECK(report.max_reproduction_error <= 1e-9);
  // Non-collinear pose points.
  const Eigen::Vector2d p0 = a.poses[0].point, p1 = a.poses[1].point;
  bool collinear = true;
  for (const auto& p : a.poses) {
    const Eigen::Vector2d d1 = p1 - p0, d2 = p.point - p0;
    collinear = collinear && std::abs(d1.x() * d2.y() - d1.y() * d2.x()) < 1e-12;
  }
  CHECK_FALSE(collinear);
}
