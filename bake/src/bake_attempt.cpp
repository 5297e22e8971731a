// SPDX-License-Identifier: MIT
// One pass of the bake's pipeline (bake_attempt.h), in the order of
// DESIGN.md section 2: each step takes const input and returns its own
// type, in its own header.
#include "bake_attempt.h"

#include <algorithm>

#include "drawing_memo.h"
#include "drawn_pose.h"
#include "posemorph/bake/arap_system.h"
#include "posemorph/bake/deform_poses.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/grid_resolution.h"
#include "posemorph/bake/join_parts.h"
#include "posemorph/bake/machine_section.h"
#include "posemorph/bake/orient_triangles.h"
#include "posemorph/bake/pose_analysis.h"
#include "posemorph/bake/pose_space_weights.h"
#include "posemorph/bake/serialise_rig.h"
#include "posemorph/bake/stage.h"
#include "posemorph/bake/validate_rig.h"
#include "posemorph/rig_format.h"

namespace posemorph::bake {
namespace {

// The compact encoding's budget in rig units: drawing pixels are rig units
// when the poses come from drawings; otherwise bake.pixels_per_unit, or the
// rig's size counted as 1024 pixels.
CompactSettings CompactSettingsFor(const BakeParameters& parameters, const PoseMeshes& meshes) {
  CompactSettings settings;
  settings.max_error_px = parameters.max_error_px;
  settings.pixels_per_unit = HasCanvases(meshes)              ? 1.0
                             : parameters.pixels_per_unit > 0 ? parameters.pixels_per_unit
                                                              : 1024.0 / RigBoundingBoxDiagonal(meshes);
  return settings;
}

std::uint64_t LowerNonzeros(const Eigen::SparseMatrix<double>& K) {
  std::uint64_t n = 0;
  for (int c = 0; c < K.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, c); it; ++it) n += it.row() >= c;
  return n;
}

}  // namespace

Attempt BakeOnce(const RigDescription& description) {
  Attempt a;
  const std::string& file = description.file;
  BakeStage stage("mapping the drawings");
  if (description.parts.empty()) {
    a.drawings = MapDrawings(description);
    BakeStage deform_stage("deforming poses");
    a.meshes = DeformPoses(description, a.drawings);
  } else {
    JoinedParts joined = JoinParts(description);
    a.meshes = std::move(joined.meshes);
    a.drawings.report = std::move(joined.report);
    a.joints = std::move(joined.joints);
  }
  PoseMeshes& meshes = a.meshes;
  BakeStage validate_stage("validating the rig");
  meshes.triangles = OrientTriangles(meshes);
  if (const std::optional<std::string> problem = ValidateRig(meshes, description.paths))
    throw BakeError(file, *problem);
  const PoseAnalysis analysis = AnalysePoses(meshes);
  BakeStage arap_stage("building and factoring the ARAP system");
  const ArapSystem system = BuildArapSystem(meshes.poses[0].vertices, meshes.triangles, file);
  BakeStage weights_stage("solving the pose-space weights");
  std::vector<Eigen::Vector2d> points;
  std::vector<std::string> names;
  for (const PoseMesh& p : meshes.poses) points.push_back(p.point), names.push_back(p.name);
  a.compact_settings = CompactSettingsFor(description.parameters, meshes);
  BakeParameters weight_parameters = description.parameters;
  // Where the bake chooses the resolution, it narrows a line layout's grid too.
  weight_parameters.narrow_line_layout = GridResolutionIsAutomatic(description.parameters);
  weight_parameters.grid_resolution =
      ChooseGridResolution(points, names, weight_parameters, file, meshes, a.compact_settings.pixels_per_unit,
                           &a.grid_coarsened, &a.grid_move_px);
  weight_parameters.grid_resolution_given = true;
  const WeightGrid grid = SolvePoseSpaceWeights(points, names, weight_parameters, file, &a.weight_warnings);
  BakeStage write_stage("writing and encoding the rig");
  RigSections exact = SerialiseRig(description, meshes, analysis, system, grid);
  a.exact_bytes = RigFileSize(exact);
  if (description.parameters.compact) {
    BakeStage compact_stage("encoding the rig compactly");
    a.sections = CompactRig(exact, a.compact_settings, file, &a.compact);
  } else {
    a.sections = std::move(exact);
  }
  // A state machine joins the file before its one verification: the
  // runtime checks it (and the paths it names) in the load below.
  if (!description.state_machine.layers.empty())
    a.sections.Add(format::kMachine, MachineSection(description.state_machine));
  a.bytes = WriteRig(a.sections);
  a.is_compact = description.parameters.compact && !a.compact.fell_back;
  BakeStage check_stage("checking the baked rig");
  const double tolerance = std::max(
      1e-6, a.is_compact
                ? a.compact_settings.max_error_px / a.compact_settings.pixels_per_unit / RigBoundingBoxDiagonal(meshes)
                : 0.0);
  a.written = CheckReproduction(a.bytes, meshes, tolerance, file);
  BakeStage inbetween_stage("checking the in-betweens for folds");
  a.inbetweens = CheckInbetweens(a.written.rig, file);
  a.factor_nonzeros = system.value.size();
  a.matrix_nonzeros = LowerNonzeros(system.K);
  a.grid_cells_x = grid.cells_x;
  a.grid_cells_y = grid.cells_y;
  return a;
}

GhostingDrawings ReadGhostingDrawings(const RigDescription& description) {
  GhostingDrawings g;
  if (!description.parts.empty()) {
    g.skipped = "the rig is drawn as parts, and the measure takes one drawing per pose";
    return g;
  }
  for (std::size_t i = 0; i < description.poses.size(); ++i) {
    const PoseDescription& pose = description.poses[i];
    const std::string& d = pose.drawing;
    const bool png = IsRasterDrawing(d);  // a PNG, or a layer of a layered file: pixels too
    if (!pose.drawn || !pose.vertices.empty() || !png) {
      return GhostingDrawings{{}, {}, "pose '" + pose.name + "' has no PNG drawing"};
    }
    if (!pose.image.empty() && pose.image != pose.drawing) {
      return GhostingDrawings{
          {}, {}, "pose '" + pose.name + "' draws another image than the PNG drawing it was mapped from"};
    }
    std::uint32_t w = 0, h = 0;
    g.pixels.push_back(GhostingDrawingOf(
        pose.drawing_path, ErrorSource(description.file, "pose '" + pose.name + "': " + pose.drawing_path), &w, &h));
    g.sizes.push_back({w, h});
  }
  return g;
}

const Ghosting& GhostingOf(Attempt& a, const GhostingDrawings& g, const std::string& file) {
  if (a.ghosting) return *a.ghosting;
  Ghosting measured;
  if (g.skipped.empty()) {
    std::vector<DrawingPixels> drawings;
    for (std::size_t i = 0; i < g.pixels.size(); ++i)
      drawings.push_back({g.sizes[i][0], g.sizes[i][1], g.pixels[i].data()});
    measured = MeasureGhosting(a.written.rig, drawings, file);
  }
  return a.ghosting.emplace(std::move(measured));
}

}  // namespace posemorph::bake
