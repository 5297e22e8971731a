// SPDX-License-Identifier: MIT
// The whole bake as the paper's pipeline (DESIGN.md section 2): each step
// takes const input and returns its own type, in its own header.
#include "posemorph/bake/bake.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <functional>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <optional>

#include "drawing_memo.h"
#include "posemorph/bake/arap_system.h"
#include "posemorph/bake/bake_channels.h"
#include "posemorph/bake/deform_poses.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/grid_resolution.h"
#include "posemorph/bake/join_parts.h"
#include "posemorph/bake/machine_section.h"
#include "posemorph/bake/map_drawings.h"
#include "posemorph/bake/mapping/outline_image.h"
#include "posemorph/bake/mesh_quality.h"
#include "posemorph/bake/orient_triangles.h"
#include "posemorph/bake/pose_analysis.h"
#include "posemorph/bake/pose_space_weights.h"
#include "posemorph/bake/reproduction_check.h"
#include "posemorph/bake/serialise_rig.h"
#include "posemorph/bake/stage.h"
#include "posemorph/bake/validate_rig.h"
#include "posemorph/rig_format.h"
#include "drawn_pose.h"

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

// A fold inside the pose hull fails the bake unless folds are allowed.
void RefuseFolds(const RigDescription& description, const ReproductionCheck& written,
                 const InbetweenCheck& inbetweens) {
  const std::size_t n = inbetweens.FoldsInHull();
  if (n == 0 || description.parameters.allow_folds) return;
  throw BakeError(description.file,
                  "the in-betweens fold: " + std::to_string(n) + (n == 1 ? " triangle turns" : " triangles turn") +
                      " over (the worst: " + DescribeFold(written.rig, inbetweens.folds[0]) +
                      "); add a landmark there, or bake with --allow-folds (bake.allow_folds) to write it anyway");
}

// Folds that were allowed, or found only on paths outside the hull: ten, then a count.
std::vector<std::string> FoldWarnings(const std::string& file, const Rig& rig, const InbetweenCheck& inbetweens) {
  std::vector<std::string> warnings;
  const std::size_t shown = std::min<std::size_t>(inbetweens.folds.size(), 10);
  for (std::size_t k = 0; k < shown; ++k)
    warnings.push_back(file + ": the in-betweens fold" + (inbetweens.folds[k].in_hull ? " (allowed)" : "") + ": " +
                       DescribeFold(rig, inbetweens.folds[k]));
  if (inbetweens.folds.size() > shown)
    warnings.push_back(file + ": the in-betweens fold: " + std::to_string(inbetweens.folds.size() - shown) +
                       " more triangles turn over");
  return warnings;
}

// Every pose's PNG drawing, reduced for the ghosting measure (ghosting.h),
// read once per bake; `skipped` says why there are none when a pose has no
// PNG drawing (or draws another image).
struct GhostingDrawings {
  std::vector<std::vector<unsigned char>> pixels;
  std::vector<std::array<std::uint32_t, 2>> sizes;  // width, height
  std::string skipped;
};

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

// The ghosting measure of the rig written, or nothing (g.skipped says why).
Ghosting MeasureBakedGhosting(const GhostingDrawings& g, const Rig& rig, const std::string& file) {
  if (!g.skipped.empty()) return {};
  std::vector<DrawingPixels> drawings;
  for (std::size_t i = 0; i < g.pixels.size(); ++i)
    drawings.push_back({g.sizes[i][0], g.sizes[i][1], g.pixels[i].data()});
  return MeasureGhosting(rig, drawings, file);
}

std::uint64_t LowerNonzeros(const Eigen::SparseMatrix<double>& K) {
  std::uint64_t n = 0;
  for (int c = 0; c < K.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, c); it; ++it) n += it.row() >= c;
  return n;
}

