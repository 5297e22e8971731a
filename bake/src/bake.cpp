// SPDX-License-Identifier: MIT
// The whole bake as the paper's pipeline (DESIGN.md section 2): one pass
// (bake_attempt.h), mapped again where it folds or its mesh is poor
// (map_again.h), its report and its refusals.
#include "posemorph/bake/bake.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <sstream>
#include <string>

#include "bake_attempt.h"
#include "map_again.h"
#include "posemorph/bake/bake_channels.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/mesh_quality.h"
#include "posemorph/bake/stage.h"

namespace posemorph::bake {
namespace {

// A fold inside the pose hull fails the bake unless folds are allowed.
// The fold retries left untried at mapping.retry_seconds, said; "" when none was.
std::string RetriesUntried(const RetriesLeft& left) {
  if (left.untried == 0) return "";
  std::ostringstream s;
  s << "mapping again stopped at mapping.retry_seconds (" << left.seconds << " s) with " << left.untried << " of its "
    << left.retries << " fold retries untried (0 tries them all)";
  return s.str();
}

void RefuseFolds(const RigDescription& description, const ReproductionCheck& written, const InbetweenCheck& inbetweens,
                 const RetriesLeft& left) {
  const std::size_t n = inbetweens.FoldsInHull();
  if (n == 0 || description.parameters.allow_folds) return;
  const std::string untried = RetriesUntried(left);
  throw BakeError(description.file,
                  "the in-betweens fold: " + std::to_string(n) + (n == 1 ? " triangle turns" : " triangles turn") +
                      " over (the worst: " + DescribeFold(written.rig, inbetweens.folds[0]) +
                      "); add a landmark there, or bake with --allow-folds (bake.allow_folds) to write it anyway" +
                      (untried.empty() ? "" : "; " + untried));
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
  RetriesLeft left;
  RigDescription chosen = description;
  // mapping.map_again false: the first mapping, whatever it measures.
  const bool map_again = description.mapping.map_again && first.drawings.report.mapped;
  if (map_again && first.inbetweens.FoldsInHull() > 0)
    again = MapAgainWithoutFolds(description, first.drawings.report, start, &tried, &variant, &chosen, &left);
  if (again)
    retry_warnings.push_back(file + ": the in-betweens folded (" + std::to_string(first.inbetweens.FoldsInHull()) +
                             " triangles; the worst: " + DescribeFold(first.written.rig, first.inbetweens.folds[0]) +
                             "); mapped again with " + variant + ": fold-free");
  else
    RefuseFolds(description, first.written, first.inbetweens, left);
  if (const std::string untried = RetriesUntried(left); !again && !untried.empty())
    retry_warnings.push_back(file + ": " + untried);
  std::optional<GhostingDrawings> ghosting_drawings;  // read once, when first needed
  auto drawings = [&]() -> const GhostingDrawings& {
    if (!ghosting_drawings) ghosting_drawings = ReadGhostingDrawings(description);
    return *ghosting_drawings;
  };
  std::optional<Attempt> finer, other;
  if (map_again) {
    finer = RefineFurther(chosen, again ? *again : first, drawings);
    other = MapAnotherWay(chosen, finer ? *finer : again ? *again : first, drawings);
  }
  Attempt& a = other ? *other : finer ? *finer : again ? *again : first;
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
    r.ghosting = GhostingOf(a, drawings(), file);
    r.ghosting_skipped = drawings().skipped;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  // a.written loaded the rig from a.bytes, the file's bytes.
  return BakedRig{std::move(a.sections), std::move(a.bytes), std::move(a.written.rig), std::move(a.meshes),
                  a.written.tolerance};
}

}  // namespace posemorph::bake