// SPDX-License-Identifier: MIT
#include "posemorph/bake/bake.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sys/stat.h>
#include <unistd.h>

#include "posemorph/bake/arap_system.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/inbetween_check.h"
#include "posemorph/bake/pose_space_samples.h"
#include "posemorph/bake/stage.h"
#include "posemorph/bake/pose_space_weights.h"
#include "posemorph/bake/triangle_math.h"
#include "posemorph/jobs.h"
#include "posemorph/rig.h"
#include "posemorph/rig_format.h"
#include "rig_writer.h"

namespace posemorph::bake {
namespace {

namespace fmt = format;

// Rotation angle and stretch of every triangle in every pose, relative to pose
// 0, with angles unwrapped over the triangle adjacency (triangle-major).
void AnalysePoses(const RigDescription& rig, std::vector<double>& angles, std::vector<double>& shears) {
  const std::size_t T = rig.triangles.size(), N = rig.poses.size();
  const auto neighbours = EdgeNeighbours(rig.triangles);
  angles.assign(T * N, 0);
  shears.assign(T * N * 3, 0);
  std::vector<Eigen::Matrix2d> rest_inverse(T);
  std::vector<double> rest_areas(T);
  for (std::size_t t = 0; t < T; ++t) {
    rest_inverse[t] = EdgeMatrix(rig.poses[0].vertices, rig.triangles[t]).inverse();
    rest_areas[t] = std::abs(SignedArea(rig.poses[0].vertices, rig.triangles[t]));
  }
  std::vector<double> pose_angles(T);
  for (std::size_t i = 0; i < N; ++i) {
    std::vector<Eigen::Matrix2d> S(T);
    for (std::size_t t = 0; t < T; ++t) {
      // Validation guarantees det > 0 (no flipped triangle), so the split exists.
      const PolarSplit split = PolarDecompose(EdgeMatrix(rig.poses[i].vertices, rig.triangles[t]) * rest_inverse[t]);
      pose_angles[t] = split.alpha;
      S[t] = split.S;
    }
    UnwrapAngles(neighbours, rest_areas, pose_angles);
    for (std::size_t t = 0; t < T; ++t) {
      angles[t * N + i] = pose_angles[t];
      shears[(t * N + i) * 3 + 0] = S[t](0, 0);
      shears[(t * N + i) * 3 + 1] = S[t](0, 1);
      shears[(t * N + i) * 3 + 2] = S[t](1, 1);
    }
  }
}

template <typename T>
std::vector<unsigned char> Bytes(const T& value) {
  std::vector<unsigned char> out(sizeof(T));
  std::memcpy(out.data(), &value, sizeof(T));
  return out;
}

}  // namespace

std::vector<unsigned char> BakeRig(RigDescription& rig, BakeReport* report) {
  const auto start = std::chrono::steady_clock::now();
  {
    BakeStage stage("mapping the drawings and deforming poses");
    ResolveDeformedPoses(rig);
  }
  BakeStage stage("validating the rig");
  ValidateRigDescription(rig);
  const std::size_t V = rig.poses[0].vertices.size(), T = rig.triangles.size(), N = rig.poses.size();
  const Points& rest = rig.poses[0].vertices;

  std::vector<double> angles, shears;
  AnalysePoses(rig, angles, shears);
  BakeStage arap_stage("building and factoring the ARAP system");
  const ArapSystem sys = BuildArapSystem(rest, rig.triangles, rig.file);

  std::vector<Eigen::Vector2d> points;
  std::vector<std::string> names;
  for (const auto& p : rig.poses) {
    points.push_back(p.point);
    names.push_back(p.name);
  }
  BakeStage weights_stage("solving the pose-space weights");
  const WeightGrid grid = SolvePoseSpaceWeights(points, names, rig.parameters, rig.file);
  BakeStage write_stage("writing and encoding the rig");

  Eigen::AlignedBox2d box;
  for (const auto& v : rest) box.extend(v);

  fmt::Meta meta{};
  meta.vertex_count = std::uint32_t(V);
  meta.triangle_count = std::uint32_t(T);
  meta.pose_count = std::uint32_t(N);
  meta.path_count = std::uint32_t(rig.paths.size());
  meta.grid_cells_x = grid.cells_x;
  meta.grid_cells_y = grid.cells_y;
  meta.factor_nonzeros = std::uint32_t(sys.value.size());
  const bool has_uvs = !rig.poses[0].uvs.empty();
  meta.flags = (has_uvs ? fmt::kMetaFlagHasUVs : 0) | (grid.centre_weights.empty() ? 0 : fmt::kMetaFlagGridCentres) |
               (rig.nearest_filter ? fmt::kMetaFlagNearestFilter : 0);
  meta.grid_origin_x = grid.origin_x;
  meta.grid_origin_y = grid.origin_y;
  meta.grid_cell_size = grid.cell;
  meta.default_sigma = rig.parameters.sigma;
  meta.rig_size = box.diagonal().norm();

  std::vector<std::uint32_t> tris;
  for (const auto& t : rig.triangles) tris.insert(tris.end(), t.begin(), t.end());
  std::vector<double> positions, pose_points, centroids;
  std::vector<float> uvs;
  for (const auto& p : rig.poses) {
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (std::size_t v = 0; v < V; ++v) {
      positions.push_back(p.vertices[v].x());
      positions.push_back(p.vertices[v].y());
      c += sys.vertex_masses[v] * p.vertices[v];
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
  std::vector<unsigned char> strings, path_table;
  std::vector<double> keys;
  for (const auto& p : rig.poses) AppendString(strings, p.name);
  for (const auto& p : rig.poses) AppendString(strings, p.image);
  for (const auto& path : rig.paths) {
    AppendString(strings, path.name);
    const std::uint32_t entry[2] = {std::uint32_t(path.keys.size()),
                                    (path.loop ? fmt::kPathFlagLoop : 0u) |
                                        (std::uint32_t(path.catmull_rom ? PathInterpolation::kCatmullRom : PathInterpolation::kLinear)
                                         << fmt::kPathInterpolationShift)};
    const auto* e = reinterpret_cast<const unsigned char*>(entry);
    path_table.insert(path_table.end(), e, e + sizeof(entry));
    for (const auto& k : path.keys) keys.insert(keys.end(), k.begin(), k.end());
  }

  RigWriter w;
  w.Add(fmt::kMeta, Bytes(meta));
  w.AddArray(fmt::kTriangles, tris);
  w.AddArray(fmt::kPosePositions, positions);
  w.AddArray(fmt::kPosePoints, pose_points);
  w.AddArray(fmt::kPoseCentroids, centroids);
  w.AddArray(fmt::kVertexMasses, sys.vertex_masses);
  w.AddArray(fmt::kGradients, sys.gradients);
  w.AddArray(fmt::kAngles, angles);
  w.AddArray(fmt::kShears, shears);
  w.AddArray(fmt::kPermutation, sys.order);
  w.AddArray(fmt::kFactorColumns, sys.col_start);
  w.AddArray(fmt::kFactorRows, sys.row);
  w.AddArray(fmt::kFactorValues, sys.value);
  w.AddArray(fmt::kFactorInvDiagonal, sys.inv_diagonal);
  std::vector<double> grid_nodes = grid.weights;  // corners, then cell centres (format 1.2)
  grid_nodes.insert(grid_nodes.end(), grid.centre_weights.begin(), grid.centre_weights.end());
  w.AddArray(fmt::kWeightGrid, grid_nodes);
  w.Add(fmt::kStrings, strings);
  w.Add(fmt::kPaths, path_table);
  w.AddArray(fmt::kPathKeys, keys);
  if (has_uvs) w.AddArray(fmt::kUVs, uvs);
  std::vector<double> canvases;
  bool any_canvas = false;
  for (const auto& p : rig.poses) {
    canvases.insert(canvases.end(), {p.canvas_size.x(), p.canvas_size.y(), p.canvas_pivot.x(), p.canvas_pivot.y()});
    any_canvas |= p.canvas_size.x() > 0;
  }
  if (any_canvas) w.AddArray(fmt::kCanvases, canvases);
  std::vector<unsigned char> bytes = w.Finish();
  const std::uint64_t exact_bytes = bytes.size();

  // The compact encoding, within the error budget of the exact one.
  double tolerance = 1e-6;  // pose reproduction, relative to the rig size
  double pixels_per_unit = 0;
  CompactReport compact_report;
  if (rig.parameters.compact) {
    CompactSettings settings;
    settings.max_error_px = rig.parameters.max_error_px;
    pixels_per_unit = any_canvas ? 1.0
                      : rig.parameters.pixels_per_unit > 0 ? rig.parameters.pixels_per_unit
                                                           : 1024.0 / meta.rig_size;
    settings.pixels_per_unit = pixels_per_unit;
    bytes = CompactRig(bytes, settings, rig.file, &compact_report);
    if (!compact_report.fell_back)
      tolerance = std::max(tolerance, settings.max_error_px / pixels_per_unit / meta.rig_size);
  }

  // Check what we wrote with the runtime that will read it: it loads, and
  // evaluating at each pose point gives that pose back.
  BakeStage check_stage("checking the baked rig");
  Rig loaded;
  Error err;
  if (!LoadRig(bytes.data(), bytes.size(), &loaded, &err))
    throw BakeError(rig.file, std::string("internal error: the baked rig does not load: ") + err.message);
  std::vector<double> x;
  double worst = 0;
  for (std::size_t i = 0; i < N; ++i) {
    if (!EvaluateFrame(loaded, points[i], x)) throw BakeError(rig.file, "internal error: the baked rig does not evaluate");
    for (std::size_t v = 0; v < V; ++v)
      worst = std::max(worst, (Eigen::Vector2d(x[2 * v], x[2 * v + 1]) - rig.poses[i].vertices[v]).norm());
  }
  worst /= meta.rig_size;
  if (!(worst <= tolerance))
    throw BakeError(rig.file, "internal error: the baked rig reproduces its poses only to " + std::to_string(worst) + " of its size");

  // The in-betweens: no triangle may turn over between the poses.
  BakeStage inbetween_stage("checking the in-betweens for folds");
  InbetweenCheck inbetweens = CheckInbetweens(loaded, rig.file);
  const std::size_t folds_in_hull = inbetweens.FoldsInHull();
  if (folds_in_hull > 0 && !rig.parameters.allow_folds) {
    const std::size_t n = folds_in_hull;
    throw BakeError(rig.file, "the in-betweens fold: " + std::to_string(n) + (n == 1 ? " triangle turns" : " triangles turn") +
                                  " over (the worst: " + DescribeFold(loaded, inbetweens.folds[0]) +
                                  "); add a landmark there, or bake with --allow-folds (bake.allow_folds) to write it anyway");
  }

  if (report) {
    report->vertices = std::uint32_t(V);
    report->triangles = std::uint32_t(T);
    report->poses = std::uint32_t(N);
    report->paths = std::uint32_t(rig.paths.size());
    report->factor_nonzeros = sys.value.size();
    report->matrix_nonzeros = 0;
    for (int c = 0; c < sys.K.outerSize(); ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(sys.K, c); it; ++it) report->matrix_nonzeros += it.row() >= c;
    report->grid_cells_x = grid.cells_x;
    report->grid_cells_y = grid.cells_y;
    report->bytes = bytes.size();
    report->max_reproduction_error = worst;
    report->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report->compact = rig.parameters.compact && !compact_report.fell_back;
    report->exact_bytes = exact_bytes;
    report->max_error_px = rig.parameters.compact ? rig.parameters.max_error_px : 0;
    report->pixels_per_unit = pixels_per_unit;
    report->compact_report = compact_report;
    report->warnings.clear();
    const std::size_t shown = std::min<std::size_t>(inbetweens.folds.size(), 10);
    for (std::size_t k = 0; k < shown; ++k)
      report->warnings.push_back(rig.file + ": the in-betweens fold" + (inbetweens.folds[k].in_hull ? " (allowed)" : "") +
                                 ": " + DescribeFold(loaded, inbetweens.folds[k]));
    if (inbetweens.folds.size() > shown)
      report->warnings.push_back(rig.file + ": the in-betweens fold: " + std::to_string(inbetweens.folds.size() - shown) +
                                 " more triangles turn over");
    report->inbetweens = std::move(inbetweens);
  }
  return bytes;
}

void WriteFileAtomic(const std::string& path, const std::vector<unsigned char>& bytes) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw BakeError(path, "cannot write: folder " + dir.string() + " does not exist");
  // A unique temporary beside the target: rename is atomic only within one file system.
  std::string tmp = (dir / ("." + target.filename().string() + ".XXXXXX")).string();
  const int fd = mkstemp(tmp.data());
  if (fd < 0) throw BakeError(path, "cannot create a temporary file in " + dir.string());
  bool ok = ::fchmod(fd, 0644) == 0;
  std::size_t written = 0;
  while (ok && written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n <= 0) ok = false;
    else written += std::size_t(n);
  }
  ok = ok && ::fsync(fd) == 0;
  ok = (::close(fd) == 0) && ok;
  ok = ok && std::rename(tmp.c_str(), path.c_str()) == 0;
  if (!ok) {
    std::remove(tmp.c_str());
    throw BakeError(path, "cannot write the file");
  }
}

}  // namespace posemorph::bake
