// SPDX-License-Identifier: MIT
// The N-way mapping of outlines (MapPolygons, nway_mapping.h): onto the
// integer grid, landmarks placed, correspondence, simplification,
// compatible triangulation, refinement and features (DESIGN.md section 4).
#include "posemorph/bake/mapping/nway_mapping.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "format_number.h"
#include "geometry.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/mapping/interior_features.h"
#include "posemorph/bake/mapping/mesh_registration.h"

namespace posemorph {
namespace bake::mapping {
namespace {

// Landmarks at arc lengths `at` along an outline that runs counter-clockwise
// which go round the other way: each one further clockwise from landmark 0.
bool Clockwise(const std::vector<double>& at, double perimeter) {
  double previous = perimeter;
  for (std::size_t l = 1; l < at.size(); ++l) {
    double rel = std::fmod(at[l] - at[0], perimeter);
    if (rel < 0) rel += perimeter;
    if (!(rel > 0 && rel < previous)) return false;
    previous = rel;
  }
  return true;
}

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

// The outlines on the integer grid, each simple and counter-clockwise: exact
// checks from here on. Returns the grid.
Grid OntoGrid(const std::vector<Polygon>& rig_outlines, const std::vector<std::vector<Point>>& rig_landmarks,
              const std::vector<std::string>& labels, const std::string& file, MappingStages& st) {
  const std::size_t N = rig_outlines.size();
  auto fail = [&](std::size_t k, const std::string& problem) -> void {
    throw BakeError(file, labels[k] + ": " + problem);
  };
  double extent = 0;
  for (std::size_t k = 0; k < N; ++k) {
    for (const Point& p : rig_outlines[k]) extent = std::max(extent, p.cwiseAbs().maxCoeff());
    for (const Point& p : rig_landmarks[k]) extent = std::max(extent, p.cwiseAbs().maxCoeff());
  }
  if (!(extent <= 1e9))
    throw BakeError(file, "an outline or landmark lies beyond +-1e9 drawing units (" + Format(extent) + ")");
  const Grid grid = Grid::For(extent);
  st.grid_scale = grid.scale;
  for (std::size_t k = 0; k < N; ++k) {
    if (rig_outlines[k].size() > kMaxOutlinePoints)
      fail(k, "the outline has " + std::to_string(rig_outlines[k].size()) + " points, more than the limit of " +
                  std::to_string(kMaxOutlinePoints));
    if (rig_landmarks[k].size() > kMaxLandmarks)
      fail(k, "gives " + std::to_string(rig_landmarks[k].size()) + " landmarks, more than the limit of " +
                  std::to_string(kMaxLandmarks));
  }
  for (std::size_t k = 0; k < N; ++k) {
    Polygon g;
    for (const Point& p : rig_outlines[k]) g.push_back(grid.ToGrid(p));
    g = WithoutRepeats(g);
    if (g.size() < 3) fail(k, "the outline encloses no area");
    if (!IsSimplePolygon(g)) fail(k, "the outline crosses or touches itself; it must be one simple closed curve");
    if (SignedArea(g) == 0) fail(k, "the outline encloses no area");
    if (SignedArea(g) < 0) std::reverse(g.begin(), g.end());
    st.outlines.push_back(std::move(g));
  }
  return grid;
}

// Pose k's landmarks on its grid outline: as many as pose 0's, near the
// outline, counter-clockwise from the start point.
std::vector<Point> PlaceLandmarks(const Polygon& outline, const Polygon& rig_outline, const std::vector<Point>& given,
                                  std::size_t first_count, const std::string& label, const std::string& first_label,
                                  const MappingParameters& prm, const Grid& grid, const std::string& file) {
  auto fail = [&](const std::string& problem) -> void { throw BakeError(file, label + ": " + problem); };
  if (given.empty()) fail("needs at least one landmark (the start point)");
  if (given.size() != first_count)
    fail("gives " + std::to_string(given.size()) + " landmark(s) but " + first_label + " gives " +
         std::to_string(first_count) + "; every drawn pose needs the same corresponding points, the start point first");
  Eigen::AlignedBox2d box;
  for (const Point& p : rig_outline) box.extend(p);
  const double size = box.diagonal().norm();
  std::vector<Point> on;
  std::vector<double> at;
  for (std::size_t l = 0; l < given.size(); ++l) {
    double dist = 0;
    const double s = NearestArcLength(outline, grid.ToGrid(given[l]), &dist);
    dist /= grid.scale;
    // Messages give drawing units: working units times working_scale.
    const double u = prm.working_scale;
    if (dist > LandmarkTolerance(prm, size))
      fail("landmark " + std::to_string(l) + " is " + Format(dist * u) + " from the outline (more than " +
           Format(prm.landmark_distance * 100) + "% of the outline's size, " + Format(size * u) + ", and more than " +
           Format(kLandmarkToleranceFloor * u) + ", the least allowed)");
    on.push_back(PointAtArcLength(outline, s));
    at.push_back(s);
  }
  const double perimeter = CumulativeArcLength(outline).back();
  double previous = 0;
  for (std::size_t l = 1; l < at.size(); ++l) {
    double rel = std::fmod(at[l] - at[0], perimeter);
    if (rel < 0) rel += perimeter;
    if (!(rel > previous))
      fail(at.size() >= 3 && Clockwise(at, perimeter)
               ? std::string("landmarks are out of order: they go clockwise around the shape as seen in the drawing; "
                             "give them counter-clockwise, from landmark 0, in the same order in every pose")
               : "landmark " + std::to_string(l) +
                     " is out of order or coincides with another: landmarks go "
                     "counter-clockwise around the shape as seen in the drawing, in the same order in every pose");
    previous = rel;
  }
  return on;
}

// The features on the grid: as many in every pose, strictly inside the
// outline, apart by at least a quarter of the mesh's longest edge.
std::vector<std::vector<Point>> GridFeatures(const std::vector<Polygon>& outlines,
                                             const std::vector<std::vector<Point>>& rig_features,
                                             const MappingSizes& sizes, const std::vector<std::string>& labels,
                                             const Grid& grid, const std::string& file) {
  std::vector<std::vector<Point>> out;
  if (rig_features.empty()) return out;
  const std::size_t F = rig_features[0].size();
  for (std::size_t k = 0; k < outlines.size(); ++k) {
    auto fail = [&](const std::string& problem) -> void { throw BakeError(file, labels[k] + ": " + problem); };
    const std::vector<Point>& given = rig_features[k];
    if (given.size() > kMaxFeatures)
      fail("gives " + std::to_string(given.size()) + " features, more than the limit of " +
           std::to_string(kMaxFeatures));
    if (given.size() != F)
      fail("gives " + std::to_string(given.size()) + " feature(s) but " + labels[0] + " gives " + std::to_string(F) +
           "; every drawn pose lists the same features in the same order");
    out.emplace_back();
    for (std::size_t f = 0; f < F; ++f) {
      if (!(given[f].cwiseAbs().maxCoeff() <= 1e9)) fail("feature " + std::to_string(f) + " lies beyond +-1e9");
      const Point g = grid.ToGrid(given[f]);
      Eigen::AlignedBox2d box;
      for (const Point& p : outlines[k]) box.extend(p);
      if (!box.contains(g) || PointInPolygon(outlines[k], g) != 1)
        fail("feature " + std::to_string(f) +
             " lies outside the outline (or on it): features are points inside "
             "the shape");
      const double resolution = sizes.max_edge_length / 4;
      for (std::size_t e = 0; e < f; ++e) {
        const double apart = (given[f] - given[e]).norm();
        if (apart < resolution)
          fail("features " + std::to_string(e) + " and " + std::to_string(f) + " are " +
               Format(apart * sizes.working_scale) + " apart, closer than the mesh resolution (a quarter of the " +
               "longest edge, " + Format(resolution * sizes.working_scale) +
               "): give one feature, or a smaller mapping.max_edge_length");
      }
      out.back().push_back(g);
    }
  }
  return out;
}

}  // namespace

MappingStages MapPolygons(const std::vector<Polygon>& rig_outlines,
                          const std::vector<std::vector<Point>>& rig_landmarks,
                          const std::vector<std::vector<Point>>& rig_features, const MappingParameters& prm,
                          const std::vector<std::string>& labels, const std::string& file) {
  const std::size_t N = rig_outlines.size();
  auto fail = [&](std::size_t k, const std::string& problem) -> void {
    throw BakeError(file, labels[k] + ": " + problem);
  };
  MappingStages st;
  const Grid grid = OntoGrid(rig_outlines, rig_landmarks, labels, file, st);
  Eigen::AlignedBox2d box0;
  for (const Point& p : rig_outlines[0]) box0.extend(p);
  st.sizes = ResolveMappingSizes(prm, box0.diagonal().norm());
  const std::vector<std::vector<Point>> features =
      GridFeatures(st.outlines, rig_features, st.sizes, labels, grid, file);
  for (std::size_t k = 0; k < N; ++k)
    st.landmarks.push_back(PlaceLandmarks(st.outlines[k], rig_outlines[k], rig_landmarks[k], rig_landmarks[0].size(),
                                          labels[k], labels[0], prm, grid, file));

  for (std::size_t k = 1; k < N; ++k) {
    const StartAlignment a = AlignStart(st.outlines[0], st.landmarks[0][0], st.outlines[k], st.landmarks[k][0]);
    if (a.Misplaced()) {
      st.spinning.push_back({k, a.best_shift, grid.FromGrid(PointAtArcLength(st.outlines[k], a.best_start)), a});
    }
  }

  // Correspondence, simplification, compatible triangulation, refinement.
  MatchingParameters mp;
  mp.spacing = st.sizes.spacing * grid.scale;
  mp.smoothing = prm.correspondence_smoothing;
  if (prm.stretch_cost > 0) mp.stretch_cost = prm.stretch_cost;
  st.matched = MatchBoundaries(st.outlines, st.landmarks, mp);
  if (st.matched.spacing > mp.spacing)
    st.warnings.push_back(labels[0] + ": the outline is " +
                          Format(CumulativeArcLength(st.outlines[0]).back() / grid.scale * prm.working_scale) +
                          " long; it is matched at a spacing of " +
                          Format(st.matched.spacing / grid.scale * prm.working_scale) + " instead of " +
                          Format(st.sizes.spacing) + " (mapping.spacing; at most " +
                          std::to_string(kMaxMatchedSamples) + " samples)");
  // Each stage throws its errors complete: file, pose, and why the input is as it is.
  const std::string coarse =
      st.matched.spacing > mp.spacing
          ? "the outlines are matched at a spacing of " + Format(st.matched.spacing / grid.scale * prm.working_scale) +
                ", coarser than mapping.spacing, because " + labels[0] + "'s outline is longer than " +
                std::to_string(kMaxMatchedSamples) + " samples allow"
          : "";
  std::vector<ErrorSource> poses;
  for (const std::string& label : labels) poses.emplace_back(file, label, coarse);
  st.simplified = SimplifyEnclosing(st.outlines, st.matched, st.sizes.simplify_tolerance * grid.scale, poses);
  for (std::size_t k = 0; k < N; ++k) {
    // The promise of this stage, checked exactly: simple, and the outline inside or on it.
    const Polygon& q = st.simplified.polygons[k];
    if (!IsSimplePolygon(q) || SignedArea(q) <= 0 || !Encloses(q, st.outlines[k]))
      fail(k, "internal: the simplified boundary does not enclose the outline");
  }
  std::string names;
  for (const std::string& l : labels) names += (names.empty() ? "" : ", ") + l;
  RefinementParameters rp;
  rp.max_edge_length = st.sizes.max_edge_length * grid.scale;
  rp.min_angle_goal = prm.min_angle;
  rp.rounds = prm.refinement_rounds;
  rp.max_vertices = std::size_t(prm.max_vertices);
  // The mesh in proportion to the sprite: the splits for the angle goal
  // stop at kVerticesPerOutlinePoint per point of the first pose's traced
  // outline (gaucho, ceferino's sheet, standing against an arm raised: 963
  // vertices for 374 outline points, 2.6 per point, before).
  if (prm.proportional_vertices)
    rp.max_angle_vertices = std::size_t(kVerticesPerOutlinePoint * double(rig_outlines[0].size()));
  rp.collapse_slivers = prm.collapse_slivers;
  // A sliver's boundary vertex is removed only where the boundary moves by a
  // quarter of the simplification's tolerance at most (Pip at 1024 px: 5.1
  // -> 11.0 degrees, the boundary where it was within 0.01 px; half: the
  // same; the whole tolerance: 9.6 degrees).
  rp.max_collapse_distance = st.sizes.simplify_tolerance * grid.scale / 4;
  std::vector<ErrorSource> each;
  for (const std::string& label : labels) each.emplace_back(file, label);
  if (prm.registration) {
    st.mesh = RegisterCompatibly(st.simplified.polygons, rp, each, std::size_t(prm.max_steiner_points));
  } else {
    try {
      st.mesh =
          TriangulateCompatibly(st.simplified.polygons, ErrorSource(file, names), std::size_t(prm.max_steiner_points));
    } catch (const BakeError& triangulation) {
      // Where no compatible triangulation is found, pose 0's mesh deformed
      // onto the others may still be; if not, the triangulation's message
      // says why.
      try {
        st.mesh = RegisterCompatibly(st.simplified.polygons, rp, each, std::size_t(prm.max_steiner_points));
        std::string why = triangulation.what();
        if (why.compare(0, file.size() + 2, file + ": ") == 0) why.erase(0, file.size() + 2);
        st.warnings.push_back(why + "; mapped instead by deforming the first pose's mesh onto the others");
      } catch (const BakeError&) {
        throw triangulation;
      }
    }
  }
  auto refine = [&] {
    if (!RefineCompatibly(st.mesh, rp))
      throw BakeError(file, "mapping.max_edge_length " + Format(rp.max_edge_length / grid.scale) +
                                " needs more than mapping.max_vertices " + std::to_string(prm.max_vertices) +
                                " mesh vertices; give a longer max_edge_length (0: from the shape's size) or a "
                                "larger max_vertices");
  };
  refine();
  if (!features.empty() && !features[0].empty()) {
    // Placed in the refined mesh (room for the interior to follow them), then
    // refined again around them, the features held.
    PlaceFeatures(st.mesh, features, each, grid.scale / prm.working_scale);  // messages in drawing units
    refine();
  }
  return st;
}

}  // namespace bake::mapping

}  // namespace posemorph
