// The N-way mapping driver: drawn poses of a rig description -> one shared
// triangle list and per-pose vertices and uvs (DESIGN.md section 4).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "geometry.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/rig_description.h"

namespace posemorph::bake {
namespace {

using mapping::Point;
using mapping::Polygon;

std::string Format(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}

bool EndsWith(std::string s, const std::string& suffix) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

struct DrawnPose {
  std::size_t index = 0;       // in rig.poses
  Polygon outline;             // rig coordinates (y up), counter-clockwise
  std::vector<Point> landmarks;
  // uv = ((x - origin.x) / size.x, (-y - origin.y) / size.y) for drawings (rows go down)
  bool from_drawing = false;
  Point origin{0, 0}, size{1, 1};
};

Polygon WithoutRepeats(const Polygon& p) {
  Polygon out;
  for (const Point& q : p)
    if (out.empty() || q != out.back()) out.push_back(q);
  while (out.size() > 1 && out.front() == out.back()) out.pop_back();
  // Drop exactly collinear middle points: they carry no shape.
  Polygon clean;
  const std::size_t n = out.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Point &a = out[(i + n - 1) % n], &b = out[i], &c = out[(i + 1) % n];
    if (mapping::Cross(a, b, c) != 0 || (b - a).dot(c - b) < 0) clean.push_back(b);
  }
  return clean;
}

}  // namespace

