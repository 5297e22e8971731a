// SPDX-License-Identifier: MIT
// N-way mapping: outlines, correspondence, enclosing simplification and
// compatible triangulation, on shapes generated here and on the drawn samples.
#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <unistd.h>

#include "cli.h"
#include "posemorph/bake/bake.h"
#include "posemorph/bake/deform_poses.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/inbetween_check.h"
#include "posemorph/bake/pose_space_samples.h"
#include "posemorph/bake/mapping/nway_mapping.h"
#include "posemorph/bake/rig_description.h"
#include "drawing_coverage.h"

namespace pb = posemorph::bake;
namespace pm = posemorph::bake::mapping;
using pm::Point;
using pm::Polygon;

namespace {

Polygon Star(int points, double r_out, double r_in, double turn) {
  Polygon p;
  for (int k = 0; k < 2 * points; ++k) {
    const double a = turn + M_PI * k / points;
    const double r = k % 2 ? r_in : r_out;
    p.push_back({r * std::cos(a), r * std::sin(a)});
  }
  return p;
}

// A band around a centre line c(t), t in [0, 1], of half-width w: one side out, the other back.
Polygon Band(const std::function<Point(double)>& c, double w, int samples) {
  Polygon left, right;
  for (int k = 0; k <= samples; ++k) {
    const double t = double(k) / samples, h = 1e-4;
    const Point d = (c(std::min(1.0, t + h)) - c(std::max(0.0, t - h))).normalized();
    const Point n(-d.y(), d.x());
    right.push_back(c(t) - w * n);
    left.push_back(c(t) + w * n);
  }
  Polygon p = right;
  p.insert(p.end(), left.rbegin(), left.rend());
  return p;
}

Polygon Spiral(double turns, double width) {
  return Band(
      [&](double t) {
        const double a = t * turns * 2 * M_PI, r = 20 + 60 * t;
        return Point(r * std::cos(a), r * std::sin(a));
      },
      width, 160);
}

Polygon SShape(double amplitude, double width) {
  return Band([&](double t) { return Point(200 * t, amplitude * std::sin(2 * M_PI * t)); }, width, 120);
}

Polygon Comb(int teeth, double bend) {
  // Spine along the bottom, teeth up, each tooth leaning by `bend` (x offset at its tip).
  Polygon p{{0, 0}, {20.0 * teeth, 0}};
  for (int k = teeth - 1; k >= 0; --k) {
    const double x0 = 20.0 * k;
    p.push_back({x0 + 14, 12});
    p.push_back({x0 + 14 + bend, 80});
    p.push_back({x0 + 6 + bend, 80});
    p.push_back({x0 + 6, 12});
  }
  p.push_back({0, 12});
  return p;
}

Polygon DeepC(double opening) {  // a C whose mouth narrows to `opening`
  Polygon p;
  const int n = 90;
  for (int k = 0; k <= n; ++k) {
    const double a = opening + (2 * M_PI - 2 * opening) * k / n;
    p.push_back({100 * std::cos(a), 100 * std::sin(a)});
  }
  for (int k = n; k >= 0; --k) {
    const double a = opening + (2 * M_PI - 2 * opening) * k / n;
    p.push_back({60 * std::cos(a), 60 * std::sin(a)});
  }
  return p;
}

Polygon Transformed(const Polygon& p, double angle, double scale, const Point& shift) {
  Polygon out;
  const double c = std::cos(angle), s = std::sin(angle);
  for (const Point& q : p) out.push_back(Point(c * q.x() - s * q.y(), s * q.x() + c * q.y()) * scale + shift);
  return out;
}

pb::RigDescription OutlineRig(const std::vector<Polygon>& outlines) {
  pb::RigDescription rig;
  rig.file = "corpus.json";
  for (std::size_t i = 0; i < outlines.size(); ++i) {
    pb::PoseDescription pose;
    pose.name = "pose" + std::to_string(i);
    pose.point = Point(std::cos(2.0 * M_PI * i / outlines.size()), std::sin(2.0 * M_PI * i / outlines.size()));
    pose.drawn = true;
    pose.outline = outlines[i];
    pose.landmarks = {outlines[i][0]};
    rig.poses.push_back(pose);
  }
  return rig;
}

// Rig-space polygon -> grid coordinates the exact tests accept (a power-of-two scale).
Polygon OnGrid(const Polygon& p, double scale = 1024) {
  Polygon out;
  for (const Point& q : p) out.push_back(Point(std::nearbyint(q.x() * scale), std::nearbyint(q.y() * scale)));
  return out;
}

double DistanceToPolyline(const Polygon& p, const Point& q) {
  double best = 1e300;
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    const Point a = p[i], b = p[i + 1], ab = b - a;
    const double t = std::clamp((q - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
    best = std::min(best, (a + t * ab - q).norm());
  }
  return best;
}

Polygon Closed(Polygon p) {
  p.push_back(p.front());
  return p;
}

// Every triangle positive in every pose, one connectivity (shared by
// construction), and the rig bakes. These shapes have no landmarks but the
// start point, and some fold between poses: folds are allowed (and counted).
std::size_t CheckCompatible(pb::RigDescription& rig) {
  for (const auto& pose : rig.poses) {
    REQUIRE(pose.vertices.size() == rig.poses[0].vertices.size());
    for (const auto& t : rig.triangles)
      REQUIRE(posemorph::test::Orient(pose.vertices[t[0]], pose.vertices[t[1]], pose.vertices[t[2]]) > 0);
  }
  rig.parameters.allow_folds = true;
  pb::BakeReport report;
  CHECK_NOTHROW(pb::BakeRig(rig, &report));
  MESSAGE("in-betweens: smallest area ratio " << report.inbetweens.min_area_ratio << ", "
                                              << report.inbetweens.FoldsInHull() << " triangles fold in the hull");
  return report.inbetweens.FoldsInHull();
}

// The area of triangle t in the frame at a pose-space point, from the runtime.
double FrameArea(const posemorph::Rig& rig, const Point& at, std::uint32_t t) {
  std::vector<double> x;
  REQUIRE(pb::EvaluateFrame(rig, at, x));
  const std::uint32_t* v = rig.triangles().data + 3 * t;
  return 0.5 * ((x[2 * v[1]] - x[2 * v[0]]) * (x[2 * v[2] + 1] - x[2 * v[0] + 1]) -
                (x[2 * v[1] + 1] - x[2 * v[0] + 1]) * (x[2 * v[2]] - x[2 * v[0]]));
}

}  // namespace

TEST_CASE("mapping: robustness corpus triangulates compatibly") {
  std::map<std::string, std::vector<Polygon>> corpus;
  for (int n = 2; n <= 8; ++n) {
    std::vector<Polygon> stars;
    for (int i = 0; i < n; ++i) stars.push_back(Star(5 + (n % 3), 100, 30 + 6 * i, 0.15 * i));
    corpus["star x" + std::to_string(n)] = stars;
  }
  corpus["spirals"] = {Spiral(1.2, 8), Spiral(1.5, 7), Spiral(0.9, 9), Spiral(1.7, 6)};
  corpus["thin S"] = {SShape(40, 3), SShape(-30, 3), SShape(5, 4), SShape(60, 2.5)};
  corpus["combs"] = {Comb(6, 0), Comb(6, 12), Comb(6, -10), Comb(6, 5), Comb(6, -4)};
  corpus["deep C"] = {DeepC(0.6), DeepC(0.08), DeepC(1.2)};
  corpus["spiral vs S"] = {Spiral(1.5, 8), SShape(50, 8)};
  int folding = 0, folding_drawn = 0, rescued = 0;
  for (auto& [name, shapes] : corpus) {
    const std::string case_name = name;  // Clang 14 cannot capture a structured binding
    CAPTURE(case_name);
    pb::RigDescription rig = OutlineRig(shapes);
    pb::MappedDrawings mapped;
    REQUIRE_NOTHROW(mapped = pb::MapDrawings(rig));
    const pb::MappingReport& r = mapped.report;
    rig = pb::WithPoseMeshes(rig, pb::DeformPoses(rig, mapped));
    MESSAGE(name << ": " << r.matched_vertices << " matched -> " << r.boundary_vertices << " boundary, "
                 << r.steiner_points << " Steiner, " << r.vertices << " vertices, " << r.triangles
                 << " triangles, min angle " << r.min_angle_degrees << ", " << r.seconds * 1e3 << " ms");
    const bool folds = CheckCompatible(rig) > 0;
    folding += folds;
    if (folds) {
      // Baked from the outlines, the bake maps again when the first mapping folds.
      pb::RigDescription drawn = OutlineRig(shapes);
      drawn.parameters.allow_folds = true;
      drawn.mapping.retry_seconds = 0;  // every retry, however slow the build
      pb::BakeReport report;
      pb::BakeRig(drawn, &report);
      MESSAGE(name << " from its outlines: " << report.mapping.fold_retries << " mapping(s) tried again, "
                   << report.inbetweens.FoldsInHull() << " triangles fold in the hull");
      folding_drawn += report.inbetweens.FoldsInHull() > 0;
      rescued += report.inbetweens.FoldsInHull() == 0;
      // Mapped once (mapping.map_again false), the first mapping is written, folds and all.
      drawn.mapping.map_again = false;
      pb::BakeReport once;
      pb::BakeRig(drawn, &once);
      CHECK(once.mapping.fold_retries == 0);
      CHECK(once.mapping.refined_further_by.empty());
      CHECK(once.mapping.registered_over == 0);
      CHECK(once.inbetweens.FoldsInHull() > 0);
      CHECK(once.vertices == r.vertices);
    }
  }
  MESSAGE(folding << " of " << corpus.size() << " corpus rigs fold in the pose hull (no landmarks but the start) "
                  << "with the first mapping; baked, " << rescued << " of them mapped again fold-free, "
                  << folding_drawn << " still fold");
  CHECK(folding > 0);  // the corpus does exercise the retries
  CHECK(folding_drawn == 0);
}

TEST_CASE("mapping: map_again is read as written, true by default, and a bad value fails naming the key") {
  const std::string base = R"({"posemorph": 1, "poses": [
      {"name": "a", "point": [0, 0], "outline": [[0, 0], [1, 0], [0, 1]], "landmarks": [[0, 0]]},
      {"name": "b", "point": [1, 0], "outline": [[0, 0], [2, 0], [0, 1]], "landmarks": [[0, 0]]}], "mapping": )";
  CHECK(pb::ParseRigDescription(base + "{}}", "r.json", ".").mapping.map_again);
  CHECK(!pb::ParseRigDescription(base + R"({"map_again": false}})", "r.json", ".").mapping.map_again);
  CHECK_THROWS_WITH_AS(pb::ParseRigDescription(base + R"({"map_again": 0}})", "r.json", "."),
                       "r.json: mapping.map_again: expected true or false", pb::BakeError);
}

