// SPDX-License-Identifier: MIT
#include "posemorph/bake/serialise_rig.h"

#include <cstring>
#include <filesystem>
#include <optional>

#include <Eigen/Geometry>

#include "posemorph/jobs.h"
#include "posemorph/rig_format.h"
#include "rig_writer.h"

namespace posemorph::bake {
namespace {

namespace fmt = format;

}  // namespace

double RigBoundingBoxDiagonal(const PoseMeshes& meshes) {
  Eigen::AlignedBox2d box;
  for (const auto& v : meshes.poses.at(0).vertices) box.extend(v);
  return box.diagonal().norm();
}

bool HasCanvases(const PoseMeshes& meshes) {
  for (const PoseMesh& p : meshes.poses)
    if (p.canvas_size.x() > 0) return true;
  return false;
}

namespace {

// Some part's draw order differs between poses (format 1.6, PORD).
bool DrawOrderChanges(const PoseMeshes& meshes) {
  for (const MeshPart& part : meshes.parts)
    for (int order : part.pose_orders)
      if (order != part.order) return true;
  return false;
}

// The description's folder relative to the folder of the rig file, when the
// rig file is known, some pose references a drawing, and one folder can be
// reached from the other by a relative path.
std::optional<std::string> DrawingFolder(const RigDescription& description, const PoseMeshes& meshes) {
  namespace fs = std::filesystem;
  bool any_image = false;
  for (const PoseMesh& p : meshes.poses) any_image = any_image || !p.image.empty();
  for (const MeshPart& part : meshes.parts)
    for (const std::string& image : part.images) any_image = any_image || !image.empty();
  if (description.rig_file.empty() || description.file.empty() || !any_image) return std::nullopt;
  std::error_code ec;
  const fs::path from = fs::absolute(fs::path(description.rig_file), ec).lexically_normal().parent_path();
  if (ec) return std::nullopt;
  const fs::path to = fs::absolute(fs::path(description.file), ec).lexically_normal().parent_path();
  if (ec) return std::nullopt;
  const fs::path relative = to.lexically_relative(from);
  if (relative.empty()) return std::nullopt;
  return relative.generic_string();
}

bool HasEvents(const RigDescription& description) {
  for (const PathDescription& path : description.paths)
    if (!path.events.empty()) return true;
  return false;
}

// META: counts, flags, the grid's geometry, sigma and the rig's size.
fmt::Meta MakeMeta(const RigDescription& description, const PoseMeshes& meshes, const ArapSystem& system,
                   const WeightGrid& grid, bool has_drawing_folder) {
  const std::size_t V = meshes.poses[0].vertices.size(), T = meshes.triangles.size(), N = meshes.poses.size();
  fmt::Meta meta{};
  meta.vertex_count = std::uint32_t(V);
  meta.triangle_count = std::uint32_t(T);
  meta.pose_count = std::uint32_t(N);
  meta.path_count = std::uint32_t(description.paths.size());
  meta.grid_cells_x = grid.cells_x;
  meta.grid_cells_y = grid.cells_y;
  meta.factor_nonzeros = std::uint32_t(system.value.size());
  const bool has_uvs = !meshes.poses[0].uvs.empty();
  meta.flags = (has_uvs ? fmt::kMetaFlagHasUVs : 0) | (grid.centre_weights.empty() ? 0 : fmt::kMetaFlagGridCentres) |
               (description.nearest_filter ? fmt::kMetaFlagNearestFilter : 0) |
               (has_drawing_folder ? fmt::kMetaFlagDrawingFolder : 0) |
               (meshes.parts.empty() ? 0 : fmt::kMetaFlagParts) |
               (DrawOrderChanges(meshes) ? fmt::kMetaFlagPartPoseOrders : 0) |
               (HasEvents(description) ? fmt::kMetaFlagEvents : 0);
  meta.grid_origin_x = grid.origin_x;
  meta.grid_origin_y = grid.origin_y;
  meta.grid_cell_size = grid.cell;
  meta.default_sigma = description.parameters.sigma;
  meta.rig_size = RigBoundingBoxDiagonal(meshes);

  return meta;
}

// The poses' vertices, points, centroids (mass-weighted) and uvs, flat.
struct PoseArrays {
  std::vector<double> positions, pose_points, centroids;
  std::vector<float> uvs;
};

PoseArrays FlattenPoses(const PoseMeshes& meshes, const std::vector<double>& vertex_masses) {
  const std::size_t V = meshes.poses[0].vertices.size();
  const bool has_uvs = !meshes.poses[0].uvs.empty();
  PoseArrays a;
  std::vector<double>&positions = a.positions, &pose_points = a.pose_points, &centroids = a.centroids;
  std::vector<float>& uvs = a.uvs;
  for (const PoseMesh& p : meshes.poses) {
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (std::size_t v = 0; v < V; ++v) {
      positions.push_back(p.vertices[v].x());
      positions.push_back(p.vertices[v].y());
      c += vertex_masses[v] * p.vertices[v];
      if (has_uvs) {
        uvs.push_back(p.uvs[v].x());
        uvs.push_back(p.uvs[v].y());
      }
    }
    pose_points.push_back(p.point.x());
    pose_points.push_back(p.point.y());
    centroids.push_back(c.x());
    centroids.push_back(c.y());
  }
  return a;
}

// STRS (pose names, image references, path names, the drawings' folder, part
// strings, event names), PATH, PKEY and EVNT.
struct NamesAndPaths {
  std::vector<unsigned char> strings, path_table, events;  // events: EVNT (format 1.8), empty without
  std::vector<double> keys;
};

NamesAndPaths FlattenNamesAndPaths(const RigDescription& description, const PoseMeshes& meshes,
                                   const std::optional<std::string>& drawing_folder) {
  NamesAndPaths a;
  std::vector<unsigned char>&strings = a.strings, &path_table = a.path_table;
  std::vector<double>& keys = a.keys;
  for (const PoseMesh& p : meshes.poses) AppendString(strings, p.name);
  for (const PoseMesh& p : meshes.poses) AppendString(strings, p.image);
  for (const auto& path : description.paths) {
    AppendString(strings, path.name);
    fmt::PathEntry entry{};
    entry.key_count = std::uint32_t(path.keys.size());
    entry.flags = (path.loop ? fmt::kPathFlagLoop : 0u) |
                  (std::uint32_t(path.catmull_rom ? PathInterpolation::kCatmullRom : PathInterpolation::kLinear)
                   << fmt::kPathInterpolationShift);
    AppendRecord(path_table, entry);
    for (const auto& k : path.keys) keys.insert(keys.end(), k.begin(), k.end());
  }
  if (drawing_folder) AppendString(strings, *drawing_folder);
  for (const MeshPart& part : meshes.parts) AppendString(strings, part.name);
  for (const MeshPart& part : meshes.parts)
    for (const std::string& image : part.images) AppendString(strings, image);
  for (std::size_t p = 0; p < description.paths.size(); ++p)
    for (const auto& [time, name] : description.paths[p].events) {
      AppendString(strings, name);
      fmt::EventEntry entry{};
      entry.time = time;
      entry.path = std::uint32_t(p);
      AppendRecord(a.events, entry);
    }
  return a;
}

}  // namespace

RigSections SerialiseRig(const RigDescription& description, const PoseMeshes& meshes, const PoseAnalysis& analysis,
                         const ArapSystem& system, const WeightGrid& grid) {
  const std::optional<std::string> drawing_folder = DrawingFolder(description, meshes);
  const fmt::Meta meta = MakeMeta(description, meshes, system, grid, drawing_folder.has_value());
  const bool has_uvs = !meshes.poses[0].uvs.empty();
  std::vector<std::uint32_t> tris;
  for (const auto& t : meshes.triangles) tris.insert(tris.end(), t.begin(), t.end());
  const PoseArrays poses = FlattenPoses(meshes, system.vertex_masses);
  const NamesAndPaths names = FlattenNamesAndPaths(description, meshes, drawing_folder);
  RigSections w;
  w.Add(fmt::kMeta, RecordBytes(meta));
  w.AddArray(fmt::kTriangles, tris);
  w.AddArray(fmt::kPosePositions, poses.positions);
  w.AddArray(fmt::kPosePoints, poses.pose_points);
  w.AddArray(fmt::kPoseCentroids, poses.centroids);
  w.AddArray(fmt::kVertexMasses, system.vertex_masses);
  w.AddArray(fmt::kGradients, system.gradients);
  w.AddArray(fmt::kAngles, analysis.angles);
  w.AddArray(fmt::kStretches, analysis.stretches);
  w.AddArray(fmt::kPermutation, system.order);
  w.AddArray(fmt::kFactorColumns, system.col_start);
  w.AddArray(fmt::kFactorRows, system.row);
  w.AddArray(fmt::kFactorValues, system.value);
  w.AddArray(fmt::kFactorInvDiagonal, system.inv_diagonal);
  std::vector<double> grid_nodes = grid.weights;  // corners, then cell centres (format 1.2)
  grid_nodes.insert(grid_nodes.end(), grid.centre_weights.begin(), grid.centre_weights.end());
  w.AddArray(fmt::kWeightGrid, grid_nodes);
  w.Add(fmt::kStrings, names.strings);
  w.Add(fmt::kPaths, names.path_table);
  w.AddArray(fmt::kPathKeys, names.keys);
  if (!names.events.empty()) w.Add(fmt::kEvents, names.events);
  if (has_uvs) w.AddArray(fmt::kUVs, poses.uvs);
  if (description.anchor_given || description.facing_left) {
    // The anchor in rig units: given in the first pose's drawing pixels when it is drawn.
    fmt::PlacementRecord placement{};
    const PoseMesh& first = meshes.poses[0];
    const bool drawn = first.canvas_size.x() > 0;
    Eigen::Vector2d anchor(0, 0);
    if (description.anchor_given)
      anchor = drawn ? Eigen::Vector2d(description.anchor.x() - first.canvas_pivot.x(),
                                       first.canvas_pivot.y() - description.anchor.y())
                     : description.anchor;
    else {  // facing given alone: the default anchor, the bottom centre of pose 0
      const auto& v = first.vertices;
      double x0 = v[0].x(), x1 = v[0].x(), y0 = v[0].y();
      for (const Eigen::Vector2d& p : v) x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x()), y0 = std::min(y0, p.y());
      anchor = {(x0 + x1) / 2, y0};
    }
    placement.anchor_x = anchor.x(), placement.anchor_y = anchor.y();
    placement.flags = description.facing_left ? fmt::kPlacementFacingLeft : 0;
    std::vector<unsigned char> bytes;
    AppendRecord(bytes, placement);
    w.Add(fmt::kPlacement, bytes);
  }
  if (HasCanvases(meshes)) {
    std::vector<double> canvases;
    for (const PoseMesh& p : meshes.poses)
      canvases.insert(canvases.end(), {p.canvas_size.x(), p.canvas_size.y(), p.canvas_pivot.x(), p.canvas_pivot.y()});
    w.AddArray(fmt::kCanvases, canvases);
  }
  if (!meshes.parts.empty()) {
    std::vector<unsigned char> parts;
    for (const MeshPart& part : meshes.parts) {
      fmt::PartEntry entry{};
      entry.first_triangle = part.first_triangle;
      entry.triangle_count = part.triangle_count;
      entry.draw_order = std::int32_t(part.order);
      AppendRecord(parts, entry);
    }
    w.Add(fmt::kParts, std::move(parts));
  }
  if (DrawOrderChanges(meshes)) {
    std::vector<std::uint32_t> orders;  // pose-major
    for (std::size_t i = 0; i < meshes.poses.size(); ++i)
      for (const MeshPart& part : meshes.parts)
        orders.push_back(std::uint32_t(std::int32_t(part.pose_orders.empty() ? part.order : part.pose_orders[i])));
    w.AddArray(fmt::kPartPoseOrders, orders);
  }
  return w;
}

}  // namespace posemorph::bake