void MapDrawings(RigDescription& rig) {
  std::vector<DrawnPose> drawn;
  for (std::size_t i = 0; i < rig.poses.size(); ++i)
    if (rig.poses[i].drawn && rig.poses[i].vertices.empty()) {
      drawn.emplace_back();
      drawn.back().index = i;
    }
  if (drawn.empty()) return;
  const auto start = std::chrono::steady_clock::now();
  const MappingParameters& prm = rig.mapping;
  MappingReport& report = rig.mapping_report;
  report = MappingReport{};
  auto fail = [&](const DrawnPose& d, const std::string& problem) -> void {
    throw BakeError(rig.file, "pose '" + rig.poses[d.index].name + "' (index " + std::to_string(d.index) + "): " + problem);
  };

  // 1. Outlines, in rig coordinates (y up).
  for (DrawnPose& d : drawn) {
    PoseDescription& pose = rig.poses[d.index];
    Polygon raw;
    const bool png = EndsWith(pose.drawing, ".png"), svg = EndsWith(pose.drawing, ".svg");
    if (!pose.drawing.empty() && !png && !svg) fail(d, "drawing \"" + pose.drawing + "\" is neither .png nor .svg");
    try {
      if (pose.drawing.empty()) {
        raw = pose.outline;
        d.landmarks = pose.landmarks;
      } else if (png) {
        mapping::ImageOutline io = mapping::OutlineFromPng(pose.drawing_path, prm.alpha_threshold);
        if (io.dropped_components > 0)
          report.warnings.push_back(pose.drawing_path + ": dropped " + std::to_string(io.dropped_components) +
                                    " speck(s) apart from the shape (" + std::to_string(io.dropped_pixels) + " pixels)");
        for (const Point& p : io.outline) raw.push_back({p.x(), -p.y()});
        d.from_drawing = true;
        d.size = Point(io.width, io.height);
      } else {
        mapping::SvgOutline so = mapping::OutlineFromSvg(pose.drawing_path, prm.curve_tolerance);
        for (const Point& p : so.outline) raw.push_back({p.x(), -p.y()});
        d.from_drawing = true;
        d.origin = so.canvas_origin;
        d.size = so.canvas_size;
      }
    } catch (const BakeError& e) {
      fail(d, e.what());
    }
    if (d.from_drawing)
      for (const Point& p : pose.landmarks) d.landmarks.push_back({p.x(), -p.y()});
    if (std::abs(mapping::SignedArea(raw)) == 0) fail(d, "the outline encloses no area");
    if (mapping::SignedArea(raw) < 0) std::reverse(raw.begin(), raw.end());
    d.outline = std::move(raw);
    report.outline_vertices.push_back(d.outline.size());
  }

  // 2. Onto the integer grid; exact checks from here on.
  double extent = 0;
  for (const DrawnPose& d : drawn) {
    for (const Point& p : d.outline) extent = std::max(extent, p.cwiseAbs().maxCoeff());
    for (const Point& p : d.landmarks) extent = std::max(extent, p.cwiseAbs().maxCoeff());
  }
  const mapping::Grid grid = mapping::Grid::For(extent);
  std::vector<Polygon> outlines;
  for (DrawnPose& d : drawn) {
    Polygon g;
    for (const Point& p : d.outline) g.push_back(grid.ToGrid(p));
    g = WithoutRepeats(g);
    if (g.size() < 3 || mapping::SignedArea(g) <= 0) fail(d, "the outline encloses no area");
    if (!mapping::IsSimplePolygon(g)) fail(d, "the outline crosses or touches itself; it must be one simple closed curve");
    outlines.push_back(std::move(g));
  }

  // 3. Landmarks: same count everywhere, near the outline, in the same order.
  const DrawnPose& first = drawn[0];
  std::vector<std::vector<Point>> landmarks;
  for (std::size_t k = 0; k < drawn.size(); ++k) {
    const DrawnPose& d = drawn[k];
    if (d.landmarks.size() != first.landmarks.size())
      fail(d, "gives " + std::to_string(d.landmarks.size()) + " landmark(s) but pose '" +
                  rig.poses[first.index].name + "' gives " + std::to_string(first.landmarks.size()) +
                  "; every drawn pose needs the same corresponding points, the start point first");
    Eigen::AlignedBox2d box;
    for (const Point& p : d.outline) box.extend(p);
    const double size = box.diagonal().norm();
    std::vector<Point> on;
    std::vector<double> at;
    for (std::size_t l = 0; l < d.landmarks.size(); ++l) {
      double dist = 0;
      const double s = mapping::NearestArcLength(outlines[k], grid.ToGrid(d.landmarks[l]), &dist);
      dist /= grid.scale;
      if (dist > prm.landmark_distance * size)
        fail(d, "landmark " + std::to_string(l) + " is " + Format(dist) + " from the outline (more than " +
                    Format(prm.landmark_distance * 100) + "% of the outline's size, " + Format(size) + ")");
      on.push_back(mapping::PointAtArcLength(outlines[k], s));
      at.push_back(s);
    }
    // Counter-clockwise from the start point, strictly increasing.
    const double perimeter = [&] {
      double p = 0;
      for (std::size_t i = 0; i < outlines[k].size(); ++i)
        p += (outlines[k][(i + 1) % outlines[k].size()] - outlines[k][i]).norm();
      return p;
    }();
    double previous = 0;
    for (std::size_t l = 1; l < at.size(); ++l) {
      double rel = std::fmod(at[l] - at[0], perimeter);
      if (rel < 0) rel += perimeter;
      if (!(rel > previous))
        fail(d, "landmark " + std::to_string(l) + " is out of order or coincides with another: landmarks must follow "
                "the outline in the same direction in every pose");
      previous = rel;
    }
    landmarks.push_back(std::move(on));
  }

  // 4. Correspondence, simplification, compatible triangulation, refinement.
  mapping::MatchingParameters mp;
  mp.spacing = prm.spacing * grid.scale;
  const mapping::CorrespondedBoundary matched = mapping::MatchBoundaries(outlines, landmarks, mp);
  report.matched_vertices = matched.points[0].size();
  mapping::SimplifiedBoundary simple;
  try {
    simple = mapping::SimplifyEnclosing(outlines, matched, prm.simplify_tolerance * grid.scale);
  } catch (const BakeError& e) {
    throw BakeError(rig.file, e.what());
  }
  report.boundary_vertices = simple.polygons[0].size();
  report.simplification_error = simple.max_error / grid.scale;
  for (std::size_t k = 0; k < drawn.size(); ++k) {
    // The promise of this stage, checked exactly: simple, and the outline inside or on it.
    const Polygon& q = simple.polygons[k];
    bool ok = mapping::IsSimplePolygon(q) && mapping::SignedArea(q) > 0;
    for (const Point& p : outlines[k]) ok = ok && mapping::PointInPolygon(q, p) >= 0;
    if (!ok) fail(drawn[k], "internal: the simplified boundary does not enclose the outline");
  }
  std::string names;
  for (const DrawnPose& d : drawn) names += (names.empty() ? "'" : ", '") + rig.poses[d.index].name + "'";
  mapping::CompatibleMesh mesh;
  try {
    mesh = mapping::TriangulateCompatibly(simple.polygons, "poses " + names);
  } catch (const BakeError& e) {
    throw BakeError(rig.file, e.what());
  }
  report.steiner_points = mesh.steiner_points;
  Eigen::AlignedBox2d box0;
  for (const Point& p : drawn[0].outline) box0.extend(p);
  mapping::RefinementParameters rp;
  rp.max_edge_length = (prm.max_edge_length > 0 ? prm.max_edge_length : box0.diagonal().norm() / 10) * grid.scale;
  rp.min_angle_goal = prm.min_angle;
  mapping::RefineCompatibly(mesh, rp);
  report.min_angle_degrees = mapping::MinAngleDegrees(mesh);
  report.vertices = mesh.vertices[0].size();
  report.triangles = mesh.triangles.size();

  // 5. Back to rig coordinates; uvs into each pose's own drawing.
  rig.triangles.clear();
  for (const auto& t : mesh.triangles)
    rig.triangles.push_back({std::uint32_t(t[0]), std::uint32_t(t[1]), std::uint32_t(t[2])});
  for (std::size_t k = 0; k < drawn.size(); ++k) {
    const DrawnPose& d = drawn[k];
    PoseDescription& pose = rig.poses[d.index];
    pose.vertices.clear();
    pose.uvs.clear();
    Eigen::AlignedBox2d box;
    for (const Point& p : d.outline) box.extend(p);
    for (const Point& g : mesh.vertices[k]) {
      const Point p = grid.FromGrid(g);
      pose.vertices.push_back(p);
      Point uv;
      if (d.from_drawing) uv = Point((p.x() - d.origin.x()) / d.size.x(), (-p.y() - d.origin.y()) / d.size.y());
      else uv = Point((p.x() - box.min().x()) / box.sizes().x(), (box.max().y() - p.y()) / box.sizes().y());
      pose.uvs.push_back(uv.cast<float>());
    }
    if (pose.image.empty()) pose.image = pose.drawing;
  }
  report.mapped = true;
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace posemorph::bake