TEST_CASE("mapping: where no compatible triangulation is found, the first pose's mesh is deformed onto the others") {
  // A spiral against an S needs 5 Steiner points triangulated compatibly;
  // allowed 2, the triangulation fails and registration maps them instead.
  pb::RigDescription rig = OutlineRig({Spiral(1.5, 8), SShape(50, 8)});
  rig.mapping.max_steiner_points = 2;
  pb::MappedDrawings mapped;
  REQUIRE_NOTHROW(mapped = pb::MapDrawings(rig));
  const pb::MappingReport& r = mapped.report;
  CHECK(r.registered == false);  // not asked for: the fallback
  bool said = false;
  for (const std::string& w : r.warnings) {
    MESSAGE(w);
    said = said || (w.find("with at most 2 Steiner points") != std::string::npos &&
                    w.find("mapped instead by deforming the first pose's mesh onto the others") != std::string::npos);
  }
  CHECK(said);
  rig = pb::WithPoseMeshes(rig, pb::DeformPoses(rig, mapped));
  // As good a mesh as the triangulation makes with its 5 Steiner points.
  const pb::MappingReport triangulated = pb::MapDrawings(OutlineRig({Spiral(1.5, 8), SShape(50, 8)})).report;
  MESSAGE("spiral vs S by registration: " << r.vertices << " vertices, min angle " << r.min_angle_degrees
                                          << "; triangulated compatibly: " << triangulated.vertices
                                          << " vertices, min angle " << triangulated.min_angle_degrees);
  CHECK(r.min_angle_degrees >= triangulated.min_angle_degrees);
  CHECK(r.vertices <= triangulated.vertices * 5 / 4);
  CheckCompatible(rig);  // every triangle positive in every pose; it bakes
}

TEST_CASE("bake: an in-between that folds fails the bake, naming the triangle, where, the poses and where to hold it") {
  // A spiral and an S with only their start points as landmarks: half-way
  // between them some triangles turn over.
  pb::RigDescription rig = OutlineRig({Spiral(1.5, 8), SShape(50, 8)});
  rig = pb::WithPoseMeshes(rig, pb::ResolvePoseMeshes(rig));
  pb::RigDescription allowed = rig;
  std::string message;
  try {
    pb::BakeRig(rig);
  } catch (const pb::BakeError& e) {
    message = e.what();
  }
  CAPTURE(message);
  CHECK(message.rfind("corpus.json: the in-betweens fold: ", 0) == 0);
  CHECK(message.find(" triangles turn over (the worst: triangle ") != std::string::npos);
  CHECK(message.find(" of its smallest in a pose) at (") != std::string::npos);
  CHECK(message.find("between 'pose") != std::string::npos);
  CHECK(message.find("a landmark on the outline there would hold it: (") != std::string::npos);
  CHECK(message.find(") in 'pose0'") != std::string::npos);
  CHECK(message.find(") in 'pose1'") != std::string::npos);
  CHECK(message.find("or bake with --allow-folds (bake.allow_folds)") != std::string::npos);
  CHECK(message.find('\n') == std::string::npos);

  // Allowed, it bakes with a warning per fold, and every fold it reports is
  // one: the runtime's frame at that point has the triangle turned over.
  allowed.parameters.allow_folds = true;
  pb::BakeReport report;
  const std::vector<unsigned char> bytes = pb::BakeRig(allowed, &report);
  const pb::InbetweenCheck& check = report.inbetweens;
  REQUIRE(check.FoldsInHull() > 0);
  CHECK(check.min_area_ratio <= check.folds[0].area_ratio);
  CHECK(report.warnings.size() == std::min<std::size_t>(check.folds.size(), 10) + (check.folds.size() > 10));
  CHECK(report.warnings[0].find("corpus.json: the in-betweens fold (allowed): triangle ") == 0);
  posemorph::Rig loaded;
  REQUIRE(posemorph::LoadRig(bytes.data(), bytes.size(), &loaded, nullptr));
  for (const pb::InbetweenFold& f : check.folds) {
    CAPTURE(f.triangle);
    CHECK(f.area_ratio <= 0);
    CHECK(FrameArea(loaded, f.at, f.triangle) <= 0);
  }
  // The poses themselves are fold-free: at every pose point the check's ratio is at least 1.
  for (std::uint32_t i = 0; i < loaded.pose_count(); ++i)
    for (std::uint32_t t = 0; t < loaded.triangle_count(); ++t)
      REQUIRE(FrameArea(loaded, Point(loaded.pose_points()[2 * i], loaded.pose_points()[2 * i + 1]), t) > 0);
}

