// SPDX-License-Identifier: MIT
// posemorph-bake RIG.json: bake a rig description.
#include "commands.h"

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <optional>
#include <sstream>
#include <vector>

#include "command_args.h"
#include "textured_sheet.h"
#include "progress_line.h"
#include "posemorph/bake/bake.h"
#include "posemorph/bake/input_file.h"
#include "posemorph/bake/run_each.h"
#include "posemorph/bake/stage.h"

namespace posemorph::bake::cli {

int BakeCommand(const std::vector<std::string>& a, std::size_t from, std::ostream& report_out, std::ostream& err) {
  const Args args = Args::Parse(a, from, {"-o", "--precision", "--max-error"},
                                {"--allow-folds", "--no-align", "--map-once", "--quiet", "--no-atlas"});
  // --quiet: no progress line and no report; warnings and errors still go to stderr.
  const bool quiet = args.switches.count("--quiet") > 0;
  std::ostringstream discarded;
  std::ostream& out = quiet ? discarded : report_out;
  if (args.positional.empty()) throw UsageError("no rig description given");
  std::string output;
  if (const std::string* o = args.Get("-o")) {
    output = *o;
  } else {
    output = args.positional;
    const auto dot = output.rfind('.');
    if (dot != std::string::npos && output.find('/', dot) == std::string::npos) output.resize(dot);
    output += ".pmrig";
  }
  CheckOutputPath(output, {args.positional});
  std::optional<ProgressLine> progress;  // on a terminal, while the bake runs
  progress.emplace("posemorph-bake", !quiet && StderrTakesProgress());
  BakeStage reading("reading the rig description");
  RigDescription rig = ReadRigDescription(args.positional);
  if (const std::string* p = args.Get("--precision")) {
    if (*p != "compact" && *p != "exact") throw UsageError("--precision must be compact or exact");
    rig.parameters.compact = *p == "compact";
  }
  if (const std::string* e = args.Get("--max-error")) {
    rig.parameters.max_error_px = NumberOption("--max-error", *e);
    if (!(rig.parameters.max_error_px >= 1e-6) || rig.parameters.max_error_px > 10)
      throw UsageError("--max-error must be in [1e-6, 10] pixels");
  }
  if (args.switches.count("--allow-folds")) rig.parameters.allow_folds = true;
  if (args.switches.count("--no-align")) rig.mapping.align_interiors = false;
  if (args.switches.count("--map-once")) rig.mapping.map_again = false;
  if (args.switches.count("--no-atlas")) rig.atlas.enabled = false;
  BakeReport report;
  rig.rig_file = output;
  // A grid coarser than the default says so, with its estimate.
  auto GridNote = [](const BakeReport& r) {
    std::ostringstream s;
    if (r.grid_coarsened)
      s << " (coarser than 64: vertices within " << std::setprecision(2) << r.grid_move_px
        << " px of the default grid's)";
    return s.str();
  };
  std::vector<unsigned char> bytes = BakeRig(rig, &report);
  std::optional<PackedAtlas> atlas;
  // A drawing named as a layer of a layered file exists as pixels only in the atlas.
  const RigDrawings& drawn = report.drawings;
  const bool layered = drawn.layered;
  if (layered && !rig.atlas.enabled)
    throw BakeError(rig.file,
                    "a drawing names a layer of a layered file (.ora, .psd), which renderers read from "
                    "the texture atlas: it cannot be baked with \"atlas\": false or --no-atlas");
  if (rig.atlas.enabled && drawn.all) {
    BakeStage packing("packing the texture atlas");
    atlas = PackAtlas(bytes, output, std::filesystem::path(rig.file).parent_path().string(), rig.atlas, rig.file);
    if (atlas->skipped.empty()) {
      bytes = std::move(atlas->rig);
      report.bytes = bytes.size();
    } else if (layered) {
      throw BakeError(rig.file, "no texture atlas, which its layered drawings need: " + atlas->skipped);
    } else {
      err << "posemorph-bake: warning: " << args.positional << ": no texture atlas: " << atlas->skipped << "\n";
      atlas.reset();
    }
  }
  BakeStage writing("writing the output");
  // The pages first: a rig on disk never names a page that is not there.
  // Encoded over the machine's cores (a 2048 x 2048 page takes half a
  // second), the same bytes, then written in order.
  if (atlas) {
    std::vector<std::vector<unsigned char>> encoded(atlas->pages.size());
    RunEach(encoded.size(), 0, [&](std::size_t i) {
      const AtlasPage& page = atlas->pages[i];
      encoded[i] = EncodePng(RgbaImage{page.width, page.height, page.rgba}, page.name);
    });
    for (std::size_t i = 0; i < encoded.size(); ++i)
      WriteFileAtomic((std::filesystem::path(output).parent_path() / atlas->pages[i].name).string(), encoded[i]);
  }
  WriteFileAtomic(output, bytes);
  progress.reset();  // erased before the report
  out << "baked " << args.positional << " -> " << output << ": " << report.vertices << " vertices, " << report.triangles
      << " triangles, " << report.poses << " poses, " << report.paths << " paths, " << report.bytes << " bytes, "
      << "nnz(L) " << report.factor_nonzeros << ", grid " << report.grid_cells_x << "x" << report.grid_cells_y
      << GridNote(report) << ", " << report.seconds * 1e3 << " ms; max pose reproduction error "
      << report.max_reproduction_error << " of the rig size\n";
  if (atlas) {
    out << "texture atlas: " << atlas->drawings << " drawing(s), " << atlas->regions << " part(s) x pose(s), in "
        << atlas->pages.size() << " page(s) of " << atlas->pages[0].width << "x" << atlas->pages[0].height << " (";
    for (std::size_t k = 0; k < atlas->pages.size(); ++k) out << (k ? ", " : "") << atlas->pages[k].name;
    out << ") beside the rig, " << std::fixed << std::setprecision(0) << atlas->filled * 100 << "% filled; "
        << atlas->drawing_pixels << " drawing pixels -> "
        << std::uint64_t(atlas->pages.size()) * atlas->pages[0].width * atlas->pages[0].height << "\n"
        << std::defaultfloat << std::setprecision(6);
  }
  if (!report.parts.empty()) {
    bool changes = false;
    for (const MeshPart& part : report.parts)
      for (int order : part.pose_orders) changes = changes || order != part.order;
    out << (changes ? "parts (back to front in pose 0; the order changes with the pose):" : "parts (back to front):");
    std::vector<const MeshPart*> order;
    for (const MeshPart& part : report.parts) order.push_back(&part);
    std::stable_sort(order.begin(), order.end(),
                     [](const MeshPart* x, const MeshPart* y) { return x->order < y->order; });
    for (std::size_t k = 0; k < order.size(); ++k)
      out << (k ? ", " : " ") << Printable(order[k]->name) << " (" << order[k]->triangle_count << " triangles)";
    if (!report.joints.empty())
      out << "; " << report.joints.size() << (report.joints.size() == 1 ? " joint" : " joints")
          << ", each one vertex shared by its two parts";
    out << "\n";
  }
  if (!report.attachments.empty()) {
    out << "channels:";
    for (std::size_t c = 0; c < report.channels.size(); ++c)
      out << (c ? ", " : " ") << Printable(report.channels[c]) << (c ? "" : " (the figures above: its parts)");
    out << "; " << report.attachments.size() << " attached part(s), each solved on its own, pinned at its joint:";
    for (std::size_t k = 0; k < report.attachments.size(); ++k) {
      const AttachmentReport& at = report.attachments[k];
      out << (k ? "; " : " ") << Printable(at.part) << " (channel " << Printable(at.channel) << ", on "
          << Printable(at.parent) << " triangle " << at.parent_triangle << ": " << at.vertices << " vertices, "
          << at.triangles << " triangles, " << at.poses << " poses, " << at.bytes << " bytes, reproduction error "
          << at.max_reproduction_error << ", placed within " << at.placed_error << ")";
    }
    out << "\n";
  }
  if (report.compact_report.fell_back)
    err << "posemorph-bake: warning: " << args.positional << ": no compact encoding stays within "
        << report.max_error_px << " px of the exact rig; wrote the exact encoding (" << report.bytes << " bytes)\n";
  if (report.compact) {
    const CompactReport& c = report.compact_report;
    out << "compact encoding: " << report.bytes << " bytes (exact " << report.exact_bytes << "); max vertex error "
        << c.max_error_px << " px over " << c.samples << " frames (pose points, pose hull, paths), at the pose points "
        << c.pose_error_px << " px; budget " << report.max_error_px << " px at " << report.pixels_per_unit
        << " px per rig unit; position step " << c.position_step_px << " px, weight step " << c.weight_step << "\n";
  }
  const InbetweenCheck& ib = report.inbetweens;
  out << "in-betweens: " << ib.frames << " frames (pose hull: grid " << ib.grid << ", edges, every two poses; paths), "
      << "smallest triangle area " << ib.min_area_ratio << " of its smallest in a pose (triangle " << ib.min_triangle
      << " at (" << ib.min_at.x() << ", " << ib.min_at.y() << ")); " << ib.folds.size() << " folded triangles; "
      << ib.seconds * 1e3 << " ms\n";
  if (report.ghosting.pairs.empty())
    out << "ghosting: not measured: "
        << (report.ghosting_skipped.empty() ? "no adjacent poses" : report.ghosting_skipped) << "\n";
  else {
    out << "ghosting (colour difference of adjacent poses' drawings at their midpoint): "
        << Printable(DescribeGhosting(report.ghosting)) << "\n";
    out << "ghosting over the pose hull (the in-between check's points where two drawings or more cross-fade): "
        << Printable(DescribeHullGhosting(report.ghosting)) << "\n";
  }
  for (const std::string& w : report.warnings) err << "posemorph-bake: warning: " << Printable(w) << "\n";
  const MappingReport& m = report.mapping;
  for (const std::string& w : rig.warnings) err << "posemorph-bake: warning: " << Printable(w) << "\n";
  for (const std::string& w : m.warnings) err << "posemorph-bake: warning: " << Printable(w) << "\n";
  if (m.mapped) {
    if (m.outline_vertices.empty()) {  // parts: each mapped on its own, the figures summed
      out << "mapped drawings, part by part: ";
    } else {
      out << "mapped drawings: outlines";
      for (std::size_t v : m.outline_vertices) out << " " << v;
      out << " vertices; ";
    }
    out << m.matched_vertices << " matched boundary points -> " << m.boundary_vertices
        << " after simplification (max error " << m.simplification_error << "); " << m.steiner_points
        << " Steiner points; " << (m.features ? std::to_string(m.features) + " features; " : "") << m.vertices
        << " vertices, " << m.triangles << " triangles after refinement; "
        << "min angle " << m.min_angle_degrees << " degrees over all poses";
    if (m.refined_further_from > 0)
      out << " (refined further, " << m.refined_further_by << ": " << m.refined_further_from
          << " degrees after the usual rounds)";
    if (m.registered) {
      out << " (pose 0's mesh deformed onto the others";
      if (m.registered_over > 0) out << "; " << m.registered_over << " degrees by compatible triangulation";
      out << ")";
    }
    if (m.matched_stiffer_over > 0)
      out << " (the outlines matched resisting stretch, " << m.stretch_cost << " per sample; " << m.matched_stiffer_over
          << " degrees as matched first)";
    out << "; " << m.seconds * 1e3 << " ms\n";
    out << "interior alignment: ";
    if (m.aligned) {
      out << "regions";
      for (std::size_t k = 0; k < m.regions_found.size(); ++k)
        out << (k ? ", " : " ") << m.regions_found[k]
            << (k ? " (" + std::to_string(m.regions_matched[k]) + " paired)" : "");
      out << "; colour difference against the first pose";
      for (std::size_t k = 1; k < m.alignment_before.size(); ++k)
        out << (k > 1 ? "," : "") << " " << m.alignment_before[k] * 255 << " -> " << m.alignment_after[k] * 255;
      out << " (of 255); vertices moved up to " << m.alignment_max_move << " px; min angle "
          << m.min_angle_before_alignment << " -> " << m.min_angle_degrees << " degrees; " << m.alignment_seconds * 1e3
          << " ms\n";
    } else {
      out << "not done: " << m.alignment_skipped << "\n";
    }
  }
  return 0;
}

}  // namespace posemorph::bake::cli