// One pass of the pipeline, up to the in-between check; what the report needs.
struct Attempt {
  MappedDrawings drawings;
  PoseMeshes meshes;
  std::uint64_t factor_nonzeros = 0, matrix_nonzeros = 0;
  int grid_cells_x = 0, grid_cells_y = 0;
  bool grid_coarsened = false;       // a coarser grid than the default (grid_resolution.h)
  double grid_move_px = 0;           // and its estimate
  std::uint64_t exact_bytes = 0;     // the exact encoding's file size
  RigSections sections;              // what is written: the exact or the compact encoding
  std::vector<unsigned char> bytes;  // WriteRig(sections), as the verification loaded them
  CompactSettings compact_settings;
  CompactReport compact;
  bool is_compact = false;
  ReproductionCheck written;
  InbetweenCheck inbetweens;
  std::vector<std::string> weight_warnings;
  std::vector<std::uint32_t> joints;  // a layered character's glue joints (join_parts.h)
};

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
  weight_parameters.grid_resolution =
      ChooseGridResolution(points, names, description.parameters, file, meshes, a.compact_settings.pixels_per_unit,
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

// The mapping variants tried, in order, when the in-betweens fold: coarser
// matching, longer edges, both.
struct FoldRetry {
  double spacing_scale, edge_scale;
  bool fill_notches;
  const char* name;
};
constexpr FoldRetry kFoldRetries[] = {{2, 1, false, "matched-sample spacing x2"},
                                      {1, 1.5, false, "longest edge x1.5"},
                                      {2, 1.5, false, "spacing x2, longest edge x1.5"},
                                      {1, 1, true, "the outlines' thin notches filled"},
                                      {2, 1, true, "thin notches filled, spacing x2"},
                                      {1, 1.5, true, "thin notches filled, longest edge x1.5"},
                                      {2, 1.5, true, "thin notches filled, spacing x2, longest edge x1.5"}};

// Fold retry k's description: `description` with kFoldRetries[k]'s
// settings; nothing when it would map the same as the description.
std::optional<RigDescription> FoldRetryVariant(const RigDescription& description, int k) {
  RigDescription variant = description;
  variant.mapping.spacing_scale = kFoldRetries[k].spacing_scale;
  variant.mapping.edge_scale = kFoldRetries[k].edge_scale;
  if (kFoldRetries[k].fill_notches) {
    if (!TracesPngOutline(description)) return std::nullopt;  // nothing is traced from a PNG: the same mapping
    variant.mapping.fill_notches = true;
  }
  return variant;
}

// The first variant's bake whose in-betweens do not fold in the hull, with
// *tried set to its place in kFoldRetries + 1 and *chosen to its description;
// nothing when none does (a variant that cannot be baked at all is passed
// over).
std::optional<Attempt> MapAgainWithoutFolds(const RigDescription& description, int* tried, std::string* name,
                                            RigDescription* chosen) {
  for (int k = 0; k < int(std::size(kFoldRetries)); ++k) {
    std::optional<RigDescription> variant = FoldRetryVariant(description, k);
    if (!variant) continue;
    std::optional<Attempt> again;
    try {
      again = BakeOnce(*variant);
    } catch (const BakeError&) {
      continue;
    }
    if (again->inbetweens.FoldsInHull() == 0) {
      *tried = k + 1;
      *name = kFoldRetries[k].name;
      *chosen = std::move(*variant);
      return again;
    }
  }
  return std::nullopt;
}

// The quality floor: a mapped mesh whose smallest angle over all poses is
// below half of mapping.min_angle (10 degrees by default) is mapped again
// in the ways of kFurtherRefinements (refinement stops early once every
// angle reaches min_angle) until one reaches the floor. The best of them is
// kept when its in-betweens do not fold either and its smallest angle is
// larger; otherwise the first one stays. (Splitting more
// where one pose squeezes the outline, as an arm against the body does, can
// fold the in-betweens; trying the fold retries' variants too cost up to
// eight more mappings and gained nothing on the game-art corpus.) A mesh
// below a quarter of the floor (2.5 degrees) is not mapped again: such an
// angle comes from a squeeze or an outline finer than any split lifts, and
// mapping again only doubled the bake (a 1024-pixel star at 0.77 degrees:
// 3.3 s more, nothing kept).
constexpr int kFurtherRefinementRounds = 16;
// The ways tried, the best kept: more rounds of splitting; the usual rounds
// with the boundary vertices that make slivers removed (a short boundary
// edge where one pose squeezes the outline leaves a sliver no split lifts:
// Pip drawn at 1024 px, 5.1 -> 11.0 degrees).
struct FurtherRefinement {
  int rounds;
  bool collapse_slivers;
  int smoothing;  // MappingParameters::correspondence_smoothing
  const char* name;
};
// Then the outlines' correspondence averaged over 24, then 12, matched
// samples on each side (mapping/boundary_matching.h): where one pose
// squeezes the outline against another (an arm against the body in one,
// raised in the other), matching by bending alone gave many samples of one
// outline to one of the other (tux-yes: an edge of 0.31 px in 'down', 1.5
// px in 'up'). With 24: tux-yes 6.8 -> 12.4 degrees, its ghosting over the
// pose hull 24.4 -> 12.3; cat-walk 8.8 -> 15.1 degrees, 12.9 -> 8.7. The
// outcome swings with the width (tux-yes, 4 rounds, at 8 / 10 / 14 / 16 /
// 20 / 24: 10.1 / 8.4 / 10.4 / 10.3 / 10.8 / 12.4 degrees, folding at 8 and
// 10, ghosting 32.4 and 32.9 at 14 and 16), so a second width is tried.
// Not the default: on Pip and Sprout (8 samples) it cross-fades worse, 4.37
// -> 4.70 and 3.10 -> 3.95 over the pose hull.
constexpr int kFurtherSmoothing[] = {24, 12};
// A finer mesh whose ghosting over the pose hull (ghosting.h) is more than
// 5% worse than the first's is not kept: on the game-art corpus removing
// slivers lifted cat-springboots 12.8 -> 16.3 degrees and cat-walk 8.8 ->
// 9.9 but cross-faded 15% and 7% worse.
constexpr double kFurtherGhostingSlack = 1.05;
// In this order; once one lifts the mesh over the floor, the rest are not tried.
constexpr FurtherRefinement kFurtherRefinements[] = {
    {4, true, 0, "slivers at the boundary removed"},
    {kFurtherRefinementRounds, false, 0, "16 rounds of splitting"},
    {4, false, kFurtherSmoothing[0], "the outlines' correspondence smoothed over 24 samples"},
    {kFurtherRefinementRounds, false, kFurtherSmoothing[0],
     "the outlines' correspondence smoothed over 24 samples, 16 rounds"},
    {4, false, kFurtherSmoothing[1], "the outlines' correspondence smoothed over 12 samples"},
    {kFurtherRefinementRounds, false, kFurtherSmoothing[1],
     "the outlines' correspondence smoothed over 12 samples, 16 rounds"}};

double QualityFloor(const MappingParameters& m) { return m.min_angle / 2; }

std::optional<Attempt> RefineFurther(const RigDescription& chosen, const Attempt& a,
                                     const std::function<const GhostingDrawings&()>& drawings) {
  const MappingReport& m = a.drawings.report;
  const double floor = QualityFloor(chosen.mapping);
  if (!m.mapped || m.min_angle_degrees >= floor || m.min_angle_degrees < floor / 4 ||
      chosen.mapping.refinement_rounds >= kFurtherRefinementRounds || chosen.mapping.collapse_slivers ||
      chosen.mapping.correspondence_smoothing > 0)
    return std::nullopt;
  std::optional<Attempt> best;
  const char* how = "";
  // The ghosting of the first mesh, where it can be measured: a finer mesh
  // that cross-fades worse is not kept.
  const GhostingDrawings& g = drawings();
  const Ghosting before = MeasureBakedGhosting(g, a.written.rig, chosen.file);
  // The smoothed correspondence only where a pose squeezes the worst
  // triangle (not, say, on a spiral finer than any split lifts: 20,000
  // outline points, a second per mapping).
  const bool squeezed = Squeezed(FindSmallestAngle(a.written.rig));
  for (const auto& [rounds, collapse, smoothing, name] : kFurtherRefinements) {
    if (smoothing > 0 && !squeezed) continue;
    RigDescription finer = chosen;
    finer.mapping.refinement_rounds = rounds;
    finer.mapping.collapse_slivers = collapse;
    finer.mapping.correspondence_smoothing = smoothing;
    std::optional<Attempt> b;
    try {
      b = BakeOnce(finer);
    } catch (const BakeError&) {
      continue;
    }
    const double angle = b->drawings.report.min_angle_degrees;
    if (b->inbetweens.FoldsInHull() > 0 ||
        angle <= (best ? best->drawings.report.min_angle_degrees : m.min_angle_degrees))
      continue;
    if (!before.hull.empty() &&
        MeasureBakedGhosting(g, b->written.rig, chosen.file).hull_mean > before.hull_mean * kFurtherGhostingSlack)
      continue;
    best = std::move(b);
    how = name;
    if (angle >= floor) break;
  }
  if (best) {
    best->drawings.report.refined_further_from = m.min_angle_degrees;
    best->drawings.report.refined_further_by = how;
  }
  return best;
}

// Mapping by deformation (mapping/mesh_registration.h), the other way to
// make the meshes: where the compatible triangulation's mesh is between the
// quality floor and mapping.min_angle, the drawings are mapped again by deforming pose 0's
// mesh onto the others, and that mesh is kept when its in-betweens do not
// fold, its smallest angle reaches kRegistrationGain times the first's (or
// min_angle) and it cross-fades at most 5% worse (kFurtherGhostingSlack).
// Alone, on the game-art corpus it lifted tux-relax 12.1 -> 18.6 degrees
// and gnujump-hero 12.9 -> 19.0 (but ghosting 5.77 -> 7.46), folded the
// in-betweens of tux-egypt and cat-walk, and cross-faded Sprout 40% worse
// (3.10 -> 4.36) at 20 degrees: not the only way.
// Not below the floor: refining further has mapped such a mesh several
// times already (a spiral of 20,000 outline points at 8.9 degrees: 4.5 -> 10
// s of CPU, past the hostile corpus's bound), and on the corpus registration
// was never kept there.
// A clear gain only: the registered mesh's angle swings with small changes
// of the drawing (Pip drawn at 256 / 512 / 4096 px: 12.1 / 2.9 / 9.3
// degrees, against 10.4 / 10.6 / 11.0 triangulated compatibly), so a gain
// of a few degrees would pick one way at one size and the other at the next.
constexpr double kRegistrationGain = 1.25;
std::optional<Attempt> MapByRegistration(const RigDescription& chosen, const Attempt& a,
                                         const std::function<const GhostingDrawings&()>& drawings) {
  const MappingReport& m = a.drawings.report;
  const double goal = chosen.mapping.min_angle;
  if (!m.mapped || chosen.mapping.registration || m.min_angle_degrees >= goal ||
      m.min_angle_degrees < QualityFloor(chosen.mapping))
    return std::nullopt;
  RigDescription registered = chosen;
  registered.mapping.registration = true;
  std::optional<Attempt> b;
  try {
    b = BakeOnce(registered);
  } catch (const BakeError&) {
    return std::nullopt;
  }
  if (b->inbetweens.FoldsInHull() > 0 ||
      std::min(b->drawings.report.min_angle_degrees, goal) < std::min(m.min_angle_degrees * kRegistrationGain, goal))
    return std::nullopt;
  const GhostingDrawings& g = drawings();
  const Ghosting before = MeasureBakedGhosting(g, a.written.rig, chosen.file);
  if (!before.hull.empty() &&
      MeasureBakedGhosting(g, b->written.rig, chosen.file).hull_mean > before.hull_mean * kFurtherGhostingSlack)
    return std::nullopt;
  b->drawings.report.registered_over = m.min_angle_degrees;
  return b;
}

}  // namespace