TEST_CASE(
    "posemorph-bake: a folding rig exits 1 with one line and writes nothing, --allow-folds writes it with warnings, "
    "info lists the folds, and a drawn rig that folds is mapped again until it does not, or until "
    "mapping.retry_seconds") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("posemorph-folds-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path input = dir / "folds.json", output = dir / "folds.pmrig";
  // mapping.retry_seconds 0: every retry, however slow the build (the
  // sanitizers'); a tiny limit: none begun.
  auto write_input = [&](double retry_seconds) {
    std::ofstream f(input);
    f.precision(17);
    f << "{\"posemorph\": 1, \"mapping\": {\"retry_seconds\": " << retry_seconds << "}, \"poses\": [";
    const std::vector<Polygon> shapes = {Spiral(1.5, 8), SShape(50, 8)};
    for (std::size_t i = 0; i < shapes.size(); ++i) {
      f << (i ? ", " : "") << "{\"name\": \"" << (i ? "s" : "spiral") << "\", \"point\": [" << (i ? -1 : 1)
        << ", 0], \"landmarks\": [[" << shapes[i][0].x() << ", " << shapes[i][0].y() << "]], \"outline\": [";
      for (std::size_t k = 0; k < shapes[i].size(); ++k)
        f << (k ? ", " : "") << "[" << shapes[i][k].x() << ", " << shapes[i][k].y() << "]";
      f << "]}";
    }
    f << "]}";
  };
  write_input(1e-9);
  auto run = [](const std::vector<std::string>& args, std::string* out, std::string* err) {
    std::ostringstream o, e;
    const int status = pb::RunBakeCommand(args, o, e);
    *out = o.str();
    *err = e.str();
    return status;
  };
  std::string out, err;
  // Past mapping.retry_seconds no retry is begun: the fold is refused,
  // saying how many retries were left, and nothing is written.
  CHECK(run({input.string(), "-o", output.string()}, &out, &err) == 1);
  CHECK(err.rfind("posemorph-bake: error: " + input.string() + ": the in-betweens fold: ", 0) == 0);
  CHECK(err.find("; mapping again stopped at mapping.retry_seconds (1e-09 s) with 4 of its 4 fold retries untried "
                 "(0 tries them all)\n") != std::string::npos);
  CHECK(std::count(err.begin(), err.end(), '\n') == 1);
  CHECK_FALSE(fs::exists(output));
  // Allowed to fold, the first mapping is written, and the line says so too.
  CHECK(run({input.string(), "-o", output.string(), "--allow-folds"}, &out, &err) == 0);
  CHECK(err.find("posemorph-bake: warning: " + input.string() +
                 ": mapping again stopped at mapping.retry_seconds (1e-09 s) with 4 of its 4 fold retries untried "
                 "(0 tries them all)\n") != std::string::npos);
  fs::remove(output);

  // Drawn (here: outlines), the bake maps the spiral and the S again, coarser,
  // and writes the first fold-free mapping, saying so in one warning.
  write_input(0);
  CHECK(run({input.string(), "-o", output.string()}, &out, &err) == 0);
  CHECK(err.rfind("posemorph-bake: warning: " + input.string() + ": the in-betweens folded (", 0) == 0);
  CHECK(err.find("); mapped again with ") != std::string::npos);
  CHECK(err.find(": fold-free\n") != std::string::npos);
  // And one more: the spiral squeezes its outline too much for any mesh of
  // one layer to keep 10 degrees, which the bake says, with the squeeze.
  INFO(err);
  CHECK(std::count(err.begin(), err.end(), '\n') == 2);
  CHECK(err.find(": the mesh's smallest angle is ") != std::string::npos);
  CHECK(err.find(" degrees, below 10 (half of mapping.min_angle): triangle ") != std::string::npos);
  CHECK(err.find(" squeezes it ") != std::string::npos);
  CHECK(run({"info", output.string()}, &out, &err) == 0);
  CHECK(out.find(" 0 triangles fold in the hull") != std::string::npos);
  fs::remove(output);

  // Its first mapping given as meshes: nothing to map again, so the fold is refused.
  {
    pb::RigDescription rig = pb::ReadRigDescription(input.string());
    pb::RigDescription meshes = pb::WithPoseMeshes(rig, pb::ResolvePoseMeshes(rig));
    std::ofstream(input) << pb::RigDescriptionText(meshes);
  }
  CHECK(run({input.string(), "-o", output.string()}, &out, &err) == 1);
  CAPTURE(err);
  CHECK(err.rfind("posemorph-bake: error: " + input.string() + ": the in-betweens fold: ", 0) == 0);
  CHECK(std::count(err.begin(), err.end(), '\n') == 1);
  CHECK_FALSE(fs::exists(output));
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);  // no temporary left

  CHECK(run({input.string(), "-o", output.string(), "--allow-folds"}, &out, &err) == 0);
  CHECK(fs::exists(output));
  CHECK(err.find("posemorph-bake: warning: " + input.string() + ": the in-betweens fold (allowed): triangle ") == 0);
  CHECK(out.find("in-betweens: ") != std::string::npos);
  CHECK(run({"info", output.string()}, &out, &err) == 0);
  CHECK(out.find("  in-betweens: smallest triangle area -") != std::string::npos);
  CHECK(out.find(" triangles fold in the hull\n    triangle ") != std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("bake: the samples' in-betweens do not fold, and the check samples the hull, every two poses and the paths") {
  for (const std::string name : {"snake", "gingerbread", "worm-line"}) {
    CAPTURE(name);
    pb::RigDescription rig =
        pb::ReadRigDescription(std::string(POSEMORPH_SOURCE_DIR) + "/assets/" + name + "/" + name + ".json");
    pb::BakeReport report;
    const std::vector<unsigned char> bytes = pb::BakeRig(rig, &report);
    const pb::InbetweenCheck& check = report.inbetweens;
    MESSAGE(name << ": " << check.frames << " frames, smallest area ratio " << check.min_area_ratio);
    CHECK(check.folds.empty());
    CHECK(check.min_area_ratio > 0.5);
    CHECK(check.grid == 64);
    posemorph::Rig loaded;
    REQUIRE(posemorph::LoadRig(bytes.data(), bytes.size(), &loaded, nullptr));
    // The smallest ratio is where the check says, measured again from the runtime's frame.
    const std::uint32_t* v = loaded.triangles().data + 3 * check.min_triangle;
    double smallest = 1e300;
    for (std::uint32_t i = 0; i < loaded.pose_count(); ++i) {
      const double* p = loaded.pose_positions(i).data;
      smallest = std::min(smallest, 0.5 * ((p[2 * v[1]] - p[2 * v[0]]) * (p[2 * v[2] + 1] - p[2 * v[0] + 1]) -
                                           (p[2 * v[1] + 1] - p[2 * v[0] + 1]) * (p[2 * v[2]] - p[2 * v[0]])));
    }
    CHECK(FrameArea(loaded, check.min_at, check.min_triangle) / smallest ==
          doctest::Approx(check.min_area_ratio).epsilon(1e-12));
    // Samples: pose points, hull edges and grid, the segment between every two poses, every path.
    pb::PoseSpaceSampling sampling;
    sampling.grid = sampling.per_edge = sampling.per_pair = 64;
    const std::vector<pb::PoseSpaceSample> samples = pb::SamplePoseSpace(loaded, sampling);
    CHECK(check.frames == samples.size());
    const std::size_t N = loaded.pose_count();
    std::size_t pairs = 0, on_paths = 0;
    for (const pb::PoseSpaceSample& s : samples) on_paths += s.path >= 0;
    pairs = N * (N - 1) / 2 * 63;
    CHECK(on_paths == 201 * loaded.path_count());
    CHECK(samples.size() >= N + pairs + on_paths);
    // A smaller budget (3e4 vertex-frames) shrinks every part of the sampling; still no fold.
    const pb::InbetweenCheck small = pb::CheckInbetweens(loaded, name, 3e4);
    MESSAGE(name << " within 3e4 vertex-frames: grid " << small.grid << ", " << small.frames << " frames, smallest "
                 << small.min_area_ratio);
    CHECK(small.grid < 64);
    CHECK((double(small.frames) * loaded.vertex_count() <= 3e4 || small.grid == 2));
    CHECK(small.folds.empty());
    CHECK(small.min_area_ratio >= check.min_area_ratio);
  }
}

TEST_CASE("mapping: every stage keeps its promise on the corpus") {
  // Enclosure, simplicity, and landmarks mapping to one shared vertex.
  const std::vector<std::vector<Polygon>> cases = {
      {Star(6, 100, 35, 0), Star(6, 90, 50, 0.3), Star(6, 120, 25, -0.2)},
      {Comb(5, 0), Comb(5, 14), Comb(5, -9)},
      {DeepC(0.3), DeepC(0.1), DeepC(0.9)},
      {SShape(40, 4), SShape(-35, 3)},
  };
  for (const auto& shapes : cases) {
    std::vector<std::vector<Point>> landmarks;
    std::vector<std::string> labels;
    for (std::size_t i = 0; i < shapes.size(); ++i) {
      landmarks.push_back({shapes[i][0], shapes[i][shapes[i].size() / 2]});
      labels.push_back("pose " + std::to_string(i));
    }
    pb::MappingParameters prm;
    const pm::MappingStages st = pm::MapPolygons(shapes, landmarks, {}, prm, labels, "corpus");
    const double tol = st.sizes.simplify_tolerance * st.grid_scale;
    for (std::size_t i = 0; i < shapes.size(); ++i) {
      CAPTURE(i);
      const Polygon& q = st.simplified.polygons[i];
      CHECK(pm::IsSimplePolygon(q));
      CHECK(pm::SignedArea(q) > 0);
      CHECK(pm::Encloses(q, st.outlines[i]));
      for (const Point& p : st.outlines[i]) REQUIRE(pm::PointInPolygon(q, p) >= 0);
      // No polygon point strays further than the tolerance from the outline.
      for (const Point& p : q) CHECK(DistanceToPolyline(Closed(st.outlines[i]), p) <= tol * 1.5 + 4);
      // Landmark k is vertex simplified.landmarks[k] in every pose, near where the user put it.
      for (std::size_t k = 0; k < landmarks[i].size(); ++k)
        CHECK((q[st.simplified.landmarks[k]] - st.landmarks[i][k]).norm() <= tol + 4);
    }
    REQUIRE(st.simplified.landmarks.size() == 2);
  }
}

TEST_CASE("mapping: a polygon's self-crossing edges are named exactly") {
  // The enclosing simplification splits the spans of these edges when its
  // outward pushes made them cross each other.
  using V = std::vector<std::size_t>;
  const Polygon square = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  CHECK(pm::SelfCrossingEdges(square).empty());
  CHECK(pm::IsSimplePolygon(square));
  // A bow tie: edges 0 (0,0)-(10,10) and 2 (10,0)-(0,10) cross.
  CHECK(pm::SelfCrossingEdges({{0, 0}, {10, 10}, {10, 0}, {0, 10}}) == V{0, 2});
  // Two edges pushed down through a notch's two sides: 5 meets 2, 6 meets 1.
  const Polygon notch = {{0, 0}, {4, 0}, {5, 8}, {6, 0}, {10, 0}, {10, 10}, {5, -2}, {0, 10}};
  CHECK(pm::SelfCrossingEdges(notch) == V{1, 2, 5, 6});
  CHECK_FALSE(pm::IsSimplePolygon(notch));
  // A spike folding back onto its neighbour (and so ending on edge 0, where
  // edge 2 starts), and an edge of no length (its neighbours 0 and 2 touch).
  CHECK(pm::SelfCrossingEdges({{0, 0}, {10, 0}, {5, 0}, {5, 5}}) == V{0, 1, 2});
  CHECK(pm::SelfCrossingEdges({{0, 0}, {10, 0}, {10, 0}, {0, 10}}) == V{0, 1, 2});
}

TEST_CASE("mapping: matching a shape to its own rotated, scaled copy is the identity") {
  Polygon blob;
  for (int k = 0; k < 400; ++k) {
    const double t = 2 * M_PI * k / 400, r = 60 + 15 * std::sin(3 * t) + 8 * std::cos(5 * t);
    blob.push_back({r * std::cos(t), r * std::sin(t)});
  }
  const double angle = 0.7, scale = 1.6;
  const Point shift(30, -20);
  Polygon copy = Transformed(blob, angle, scale, shift);
  std::rotate(copy.begin(), copy.begin() + 137, copy.end());  // its vertex 0 is elsewhere
  auto back = [&](const Point& p) {
    const Point q = (p - shift) / scale;
    return Point(std::cos(-angle) * q.x() - std::sin(-angle) * q.y(),
                 std::sin(-angle) * q.x() + std::cos(-angle) * q.y());
  };
  const std::vector<std::vector<Point>> landmarks = {
      {blob[10], blob[150]},
      {Transformed({blob[10]}, angle, scale, shift)[0], Transformed({blob[150]}, angle, scale, shift)[0]}};
  pm::MatchingParameters prm;
  prm.spacing = 1.0;
  const pm::CorrespondedBoundary m = pm::MatchBoundaries({blob, copy}, landmarks, prm);
  REQUIRE(m.points[0].size() == m.points[1].size());
  REQUIRE(m.points[0].size() > 300);
  double worst = 0;
  for (std::size_t j = 0; j < m.points[0].size(); ++j)
    worst = std::max(worst, (back(m.points[1][j]) - m.points[0][j]).norm());
  MESSAGE("identity matching: worst distance " << worst << " (sample spacing " << prm.spacing << ")");
  CHECK(worst <= 1e-6);
  // The user's points map exactly onto each other.
  for (std::size_t k = 0; k < 2; ++k) {
    CHECK((m.points[0][m.landmarks[k]] - landmarks[0][k]).norm() <= 1e-9);
    CHECK((m.points[1][m.landmarks[k]] - landmarks[1][k]).norm() <= 1e-9);
  }
}

TEST_CASE("mapping: a smoothed correspondence spreads a squeeze, keeps the landmarks and an identity") {
  // Pose 1 grows a bump that pose 0 lacks: matching by bending alone gives
  // the bump's many samples to few of pose 0's, a squeeze a triangle at that
  // boundary cannot survive in both poses.
  auto blob = [](double bump) {
    Polygon p;
    for (int k = 0; k < 400; ++k) {
      const double t = 2 * M_PI * k / 400, d = (t - 1.0) / 0.12;
      const double r = 60 + 15 * std::sin(3 * t) + 8 * std::cos(5 * t) + bump * std::exp(-d * d);
      p.push_back({r * std::cos(t), r * std::sin(t)});
    }
    return p;
  };
  const Polygon plain = blob(0), bumped = blob(25);
  const std::vector<std::vector<Point>> landmarks = {{plain[0], plain[200]}, {bumped[0], bumped[200]}};
  // The largest ratio of a matched step's length in one pose to the other's, either way.
  auto squeeze = [](const pm::CorrespondedBoundary& m) {
    double worst = 1;
    const std::size_t M = m.points[0].size();
    for (std::size_t j = 0; j < M; ++j) {
      const double a = (m.points[0][(j + 1) % M] - m.points[0][j]).norm();
      const double b = (m.points[1][(j + 1) % M] - m.points[1][j]).norm();
      if (a > 1e-9 && b > 1e-9) worst = std::max({worst, a / b, b / a});
    }
    return worst;
  };
  pm::MatchingParameters prm;
  prm.spacing = 1.0;
  const pm::CorrespondedBoundary as_matched = pm::MatchBoundaries({plain, bumped}, landmarks, prm);
  prm.smoothing = 12;
  const pm::CorrespondedBoundary smoothed = pm::MatchBoundaries({plain, bumped}, landmarks, prm);
  MESSAGE("squeeze as matched " << squeeze(as_matched) << ", smoothed over 12 samples " << squeeze(smoothed));
  CHECK(squeeze(as_matched) > 3);
  CHECK(squeeze(smoothed) < squeeze(as_matched) / 2);
  for (std::size_t k = 0; k < 2; ++k)
    for (std::size_t i = 0; i < 2; ++i)
      CHECK((smoothed.points[i][smoothed.landmarks[k]] - landmarks[i][k]).norm() <= 1e-9);
  // Every matched point still on its outline, in order round it.
  for (std::size_t j = 0; j + 1 < smoothed.at[1].size(); ++j) CHECK(smoothed.at[1][j] < smoothed.at[1][j + 1]);
  // Smoothing an identity matching changes it by roundoff alone.
  const Polygon copy = Transformed(plain, 0.4, 1.3, Point(3, 4));
  const pm::CorrespondedBoundary same =
      pm::MatchBoundaries({plain, copy}, {{plain[0], plain[200]}, {copy[0], copy[200]}}, prm);
  double worst = 0;
  for (std::size_t j = 0; j < same.points[0].size(); ++j)
    worst = std::max(worst, (Transformed({same.points[0][j]}, 0.4, 1.3, Point(3, 4))[0] - same.points[1][j]).norm());
  CHECK(worst <= 1e-6);
}

TEST_CASE("mapping: the matching's work is bounded on long outlines, unchanged on short ones") {
  // A 40,000-unit square matched at spacing 1 would need 40,000^2 steps per
  // span: it gets at most kMaxMatchedSamples samples instead, identity still.
  const Polygon big = {{0, 0}, {10000, 0}, {10000, 10000}, {0, 10000}};
  const Polygon twin = Transformed(big, 0.3, 1.2, Point(5, 7));
  pm::MatchingParameters prm;
  prm.spacing = 1.0;
  const pm::CorrespondedBoundary m = pm::MatchBoundaries({big, twin}, {{big[0]}, {twin[0]}}, prm);
  CHECK(m.spacing == doctest::Approx(40000.0 / double(pm::kMaxMatchedSamples)));
  CHECK(m.points[0].size() <= 2 * pm::kMaxMatchedSamples);
  CHECK(m.points[0].size() >= pm::kMaxMatchedSamples / 2);
  double worst = 0;
  for (std::size_t j = 0; j < m.points[0].size(); ++j)
    worst = std::max(worst, (Transformed({m.points[0][j]}, 0.3, 1.2, Point(5, 7))[0] - m.points[1][j]).norm());
  CHECK(worst <= 1e-6 * 12000);
  // A short outline keeps the spacing it was given.
  const Polygon small = {{0, 0}, {100, 0}, {100, 100}, {0, 100}};
  const pm::CorrespondedBoundary s = pm::MatchBoundaries({small, small}, {{small[0]}, {small[0]}}, prm);
  CHECK(s.spacing == 1.0);
  CHECK(s.points[0].size() == 400);
}

TEST_CASE("mapping: refinement stops at its vertex budget and says so") {
  // Grid coordinates (the mapping refines on its integer grid).
  const Polygon square = {{0, 0}, {400000, 0}, {400000, 400000}, {0, 400000}};
  pm::CompatibleMesh mesh = pm::TriangulateCompatibly({square, square}, "squares", 0);
  pm::RefinementParameters rp;
  rp.max_edge_length = 5000;  // about 7,000 vertices
  rp.max_vertices = 2000;
  pm::CompatibleMesh budgeted = mesh;
  CHECK_FALSE(pm::RefineCompatibly(budgeted, rp));
  CHECK(budgeted.vertices[0].size() <= rp.max_vertices);
  rp.max_edge_length = 80000;
  CHECK(pm::RefineCompatibly(mesh, rp));
  CHECK(mesh.vertices[0].size() < rp.max_vertices);
}

TEST_CASE("mapping: the splits for the angle goal stop at max_angle_vertices, the splits for length do not") {
  // A square against a flat, sheared quadrilateral: no mesh keeps 20
  // degrees in both, so the rounds split as much as they may.
  const Polygon square = {{0, 0}, {400000, 0}, {400000, 400000}, {0, 400000}};
  const Polygon sheared = {{0, 0}, {400000, 0}, {1400000, 60000}, {1000000, 60000}};
  const pm::CompatibleMesh start = pm::TriangulateCompatibly({square, sheared}, "square and sheared", 0);
  pm::RefinementParameters rp;
  pm::CompatibleMesh free = start;
  REQUIRE(pm::RefineCompatibly(free, rp));
  const std::size_t unbounded = free.vertices[0].size();
  MESSAGE("the angle goal alone: " << unbounded << " vertices, " << pm::MinAngleDegrees(free) << " degrees");
  REQUIRE(unbounded > 12);
  rp.max_angle_vertices = 12;
  pm::CompatibleMesh bounded = start;
  REQUIRE(pm::RefineCompatibly(bounded, rp));
  CHECK(bounded.vertices[0].size() <= 12);
  CHECK(bounded.vertices[0].size() > start.vertices[0].size());  // it split up to the bound
  // Splitting for length is not bounded by it: its vertices stay, and the
  // angle splits stop there.
  rp.max_edge_length = 40000;
  pm::CompatibleMesh long_split = start;
  REQUIRE(pm::RefineCompatibly(long_split, rp));
  CHECK(long_split.vertices[0].size() > 100);
}

namespace {
// Whether p lies in (or on) some triangle of the mesh in pose k.
bool Covered(const pm::CompatibleMesh& mesh, std::size_t k, const Point& p) {
  const Polygon& v = mesh.vertices[k];
  for (const auto& t : mesh.triangles) {
    auto side = [&](const Point& a, const Point& b) { return (b - a).x() * (p - a).y() - (b - a).y() * (p - a).x(); };
    if (side(v[t[0]], v[t[1]]) >= 0 && side(v[t[1]], v[t[2]]) >= 0 && side(v[t[2]], v[t[0]]) >= 0) return true;
  }
  return false;
}
}  // namespace

TEST_CASE("mapping: refinement removes a boundary vertex whose short edge makes a sliver, and only grows the mesh") {
  // A 4000 x 2000 box (grid units) whose bottom has two more vertices: in
  // pose 0 on the straight edge 400 apart, in pose 1 pushed in by 100 and
  // 20 apart (a squeeze: both are reflex corners there), so the triangle on
  // that 20-unit edge is a sliver in pose 1 that no split lifts.
  const Polygon rest = {{0, 0}, {1800, 0}, {2200, 0}, {4000, 0}, {4000, 2000}, {0, 2000}};
  const Polygon squeezed = {{0, 0}, {1990, 100}, {2010, 100}, {4000, 0}, {4000, 2000}, {0, 2000}};
  const pm::CompatibleMesh first = pm::TriangulateCompatibly({rest, squeezed}, "squeezed box", 0);
  pm::RefinementParameters rp;
  rp.max_edge_length = 500;
  rp.max_collapse_distance = 200;
  pm::CompatibleMesh split = first, collapsed = first;
  REQUIRE(pm::RefineCompatibly(split, rp));
  rp.collapse_slivers = true;
  REQUIRE(pm::RefineCompatibly(collapsed, rp));
  const double split_angle = pm::MinAngleDegrees(split), collapsed_angle = pm::MinAngleDegrees(collapsed);
  INFO("min angle " << split_angle << " split only, " << collapsed_angle << " with slivers removed; vertices "
                    << split.vertices[0].size() << ", " << collapsed.vertices[0].size());
  CHECK(split_angle < 10);
  CHECK(collapsed_angle > split_angle + 5);
  // Every triangle keeps its orientation in both poses, and the mesh still
  // covers both outlines (removing a reflex corner only adds area).
  for (std::size_t k = 0; k < 2; ++k) {
    for (const auto& t : collapsed.triangles) {
      const Polygon& v = collapsed.vertices[k];
      CHECK((v[t[1]] - v[t[0]]).x() * (v[t[2]] - v[t[0]]).y() - (v[t[1]] - v[t[0]]).y() * (v[t[2]] - v[t[0]]).x() > 0);
    }
    for (const Point& p : k == 0 ? rest : squeezed) CHECK(Covered(collapsed, k, p));
    // Midpoints of the outline's edges too.
    const Polygon& o = k == 0 ? rest : squeezed;
    for (std::size_t i = 0; i < o.size(); ++i) CHECK(Covered(collapsed, k, (o[i] + o[(i + 1) % o.size()]) / 2));
  }
  CHECK(collapsed.features.empty());
  CHECK(collapsed.vertices[0].size() == collapsed.vertices[1].size());
}

TEST_CASE("mapping: the refinement's runs give the same mesh on one thread or several") {
  // The squeezed box: below the quality floor after the usual rounds, so the
  // graded runs run too, and with slivers removed, the run without as well.
  const Polygon rest = {{0, 0}, {1800, 0}, {2200, 0}, {4000, 0}, {4000, 2000}, {0, 2000}};
  const Polygon squeezed = {{0, 0}, {1990, 100}, {2010, 100}, {4000, 0}, {4000, 2000}, {0, 2000}};
  const pm::CompatibleMesh first = pm::TriangulateCompatibly({rest, squeezed}, "squeezed box", 0);
  for (bool collapse : {false, true}) {
    pm::RefinementParameters rp;
    rp.max_edge_length = 500;
    rp.max_collapse_distance = 200;
    rp.collapse_slivers = collapse;
    rp.threads = 1;
    pm::CompatibleMesh one = first;
    REQUIRE(pm::RefineCompatibly(one, rp));
    if (!collapse) REQUIRE(pm::MinAngleDegrees(one) < rp.min_angle_goal / 2);  // graded: below the floor
    for (unsigned threads : {2u, 3u, 8u, 0u}) {
      rp.threads = threads;
      pm::CompatibleMesh many = first;
      REQUIRE(pm::RefineCompatibly(many, rp));
      INFO("collapse " << collapse << ", threads " << threads);
      CHECK(many.triangles == one.triangles);
      CHECK(many.vertices == one.vertices);  // exact: the same bits
      CHECK(many.features == one.features);
    }
  }
}

TEST_CASE("mapping: refinement never removes a convex corner, which would uncover the outline") {
  // The same squeeze pushed out instead: the two close vertices are convex
  // corners in pose 1, so the refinement keeps them whatever the sliver.
  const Polygon rest = {{0, 0}, {1800, 0}, {2200, 0}, {4000, 0}, {4000, 2000}, {0, 2000}};
  const Polygon squeezed = {{0, 0}, {1990, -100}, {2010, -100}, {4000, 0}, {4000, 2000}, {0, 2000}};
  pm::CompatibleMesh split = pm::TriangulateCompatibly({rest, squeezed}, "pushed-out box", 0);
  pm::CompatibleMesh collapsed = split;
  pm::RefinementParameters rp;
  rp.max_edge_length = 500;
  rp.max_collapse_distance = 200;
  REQUIRE(pm::RefineCompatibly(split, rp));
  rp.collapse_slivers = true;
  REQUIRE(pm::RefineCompatibly(collapsed, rp));
  for (const Point& p : squeezed) CHECK(Covered(collapsed, 1, p));
  CHECK(pm::MinAngleDegrees(collapsed) == pm::MinAngleDegrees(split));
  CHECK(collapsed.vertices[0].size() == split.vertices[0].size());
}

TEST_CASE("mapping: outline limits name the pose and the limit") {
  Polygon many;
  for (std::size_t k = 0; k <= pm::kMaxOutlinePoints; ++k) {
    const double t = 2 * M_PI * double(k) / double(pm::kMaxOutlinePoints + 1);
    many.push_back({1000 * std::cos(t), 1000 * std::sin(t)});
  }
  pb::MappingParameters prm;
  try {
    pm::MapPolygons({many, many}, {{many[0]}, {many[0]}}, {}, prm, {"pose 'a'", "pose 'b'"}, "limits.json");
    FAIL("an outline over the limit was mapped");
  } catch (const pb::BakeError& e) {
    CHECK(std::string(e.what()) ==
          "limits.json: pose 'a': the outline has 100001 points, more than the limit of 100000");
  }
  const Polygon square = {{0, 0}, {40, 0}, {40, 40}, {0, 40}};
  std::vector<Point> landmarks;
  for (std::size_t k = 0; k <= pm::kMaxLandmarks; ++k)
    landmarks.push_back({40.0 * double(k) / double(pm::kMaxLandmarks + 1), 0});
  try {
    pm::MapPolygons({square, square}, {landmarks, landmarks}, {}, prm, {"pose 'a'", "pose 'b'"}, "limits.json");
    FAIL("landmarks over the limit were mapped");
  } catch (const pb::BakeError& e) {
    CHECK(std::string(e.what()) == "limits.json: pose 'a': gives 513 landmarks, more than the limit of 512");
  }
}

TEST_CASE("mapping: outlines from alpha") {
  const int W = 64, H = 64;
  std::vector<unsigned char> alpha(W * H, 0);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const double d = std::hypot(x + 0.5 - 32, y + 0.5 - 32);
      double a = std::clamp(20.5 - d, 0.0, 1.0);  // anti-aliased disk of radius 20
      if (d < 5) a = 0;                           // a hole
      alpha[y * W + x] = (unsigned char)std::lround(a * 255);
    }
  for (int y = 1; y < 4; ++y)
    for (int x = 1; x < 4; ++x) alpha[y * W + x] = 255;  // a speck
  const pm::ImageOutline io = pm::OutlineFromAlpha(alpha, W, H, 0.5, "disk.png");
  CHECK(io.dropped_components == 1);
  CHECK(io.dropped_pixels == 9);
  CHECK(io.filled_hole_pixels >= 70);
  CHECK(pm::IsSimplePolygon(OnGrid(io.outline)));
  CHECK(std::abs(std::abs(pm::SignedArea(io.outline)) - M_PI * 400) < 0.02 * M_PI * 400);
  for (const Point& p : io.outline) CHECK(std::abs((p - Point(32, 32)).norm() - 20) < 0.75);

  // Two blocks meeting only at a corner, and a one-pixel line: still one simple curve.
  std::fill(alpha.begin(), alpha.end(), 0);
  for (int y = 10; y < 20; ++y)
    for (int x = 10; x < 20; ++x) alpha[y * W + x] = alpha[(y + 10) * W + x + 10] = 255;
  for (int x = 30; x < 60; ++x) alpha[25 * W + x] = 255;
  const pm::ImageOutline pinch = pm::OutlineFromAlpha(alpha, W, H, 0.5, "pinch.png");
  CHECK(pm::IsSimplePolygon(OnGrid(pinch.outline)));
  double max_x = 0;
  for (const Point& p : pinch.outline) max_x = std::max(max_x, p.x());
  CHECK(max_x > 59);  // the thin line is part of the shape

  std::fill(alpha.begin(), alpha.end(), 10);
  CHECK_THROWS_WITH_AS(pm::OutlineFromAlpha(alpha, W, H, 0.5, "clear.png"),
                       doctest::Contains("clear.png: image is empty or fully transparent"), pb::BakeError);
}

