// SPDX-License-Identifier: MIT
// The N-way mapping driver (map_drawings.h): drawn poses of a rig
// description -> traced outlines -> MapPolygons -> one shared triangle list
// and per-pose vertices and uvs, the interiors aligned (DESIGN.md section 4).
#include "posemorph/bake/map_drawings.h"
#include "posemorph/bake/mesh_order.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <sstream>

#include "drawing_memo.h"
#include "posemorph/bake/run_each.h"
#include "drawn_pose.h"
#include "mapping/format_number.h"
#include "mapping/geometry.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/input_file.h"
#include "posemorph/bake/mapping/interior_alignment.h"
#include "posemorph/bake/mapping/interior_features.h"
#include "posemorph/bake/mapping/outline_image.h"

namespace posemorph::bake {
namespace {

using mapping::Format;
using mapping::Point;
using mapping::Polygon;

// What a PNG's tracing left out: only the largest part is mapped, so a
// separate eye or a loose hand is left out of the mesh (and drawn only
// where the mesh covers it).
std::string DroppedParts(const mapping::ImageOutline& io) {
  auto share = [&](std::size_t pixels) { return Format(100.0 * double(pixels) / double(io.shape_pixels)) + "%"; };
  const std::string where = "from (" + std::to_string(io.dropped_x0) + ", " + std::to_string(io.dropped_y0) + ") to (" +
                            std::to_string(io.dropped_x1) + ", " + std::to_string(io.dropped_y1) + ") in the drawing";
  const std::size_t n = io.dropped_parts.size();
  if (n == 1)
    return "a separate part of " + std::to_string(io.dropped_parts[0]) + " pixels (" + share(io.dropped_parts[0]) +
           " of the drawing, " + where + ")";
  return std::to_string(n) + " separate parts of " + std::to_string(io.dropped_pixels) + " pixels (" +
         share(io.dropped_pixels) + " of the drawing; the largest " + std::to_string(io.dropped_parts[0]) +
         " pixels, " + share(io.dropped_parts[0]) + ", " + where + ")";
}

// A point of a pose's drawing (y down) -> rig coordinates (y up, the pose's
// origin at 0), and back.
Point InRig(const Point& p, const PoseDescription& pose) {
  return {p.x() - pose.origin.x(), -(p.y() - pose.origin.y())};
}
Point InDrawing(const Point& p, const PoseDescription& pose) {
  return {p.x() + pose.origin.x(), -p.y() + pose.origin.y()};
}

// The mesh's triangles as the rig stores them.
Triangles SharedTriangles(const mapping::CompatibleMesh& mesh) {
  Triangles triangles;
  for (const auto& t : mesh.triangles)
    triangles.push_back({std::uint32_t(t[0]), std::uint32_t(t[1]), std::uint32_t(t[2])});
  return triangles;
}

// Step 1 for one drawn pose: its outline and landmarks in rig coordinates
// (y up), and where its drawing's canvas lies. Dropped parts of a PNG become
// warnings in `report`.
void ReadDrawnOutline(const RigDescription& rig, const MappingParameters& prm, int halvings, DrawnPose& d,
                      MappingReport& report) {
  auto fail = [&](const std::string& problem) -> void {
    throw BakeError(rig.file, PoseLabel(rig.poses[d.index].name, d.index) + ": " + problem);
  };
  const PoseDescription& pose = rig.poses[d.index];
  Polygon raw;
  const bool png = IsRasterDrawing(pose.drawing), svg = EndsWith(pose.drawing, ".svg");
  if (!pose.drawing.empty() && !png && !svg)
    fail("drawing \"" + pose.drawing + "\" is neither .png, .svg nor a layered file (.ora, .psd, with #Group/Layer)");
  {
    // A drawing's errors name the description, the pose and the drawing.
    const ErrorSource source(rig.file, PoseLabel(pose.name, d.index) + ": " + pose.drawing_path);
    if (pose.drawing.empty()) {
      raw = pose.outline;
      d.landmarks = pose.landmarks;
    } else if (png) {
      const mapping::ImageOutline io = TraceOutline(pose.drawing_path, prm, halvings, source);
      if (io.shadow_pixels > 0)
        report.warnings.push_back(rig.file + ": " + PoseLabel(pose.name, d.index) + ": " + pose.drawing_path +
                                  ": a dark, semi-transparent region of " + std::to_string(io.shadow_pixels) +
                                  " pixels from (" + std::to_string(io.shadow_x0) + ", " +
                                  std::to_string(io.shadow_y0) + ") to (" + std::to_string(io.shadow_x1) + ", " +
                                  std::to_string(io.shadow_y1) + ") in the drawing (mean alpha " +
                                  Format(io.shadow_alpha) +
                                  ") is taken as its drop shadow and left out of the mesh, so it is not drawn "
                                  "(mapping.drop_shadows: false keeps it)");
      report.filled_notch_corners += io.filled_notch_corners;
      if (io.dropped_components > 0)
        report.warnings.push_back(rig.file + ": " + PoseLabel(pose.name, d.index) + ": " + pose.drawing_path +
                                  ": dropped " + DroppedParts(io) +
                                  ": only the largest part is meshed; join the parts in the drawing to keep them");
      for (const Point& p : io.outline) raw.push_back(InRig(p, pose));
      d.from_drawing = true;
      d.origin = Point(0.0 - pose.origin.x(), 0.0 - pose.origin.y());  // the canvas's corner from the pose's origin
      d.size = Point(io.width, io.height);
    } else {
      mapping::SvgOutline so =
          mapping::OutlineFromSvg(pose.drawing_path, prm.curve_tolerance, source, {pose.layer, pose.layer_required});
      for (const Point& p : so.outline) raw.push_back(InRig(p, pose));
      d.from_drawing = true;
      d.origin = so.canvas_origin - pose.origin;
      d.size = so.canvas_size;
    }
  }
  if (d.from_drawing) {
    for (const Point& p : pose.landmarks) d.landmarks.push_back(InRig(p, pose));
    for (const Point& p : pose.features) d.features.push_back(InRig(p, pose));
  } else {
    d.features = pose.features;
  }
  if (raw.size() > mapping::kMaxOutlinePoints)
    fail((d.from_drawing ? pose.drawing_path + ": " : std::string()) + "the outline has " + std::to_string(raw.size()) +
         " points, more than the limit of " + std::to_string(mapping::kMaxOutlinePoints));
  d.outline = std::move(raw);
  report.outline_vertices.push_back(d.outline.size());
}

// The mapped meshes back in rig coordinates, with uvs into each pose's own
// drawing (or its outline's box) and the canvas a drawing was on.
void MeshesFromMapping(const RigDescription& rig, const std::vector<DrawnPose>& drawn,
                       const mapping::CompatibleMesh& mesh, const mapping::Grid& grid, double working_scale,
                       MappedDrawings& result) {
  result.triangles = SharedTriangles(mesh);
  for (std::size_t k = 0; k < drawn.size(); ++k) {
    const DrawnPose& d = drawn[k];
    const PoseDescription& description = rig.poses[d.index];
    result.poses.push_back(d.index);
    result.meshes.emplace_back();
    PoseMesh& pose = result.meshes.back();
    pose.name = description.name;
    pose.point = description.point;
    pose.image = description.image.empty() ? description.drawing : description.image;
    Eigen::AlignedBox2d box;
    for (const Point& p : d.outline) box.extend(p);
    for (const Point& g : mesh.vertices[k]) {
      const Point p = grid.FromGrid(g) * working_scale;  // exact: a power of two
      pose.vertices.push_back(p);
      Point uv;
      if (d.from_drawing)
        uv = Point((p.x() - d.origin.x()) / d.size.x(), (-p.y() - d.origin.y()) / d.size.y());
      else
        uv = Point((p.x() - box.min().x()) / box.sizes().x(), (box.max().y() - p.y()) / box.sizes().y());
      pose.uvs.push_back(uv.cast<float>());
    }
    if (d.from_drawing) {
      // Rig coordinates are drawing units with y flipped: the rig origin is
      // the drawing's (0, 0), at -origin on the canvas.
      pose.canvas_size = d.size;
      pose.canvas_pivot = Eigen::Vector2d(0.0 - d.origin.x(), 0.0 - d.origin.y());  // no -0
    }
  }
}

// The smallest angle of any triangle in any pose, degrees.
double MinAngleDegrees(const Triangles& triangles, const std::vector<PoseMesh>& meshes) {
  double least = 180;
  for (const PoseMesh& m : meshes)
    for (const auto& t : triangles)
      for (int k = 0; k < 3; ++k) {
        const Point &p = m.vertices[t[std::size_t(k)]], &q = m.vertices[t[std::size_t((k + 1) % 3)]],
                    &r = m.vertices[t[std::size_t((k + 2) % 3)]];
        const Point u = q - p, v = r - p;
        least = std::min(least, std::atan2(std::abs(u.x() * v.y() - u.y() * v.x()), u.dot(v)) * 180 / M_PI);
      }
  return least;
}

std::vector<DrawnPose> DrawnPoses(const RigDescription& rig) {
  std::vector<DrawnPose> drawn;
  for (std::size_t i = 0; i < rig.poses.size(); ++i)
    if (rig.poses[i].drawn && rig.poses[i].vertices.empty()) {
      drawn.emplace_back();
      drawn.back().index = i;
    }
  return drawn;
}

// Step 1 for every drawn pose: what MapPolygons takes.
// Outlines, landmarks and features are in working units: rig coordinates
// divided by 2^halvings (exact), so that the mapping's lengths are the
// working level's pixels.
struct MappingInput {
  std::vector<Polygon> outlines;
  std::vector<std::vector<Point>> landmarks, features;
  std::vector<std::string> labels;
  int halvings = 0;              // the pyramid level the PNG drawings were traced on
  double working_scale = 1;      // 2^halvings: rig units per working unit
  MappingParameters parameters;  // the description's, with working_scale set
};

// The pyramid level the character's PNG drawings are traced on
// (mapping.working_size): the most halvings any of them needs, so that one
// working unit is the same in every pose.
int CharacterHalvings(const RigDescription& rig, const std::vector<DrawnPose>& drawn) {
  int halvings = 0;
  if (rig.mapping.working_size <= 0) return 0;
  for (const DrawnPose& d : drawn) {
    const PoseDescription& pose = rig.poses[d.index];
    if (!pose.drawing.empty() && !IsRasterDrawing(pose.drawing) && !EndsWith(pose.drawing, ".svg"))
      throw BakeError(rig.file, PoseLabel(pose.name, d.index) + ": drawing \"" + pose.drawing +
                                    "\" is neither .png, .svg nor a layered file (.ora, .psd, with #Group/Layer)");
    if (!IsRasterDrawing(pose.drawing) || !pose.vertices.empty()) continue;
    int width = 0, height = 0;
    mapping::ReadPngSize(pose.drawing_path, &width, &height,
                         ErrorSource(rig.file, PoseLabel(pose.name, d.index) + ": " + pose.drawing_path));
    halvings = std::max(halvings, mapping::WorkingHalvings(width, height, rig.mapping.working_size));
  }
  return halvings;
}

MappingInput ReadDrawnOutlines(const RigDescription& rig, std::vector<DrawnPose>& drawn, MappingReport& report) {
  MappingInput in;
  in.halvings = CharacterHalvings(rig, drawn);
  in.working_scale = std::ldexp(1.0, in.halvings);
  in.parameters = rig.mapping;
  in.parameters.working_scale = in.working_scale;
  if (!drawn.empty()) {
    const PoseDescription& first = rig.poses[drawn[0].index];
    in.parameters.proportional_vertices = first.vertices.empty() && IsRasterDrawing(first.drawing);
  }
  const double to_working = 1 / in.working_scale;
  auto working = [&](std::vector<Point> points) {
    for (Point& p : points) p *= to_working;
    return points;
  };
  // The drawings are read over the machine's cores (decoding an HD PNG is
  // most of its tracing), each pose into its own report, joined in order:
  // the same outlines and messages, and the first pose's error first.
  std::vector<MappingReport> each(drawn.size());
  RunEach(drawn.size(), 0, [&](std::size_t k) { ReadDrawnOutline(rig, rig.mapping, in.halvings, drawn[k], each[k]); });
  for (const MappingReport& r : each) {
    report.warnings.insert(report.warnings.end(), r.warnings.begin(), r.warnings.end());
    report.filled_notch_corners += r.filled_notch_corners;
    report.outline_vertices.insert(report.outline_vertices.end(), r.outline_vertices.begin(), r.outline_vertices.end());
  }
  for (DrawnPose& d : drawn) {
    in.outlines.push_back(working(d.outline));
    in.landmarks.push_back(working(d.landmarks));
    in.features.push_back(working(d.features));
    in.labels.push_back(PoseLabel(rig.poses[d.index].name, d.index));
  }
  return in;
}

// "FILE: POSE: ..." for each pose whose start landmark seems misplaced.
std::vector<std::string> SpinningWarnings(const RigDescription& rig, const std::vector<DrawnPose>& drawn,
                                          const MappingInput& in, const mapping::MappingStages& st) {
  const std::vector<std::string>& labels = in.labels;
  std::vector<std::string> warnings;
  for (const auto& s : st.spinning) {
    const Point at = InDrawing(s.suggested * in.working_scale, rig.poses[drawn[s.pose].index]);
    warnings.push_back(rig.file + ": " + labels[s.pose] + ": its start landmark (landmark 0) may sit on another part " +
                       "of the outline than in " + labels[0] + ": the outlines' bends agree best with the start " +
                       Format(100 * s.shift) + "% of the way round, counter-clockwise as seen (mean difference " +
                       Format(s.alignment.best_cost) + " rad there, " + Format(s.alignment.cost_at_start) +
                       " at landmark 0), near (" + Format(at.x()) + ", " + Format(at.y()) +
                       ") in its drawing; if the in-betweens spin, move landmark 0 there");
  }
  return warnings;
}

MappedDrawings MapDrawingsAsTraced(const RigDescription& rig);

// MapPolygons; when it fails and some pose's start landmark seems to sit on
// another part of the outline than pose 0's (a start on the left foot in one
// drawing and on the right foot in the next), the error says so too, with
// where the outlines' bends put the start in that pose's drawing: the
// failure it led to (a feature or a joint that cannot be placed, no
// enclosing polygon) names a symptom, not the cause.
mapping::MappingStages MapPolygonsOrSayStart(const RigDescription& rig, const std::vector<DrawnPose>& drawn,
                                             const MappingInput& in) {
  const MappingParameters& prm = in.parameters;
  try {
    return mapping::MapPolygons(in.outlines, in.landmarks, in.features, prm, in.labels, rig.file);
  } catch (const BakeError& e) {
    std::string hint;
    for (std::size_t k = 1; k < in.outlines.size(); ++k) {
      if (in.landmarks[k].empty() || in.landmarks[0].empty()) continue;
      const mapping::StartAlignment a =
          mapping::AlignStart(in.outlines[0], in.landmarks[0][0], in.outlines[k], in.landmarks[k][0]);
      if (!a.Misplaced()) continue;
      const Point at = InDrawing(mapping::PointAtArcLength(in.outlines[k], a.best_start) * in.working_scale,
                                 rig.poses[drawn[k].index]);
      hint += "; " + in.labels[k] + ": its start landmark (landmark 0) may sit on another part of the outline than " +
              "in " + in.labels[0] + " (a start that switches feet between poses, say), which is what can make " +
              "this fail: the outlines' bends agree best with the start near (" + Format(at.x()) + ", " +
              Format(at.y()) + ") in its drawing; move landmark 0 there";
    }
    if (hint.empty()) throw;
    const std::string what = e.what();
    const std::string prefix = rig.file + ": ";
    throw BakeError(rig.file, (what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what) + hint);
  }
}

}  // namespace

// The drawings mapped as traced; when that fails (no enclosing polygon, a
// triangulation that cannot be made), mapped again with the PNG outlines'
// thin notches filled, which is said in a warning; when that fails too,
// the first failure is the one reported.
MappedDrawings MapDrawings(const RigDescription& rig) {
  try {
    return MapDrawingsAsTraced(rig);
  } catch (const BakeError& first) {
    if (rig.mapping.fill_notches || !TracesPngOutline(rig)) throw;
    RigDescription filled = rig;
    filled.mapping.fill_notches = true;
    try {
      MappedDrawings again = MapDrawingsAsTraced(filled);
      again.report.warnings.insert(again.report.warnings.begin(),
                                   std::string(first.what()) +
                                       "; mapped again with the outlines' thin notches filled (" +
                                       std::to_string(again.report.filled_notch_corners) + " corners)");
      return again;
    } catch (const BakeError&) {
      throw first;
    }
  }
}

namespace {

MappedDrawings MapDrawingsAsTraced(const RigDescription& rig) {
  MappedDrawings result;
  std::vector<DrawnPose> drawn = DrawnPoses(rig);
  if (drawn.empty()) return result;
  const auto start = std::chrono::steady_clock::now();
  const MappingParameters& prm = rig.mapping;
  MappingReport& report = result.report;

  // 1. Outlines, in rig coordinates (y up).
  const MappingInput in = ReadDrawnOutlines(rig, drawn, report);
  if (prm.fill_notches && report.filled_notch_corners == 0)
    throw BakeError(rig.file, "no thin notch to fill: the outlines are as traced");  // the same mapping again
  const mapping::MappingStages st = MapPolygonsOrSayStart(rig, drawn, in);
  for (const std::string& w : st.warnings) report.warnings.push_back(rig.file + ": " + w);
  for (const std::string& w : SpinningWarnings(rig, drawn, in, st)) report.warnings.push_back(w);
  const mapping::CompatibleMesh& mesh = st.mesh;
  const mapping::Grid grid{st.grid_scale};
  report.matched_vertices = st.matched.points[0].size();
  report.boundary_vertices = st.simplified.polygons[0].size();
  report.simplification_error = st.simplified.max_error / grid.scale * in.working_scale;
  report.steiner_points = mesh.steiner_points;
  report.registered = prm.registration;
  report.stretch_cost = prm.stretch_cost;
  report.features = mesh.features.size();
  for (std::size_t v : mesh.features) result.feature_vertices.push_back(std::uint32_t(v));
  report.min_angle_degrees = report.min_angle_before_alignment = mapping::MinAngleDegrees(mesh);
  report.vertices = mesh.vertices[0].size();
  report.triangles = mesh.triangles.size();

  // 5. Back to rig coordinates; uvs into each pose's own drawing.
  MeshesFromMapping(rig, drawn, mesh, grid, in.working_scale, result);
  // 7. The drawings align the interiors.
  AlignDrawnInteriors(rig, drawn, mesh, in.halvings, result);
  if (report.aligned) report.min_angle_degrees = MinAngleDegrees(result.triangles, result.meshes);
  // 8. Numbered for the compact encoding (mesh_order.h).
  OrderForCoding(&result);
  report.mapped = true;
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace

bool TracesPngOutline(const RigDescription& rig) {
  if (!rig.parts.empty()) return true;  // a part's poses may be
  for (const PoseDescription& pose : rig.poses)
    if (pose.drawn && pose.vertices.empty() && IsRasterDrawing(pose.drawing)) return true;
  return false;
}

DrawnOutlines TraceDrawings(const RigDescription& rig) {
  DrawnOutlines result;
  std::vector<DrawnPose> drawn = DrawnPoses(rig);
  MappingReport report;
  const MappingInput in = ReadDrawnOutlines(rig, drawn, report);
  for (std::size_t k = 0; k < drawn.size(); ++k) {
    const DrawnPose& d = drawn[k];
    const PoseDescription& pose = rig.poses[d.index];
    DrawnPoseOutline o;
    o.pose = d.index;
    o.label = in.labels[k];
    if (IsRasterDrawing(pose.drawing)) o.png_path = pose.drawing_path;
    Eigen::AlignedBox2d box;
    for (const Point& p : d.outline) box.extend(p), o.traced.push_back(InDrawing(p, pose));
    if (mapping::SignedArea(d.outline) < 0) std::reverse(o.traced.begin(), o.traced.end());
    for (const Point& p : d.landmarks) o.landmarks.push_back(InDrawing(p, pose));
    for (const Point& p : d.features) o.features.push_back(InDrawing(p, pose));
    o.landmark_distance =
        mapping::LandmarkTolerance(rig.mapping, box.diagonal().norm() / in.working_scale) * in.working_scale;
    result.poses.push_back(std::move(o));
  }
  if (drawn.empty()) return result;
  try {
    const mapping::MappingStages st =
        mapping::MapPolygons(in.outlines, in.landmarks, in.features, in.parameters, in.labels, rig.file);
    const mapping::Grid grid{st.grid_scale * (1 / in.working_scale)};  // working grid -> rig units
    result.simplify_tolerance = st.sizes.simplify_tolerance * in.working_scale;
    for (std::size_t k = 0; k < drawn.size(); ++k) {
      const PoseDescription& pose = rig.poses[drawn[k].index];
      DrawnPoseOutline& o = result.poses[k];
      for (const Point& g : st.landmarks[k]) o.placed.push_back(InDrawing(grid.FromGrid(g), pose));
      for (const Point& g : st.simplified.polygons[k]) o.boundary.push_back(InDrawing(grid.FromGrid(g), pose));
      for (const Point& g : st.mesh.vertices[k]) o.vertices.push_back(InDrawing(grid.FromGrid(g), pose));
    }
    result.triangles = SharedTriangles(st.mesh);
  } catch (const BakeError& e) {
    result.mapping_error = e.what();
  }
  return result;
}

}  // namespace posemorph::bake