std::vector<unsigned char> BakeRig(const RigDescription& description, BakeReport* report) {
  if (description.channels.size() > 1) return BakeCharacter(description, report);
  BakedRig baked = BakeOne(description, report);  // with its state machine, if any, verified in the one load
  if (report) report->drawings = ReadRigDrawings(baked.rig);
  return std::move(baked.bytes);
}

BakedRig BakeOne(const RigDescription& description, BakeReport* report) {
  if (description.channels.size() > 1)
    throw BakeError(description.file, "internal: BakeOne bakes one pose space; this description has channels");
  const auto start = std::chrono::steady_clock::now();
  const std::string& file = description.file;
  Attempt first = BakeOnce(description);
  std::vector<std::string> retry_warnings;
  int tried = 0;
  std::string variant;
  std::optional<Attempt> again;
  RigDescription chosen = description;
  if (first.inbetweens.FoldsInHull() > 0 && first.drawings.report.mapped)
    again = MapAgainWithoutFolds(description, &tried, &variant, &chosen);
  if (!again && first.inbetweens.FoldsInHull() > 0 && first.drawings.report.mapped &&
      !description.mapping.registration) {
    // No coarser mapping is fold-free: the mapping by deformation is tried.
    RigDescription registered = description;
    registered.mapping.registration = true;
    try {
      Attempt b = BakeOnce(registered);
      if (b.inbetweens.FoldsInHull() == 0) {
        again = std::move(b);
        tried = int(std::size(kFoldRetries)) + 1;
        variant = "the first pose's mesh deformed onto the others (registration)";
        chosen = std::move(registered);
      }
    } catch (const BakeError&) {
    }
  }
  if (again)
    retry_warnings.push_back(file + ": the in-betweens folded (" + std::to_string(first.inbetweens.FoldsInHull()) +
                             " triangles; the worst: " + DescribeFold(first.written.rig, first.inbetweens.folds[0]) +
                             "); mapped again with " + variant + ": fold-free");
  else
    RefuseFolds(description, first.written, first.inbetweens);
  std::optional<GhostingDrawings> ghosting_drawings;  // read once, when first needed
  auto drawings = [&]() -> const GhostingDrawings& {
    if (!ghosting_drawings) ghosting_drawings = ReadGhostingDrawings(description);
    return *ghosting_drawings;
  };
  std::optional<Attempt> finer = RefineFurther(chosen, again ? *again : first, drawings);
  std::optional<Attempt> registered = MapByRegistration(chosen, finer ? *finer : again ? *again : first, drawings);
  Attempt& a = registered ? *registered : finer ? *finer : again ? *again : first;
  const PoseMeshes& meshes = a.meshes;

  if (report) {
    BakeReport& r = *report;
    r = BakeReport{};
    r.vertices = std::uint32_t(meshes.poses[0].vertices.size());
    r.triangles = std::uint32_t(meshes.triangles.size());
    r.poses = std::uint32_t(meshes.poses.size());
    r.paths = std::uint32_t(description.paths.size());
    r.parts = meshes.parts;
    r.joints = a.joints;
    r.factor_nonzeros = a.factor_nonzeros;
    r.matrix_nonzeros = a.matrix_nonzeros;
    r.grid_cells_x = std::uint32_t(a.grid_cells_x);
    r.grid_cells_y = std::uint32_t(a.grid_cells_y);
    r.grid_coarsened = a.grid_coarsened;
    r.grid_move_px = a.grid_move_px;
    r.bytes = a.bytes.size();
    r.max_reproduction_error = a.written.max_error;
    r.compact = a.is_compact;
    r.exact_bytes = a.exact_bytes;
    r.max_error_px = description.parameters.compact ? description.parameters.max_error_px : 0;
    r.pixels_per_unit = description.parameters.compact ? a.compact_settings.pixels_per_unit : 0;
    r.compact_report = a.compact;
    r.warnings = retry_warnings;
    for (const std::string& w : a.weight_warnings) r.warnings.push_back(w);
    for (std::string& w : FoldWarnings(file, a.written.rig, a.inbetweens)) r.warnings.push_back(std::move(w));
    const double floor = QualityFloor(chosen.mapping);
    if (a.drawings.report.mapped && a.drawings.report.min_angle_degrees < floor)
      r.warnings.push_back(file + ": " + DescribeSmallestAngle(a.written.rig, FindSmallestAngle(a.written.rig), floor));
    r.inbetweens = a.inbetweens;
    r.mapping = a.drawings.report;
    r.mapping.fold_retries = tried;
    BakeStage ghosting_stage("measuring the ghosting");
    r.ghosting = MeasureBakedGhosting(drawings(), a.written.rig, file);
    r.ghosting_skipped = drawings().skipped;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  // a.written loaded the rig from a.bytes, the file's bytes.
  return BakedRig{std::move(a.sections), std::move(a.bytes), std::move(a.written.rig), std::move(a.meshes),
                  a.written.tolerance};
}

}  // namespace posemorph::bake