TEST_CASE("mapping: a faint pixel's notch in a PNG outline is filled when asked, and the outline only grows") {
  // A block whose top row has a pixel just below the threshold with opaque
  // pixels on three sides (as pixel art has): the border dips to within
  // 0.04 px of that pixel's centre, a notch a hundredth of a pixel wide.
  const int W = 24, H = 24;
  std::vector<unsigned char> alpha(W * H, 0);
  for (int y = 4; y < 20; ++y)
    for (int x = 4; x < 20; ++x) alpha[y * W + x] = 255;
  alpha[4 * W + 11] = 122;  // just below 0.5
  const Point centre(11.5, 4.5);
  const pm::ImageOutline as_traced = pm::OutlineFromAlpha(alpha, W, H, 0.5, "notch.png");
  const pm::ImageOutline filled = pm::OutlineFromAlpha(alpha, W, H, 0.5, "notch.png", true);
  // The thinnest concave corner: twice its triangle's area over its longest side.
  auto thinnest = [](const Polygon& outline) {
    const double orientation = pm::SignedArea(outline) > 0 ? 1 : -1;
    double least = 1e9;
    for (std::size_t i = 0, n = outline.size(); i < n; ++i) {
      const Point &a = outline[(i + n - 1) % n], &v = outline[i], &b = outline[(i + 1) % n];
      const double twice = orientation * ((v - a).x() * (b - v).y() - (v - a).y() * (b - v).x());
      if (twice < 0) least = std::min(least, -twice / std::max({(v - a).norm(), (b - v).norm(), (b - a).norm()}));
    }
    return least;
  };
  double dip = 1e9;
  for (const Point& p : as_traced.outline) dip = std::min(dip, (p - centre).norm());
  CHECK(dip < 0.05);  // the border dips to the faint pixel's centre
  CHECK(as_traced.filled_notch_corners == 0);
  CHECK(thinnest(as_traced.outline) < 1.0 / 16);  // a sliver of a notch
  CHECK(filled.filled_notch_corners > 0);
  CHECK(thinnest(filled.outline) >= 1.0 / 16);  // filled: what is left of the notch is a plain V
  CHECK(filled.outline.size() + filled.filled_notch_corners == as_traced.outline.size());
  CHECK(pm::IsSimplePolygon(OnGrid(filled.outline)));
  // Filling only adds: every traced point is inside or on the filled outline.
  Polygon outer = filled.outline;
  if (pm::SignedArea(outer) < 0) std::reverse(outer.begin(), outer.end());
  for (const Point& p : as_traced.outline) CHECK(pm::PointInPolygon(OnGrid(outer), OnGrid({p})[0]) >= 0);
  CHECK(std::abs(pm::SignedArea(filled.outline)) >= std::abs(pm::SignedArea(as_traced.outline)));
  // A shape without thin notches is traced the same either way.
  alpha[4 * W + 11] = 255;
  CHECK(pm::OutlineFromAlpha(alpha, W, H, 0.5, "block.png", true).outline ==
        pm::OutlineFromAlpha(alpha, W, H, 0.5, "block.png").outline);
}

TEST_CASE("mapping: SVG outlines") {
  const Polygon square = pm::FlattenSvgPath("M 10 10 h 20 v 20 H 10 Z", 0.1, "t.svg");
  REQUIRE(square.size() == 4);
  CHECK(square[2] == Point(30, 30));
  CHECK(pm::FlattenSvgPath("m 10 10 l 20 0 l 0 20 l -20 0 z", 0.1, "t.svg") == square);
  CHECK(pm::FlattenSvgPath("M10,10 30,10 30,30 10,30z", 0.1, "t.svg") == square);  // implicit lines

  // Curves: every point of the true curve within the tolerance of the polygon.
  for (const double tol : {0.5, 0.05}) {
    const Polygon cubic = pm::FlattenSvgPath("M 0 0 C 0 50 100 50 100 0 Z", tol, "c.svg");
    const Polygon quad = pm::FlattenSvgPath("M 0 0 Q 50 100 100 0 z", tol, "q.svg");
    double worst_c = 0, worst_q = 0;
    for (int k = 0; k <= 1000; ++k) {
      const double t = k / 1000.0, u = 1 - t;
      const Point c = 3 * u * u * t * Point(0, 50) + 3 * u * t * t * Point(100, 50) + t * t * t * Point(100, 0);
      const Point q = 2 * u * t * Point(50, 100) + t * t * Point(100, 0);
      worst_c = std::max(worst_c, DistanceToPolyline(cubic, c));
      worst_q = std::max(worst_q, DistanceToPolyline(quad, q));
    }
    CHECK(worst_c <= tol);
    CHECK(worst_q <= tol);
    CHECK(cubic.size() < std::size_t(60 / std::sqrt(tol)));
  }

  const pm::SvgOutline so = pm::OutlineFromSvgText(
      R"svg(<svg xmlns="http://www.w3.org/2000/svg" viewBox="5 6 200 100">
           <path d="M 0 0 L 1 0 L 1 1 Z"/>
           <g><polygon id="outline" points="10,10 50,10 50,40"/></g></svg>)svg",
      0.1, "p.svg");
  CHECK(so.outline == Polygon{{10, 10}, {50, 10}, {50, 40}});
  CHECK(so.canvas_origin == Point(5, 6));
  CHECK(so.canvas_size == Point(200, 100));
  CHECK_THROWS_WITH_AS(
      pm::OutlineFromSvgText(R"svg(<svg width="9" height="9"><path d="M 0 0 A 5 5 0 0 1 9 9 Z"/></svg>)svg", 0.1,
                             "a.svg"),
      doctest::Contains("a.svg: path data: arcs (A) are not supported"), pb::BakeError);
  CHECK_THROWS_WITH_AS(
      pm::OutlineFromSvgText(
          R"svg(<svg width="9" height="9"><path transform="scale(2)" d="M 0 0 L 9 0 L 9 9 Z"/></svg>)svg", 0.1,
          "t.svg"),
      doctest::Contains("has a transform"), pb::BakeError);
  // A fuzz finding: a curve to y = 1e308 flattened to infinite points.
  CHECK_THROWS_WITH_AS(
      pm::OutlineFromSvgText(
          R"svg(<svg viewBox="0 0 6 64"><path d="M 10 0 C 2 40 0 50 410 1e308V10 l 1 1 z"/></svg>)svg", 0.25,
          "big.svg"),
      doctest::Contains("big.svg: path data: the number at character 23 lies beyond +-1e9 drawing units"),
      pb::BakeError);
  CHECK_THROWS_WITH_AS(pm::OutlineFromSvgText("<svg", 0.1, "x.svg"), doctest::Contains("x.svg: invalid SVG"),
                       pb::BakeError);
}

namespace {

struct SampleFigures {
  std::string name;
  std::size_t max_boundary;  // reached: see docs/DESIGN.md
  double min_angle;          // reached by refinement
  double aligned_min_angle;  // reached after the interior alignment
  std::size_t max_steiner;
};

}  // namespace

TEST_CASE("mapping: the drawn samples map with the quality reached") {
  for (const SampleFigures& f : {SampleFigures{"pip", 62, 10.4, 10.4, 1}, SampleFigures{"sprout", 72, 8.9, 8.9, 1}}) {
    CAPTURE(f.name);
    const std::string dir = std::string(POSEMORPH_DRAWN_SAMPLES) + "/" + f.name;
    REQUIRE_MESSAGE(std::filesystem::exists(dir + "/rest.png"), "the build rasterises the drawings (rsvg-convert)");
    pb::RigDescription rig = pb::ReadRigDescription(dir + "/" + f.name + ".json");
    const pb::MappedDrawings mapped = pb::MapDrawings(rig);
    const pb::MappingReport& r = mapped.report;
    rig = pb::WithPoseMeshes(rig, pb::DeformPoses(rig, mapped));
    MESSAGE(f.name << ": outlines " << r.outline_vertices[0] << ".. vertices, " << r.matched_vertices << " matched -> "
                   << r.boundary_vertices << " boundary, " << r.steiner_points << " Steiner, " << r.vertices
                   << " vertices, " << r.triangles << " triangles, min angle " << r.min_angle_degrees);
    CHECK(r.boundary_vertices <= f.max_boundary);
    CHECK(r.steiner_points <= f.max_steiner);
    CHECK(r.aligned);
    CHECK(r.min_angle_before_alignment >= f.min_angle);
    CHECK(r.min_angle_degrees >= f.aligned_min_angle);
    CHECK(r.min_angle_degrees >= std::min(r.min_angle_before_alignment, 10.0) - 1e-9);  // the alignment's own floor
    CheckCompatible(rig);

    // Each pose's mesh covers every pixel of its own drawing's shape (the
    // anti-aliased fringe down to the threshold), seen through its uvs.
    for (const pb::PoseDescription& pose : rig.poses) {
      CAPTURE(pose.name);
      REQUIRE(pose.uvs.size() == pose.vertices.size());
      const posemorph::test::DrawingCoverage c =
          posemorph::test::CoverageOf(pose.uvs, rig.triangles, dir + "/" + pose.image, rig.mapping.alpha_threshold);
      MESSAGE(f.name << " " << pose.name << ": alpha outside the mesh " << 100 * c.alpha_outside_share << "%");
      CHECK(c.opaque > 5000);
      CHECK(c.shape_uncovered == 0);         // every pixel at or above the threshold is meshed
      CHECK(c.alpha_outside_share < 0.001);  // the fringe below it is nearly nothing
    }
  }
}

namespace {
// y up; a body 40 x 60 with a head, and an arm 8 wide from the shoulder:
// hanging down 2 units from the body (squeezed against it), and raised
// beside the head (turned 180 degrees).
Polygon ArmHangingFigure() {
  return {{0, 0},   {40, 0},  {40, 50}, {42, 50}, {42, 26}, {50, 26}, {50, 58},
          {40, 58}, {40, 60}, {32, 60}, {32, 84}, {8, 84},  {8, 60},  {0, 60}};
}
Polygon ArmRaisedFigure() {
  return {{0, 0},   {40, 0},  {40, 50}, {50, 50}, {50, 90}, {42, 90}, {42, 58},
          {40, 58}, {40, 60}, {32, 60}, {32, 84}, {8, 84},  {8, 60},  {0, 60}};
}
}  // namespace

TEST_CASE("mapping: an arm raised over the head is matched to the arm, its tip to its tip when stretch is resisted") {
  // The figure hanging its arm, raising it and holding it out sideways (90
  // degrees). Only the start point is a landmark.
  const Polygon down = ArmHangingFigure();
  const Polygon up = ArmRaisedFigure();
  const Polygon out = {{0, 0},   {40, 0},  {40, 50}, {74, 50}, {74, 58}, {40, 58},
                       {40, 60}, {32, 60}, {32, 84}, {8, 84},  {8, 60},  {0, 60}};
  const Point hanging_tip(46, 26);
  struct Case {
    const char* name;
    Polygon outline;
    Point tip;
    double stretch_cost, tip_within;
  };
  // Matched by bends alone, a 180-degree turn is ambiguous with a 90-degree
  // one (the shoulder's corners change their turn): the tip lands on the
  // arm's side a corner off (6.0 px). Resisting stretch, the sides keep
  // their lengths and the tip lands on the tip.
  for (const Case& c : {Case{"raised", up, Point(46, 90), 0.05, 8}, Case{"raised", up, Point(46, 90), 0.2, 1},
                        Case{"held out", out, Point(74, 54), 0.05, 1}, Case{"held out", out, Point(74, 54), 0.2, 1}}) {
    const std::string name = c.name;
    CAPTURE(name);
    CAPTURE(c.stretch_cost);
    pm::MatchingParameters prm;
    prm.spacing = 1.0;
    prm.stretch_cost = c.stretch_cost;
    const pm::CorrespondedBoundary m = pm::MatchBoundaries({down, c.outline}, {{Point(20, 0)}, {Point(20, 0)}}, prm);
    std::size_t tip = 0, on_arm = 0, arm = 0;
    for (std::size_t j = 0; j < m.points[0].size(); ++j) {
      const Point& p = m.points[0][j];
      if ((p - hanging_tip).norm() < (m.points[0][tip] - hanging_tip).norm()) tip = j;
      if (p.x() > 41.9 && p.y() < 56) {  // on the hanging arm (x 42..50), below the shoulder
        ++arm;
        on_arm += m.points[1][j].x() > 40.5;  // on the other pose's arm: the head is at x 8..32
      }
    }
    const double off = (m.points[1][tip] - c.tip).norm();
    MESSAGE(name << ", stretch cost " << c.stretch_cost << ": the tip lands " << off << " from the tip; " << on_arm
                 << " of the arm's " << arm << " samples on the arm");
    CHECK(arm > 50);
    CHECK(on_arm == arm);
    CHECK(off <= c.tip_within);
  }
}

TEST_CASE("bake: a sprite's mesh left below the quality floor by refining is mapped the other ways too") {
  // The arm squeezed 2 units from the body, then raised: mapped once the
  // mesh reaches 5.3 degrees, refined further 8.0, under the floor (10);
  // a mapping of a sprite's few outline points is worth the other ways
  // there too, and the outlines matched resisting stretch reach 12.2.
  pb::RigDescription rig = OutlineRig({ArmHangingFigure(), ArmRaisedFigure()});
  for (pb::PoseDescription& pose : rig.poses) pose.landmarks = {Point(20, 0)};
  pb::BakeReport report;
  pb::BakeRig(rig, &report);
  const pb::MappingReport& m = report.mapping;
  const double floor = rig.mapping.min_angle / 2;
  MESSAGE("mapped another way from " << m.matched_stiffer_over + m.registered_over << " to " << m.min_angle_degrees
                                     << " degrees");
  CHECK(m.matched_stiffer_over + m.registered_over > 0);
  CHECK(m.matched_stiffer_over + m.registered_over < floor);
  CHECK(m.min_angle_degrees >= floor);
  CHECK(report.inbetweens.FoldsInHull() == 0);
}
