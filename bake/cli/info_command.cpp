// SPDX-License-Identifier: MIT
// posemorph-bake info RIG.pmrig: what a baked rig holds.
#include "commands.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <iomanip>
#include <set>
#include <sstream>

#include "command_args.h"
#include "posemorph/bake/drawing_folder.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/ghosting.h"
#include "posemorph/bake/inbetween_check.h"
#include "posemorph/compact_codec.h"
#include "posemorph/path.h"
#include "posemorph/rig.h"
#include "posemorph/rig_format.h"
#include "preview.h"
#include "textured_sheet.h"

namespace posemorph::bake::cli {
namespace {

double MedianLoadMicroseconds(const std::vector<unsigned char>& bytes) {
  std::vector<double> times;
  for (int k = 0; k < 21; ++k) {
    const auto start = std::chrono::steady_clock::now();
    Rig rig;
    LoadRig(bytes.data(), bytes.size(), &rig, nullptr);
    times.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count());
  }
  std::nth_element(times.begin(), times.begin() + 10, times.end());
  return std::round(times[10]);
}

// What a section holds and at what precision, from its tag and header.
std::string DescribeSection(std::uint32_t tag, const unsigned char* d, std::uint64_t size) {
  namespace f = format;
  // The section's header record, or zeros when the section is shorter.
  auto header = [&](auto record) {
    f::ReadRecord(d, size, 0, &record);
    return record;
  };
  std::ostringstream s;
  if (tag == f::kQuantPositions) {
    const auto h = header(f::QuantPositionsHeader{});
    s << "positions: step " << h.step << " rig units, "
      << (h.prediction & f::kPositionsFromNeighbours ? "residuals of the mean of earlier neighbours" : "differences")
      << " Exp-Golomb coded (order " << h.code_order << ")";
    if (h.prediction & f::kPositionsAgainstPose0)
      s << "; the poses after the first less pose 0's residuals (an order per pose)";
  } else if (tag == f::kQuantTriangles) {
    s << "vertex indices: differences Exp-Golomb coded (order " << header(f::CodedTrianglesHeader{}).code_order << ")";
  } else if (tag == f::kQuantPermutation) {
    s << header(f::PackedArrayHeader{}).width << "-bit fill-reducing order (factor computed at load)";
  } else if (tag == f::kQuantTurns) {
    s << header(f::TurnsHeader{}).width
      << "-bit whole turns of the rotation angles (angles, stretches computed at load)";
  } else if (tag == f::kQuantGrid) {
    const auto h = header(f::GridHeader{});
    s << "weight grid: step " << h.step << ", predicted, Exp-Golomb coded, " << h.coded_poses << " poses stored";
  } else if (tag == f::kAffineUVs) {
    s << "uvs as affine maps of a pose's positions";
  } else if (tag == f::kCompactInfo) {
    const auto h = header(f::CompactInfo{});
    s << "error budget " << h.error_budget_px << " px; measured max " << h.max_error_px << " px, at the pose points "
      << h.pose_point_error_px << " px (" << h.pixels_per_unit << " px per rig unit)";
  } else if (tag == f::kMeta) {
    s << "counts, grid geometry";
  } else if (tag == f::kTriangles || tag == f::kPermutation || tag == f::kFactorColumns || tag == f::kFactorRows ||
             tag == f::kPaths) {
    s << "u32";
  } else if (tag == f::kUVs) {
    s << "f32 uvs";
  } else if (tag == f::kStrings) {
    s << "names and image references";
  } else if (tag == f::kParts) {
    s << "u32 parts: first triangle, triangle count, draw order";
  } else if (tag == f::kPartPoseOrders) {
    s << "i32 draw order per pose per part";
  } else if (tag == f::kEvents) {
    s << "path events: f64 time, u32 path";
  } else if (tag == f::kMachine) {
    s << "state machine: inputs, layers, states, transitions, conditions, names";
  } else if (tag == f::kChannels) {
    s << "control channels: names, attachments (each a nested rig), their joints";
  } else {
    s << "f64";
  }
  return s.str();
}

void PrintPaths(const Rig& rig, const char* indent, std::ostream& out) {
  for (std::uint32_t p = 0; p < rig.path_count(); ++p) {
    const PathView path = rig.path(p);
    const double duration = path.end_time() - path.start_time();
    out << indent << "  path '" << Printable(std::string(path.name.data, path.name.size)) << "': " << path.key_count()
        << " keys, " << duration << " s, "
        << (path.interpolation == PathInterpolation::kCatmullRom ? "catmull-rom" : "linear")
        << (path.loop ? ", loops" : "") << "\n";
    for (std::size_t e = 0; e < path.events.size; ++e) {
      const EventView& event = path.events[e];
      out << indent << "    event '" << Printable(std::string(event.name.data, event.name.size)) << "' at "
          << event.time << " s\n";
    }
  }
}

// Sizes, counts, the factor's fill, the grid, load time and kernel path.
void PrintSummary(const std::string& file, const std::vector<unsigned char>& bytes, const Rig& rig, std::ostream& out) {
  const std::uint32_t V = rig.vertex_count(), T = rig.triangle_count(), N = rig.pose_count();
  // Lower triangle of K (pinned vertex 0 removed): diagonal + one entry per interior edge.
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (std::uint32_t t = 0; t < T; ++t)
    for (int k = 0; k < 3; ++k) {
      std::uint32_t u = rig.triangles()[3 * t + k], v = rig.triangles()[3 * t + (k + 1) % 3];
      if (u && v) edges.insert({std::min(u, v), std::max(u, v)});
    }
  const std::size_t k_lower = edges.size() + (V - 1), l_strict = rig.factor().value.size;
  const PoseSpaceGrid& g = rig.grid();
  out << file << ": " << bytes.size() << " bytes (" << double(bytes.size()) / V << " per vertex), arena "
      << rig.arena_bytes() << " bytes\n"
      << "  vertices " << V << ", triangles " << T << ", poses " << N << ", paths " << rig.path_count()
      << (rig.uvs(0).empty() ? ", no uvs" : ", uvs") << "\n"
      << "  factor: n " << rig.factor().n << ", nnz(K lower) " << k_lower << ", nnz(L) " << l_strict + (V - 1)
      << " (fill " << double(l_strict + V - 1) / double(k_lower) << "x)\n"
      << "  weight grid: " << g.cells_x << " x " << g.cells_y << " cells of " << g.cell << ", origin (" << g.origin_x
      << ", " << g.origin_y << ")\n"
      << "  stands at (" << rig.anchor_x() << ", " << rig.anchor_y() << ") in rig units"
      << (rig.anchor_given() ? " (its description's anchor)" : " (the bottom centre of pose 0)") << ", faces "
      << (rig.facing_left() ? "left" : "right") << "; pad range x " << rig.pad_range().min_x << " .. "
      << rig.pad_range().max_x << ", y " << rig.pad_range().min_y << " .. " << rig.pad_range().max_y << "\n"
      << "  rig size " << rig.bounding_box_diagonal() << ", default sigma " << rig.default_sigma()
      << ", drawings sampled " << (rig.texture_filter() == TextureFilter::kNearest ? "nearest (pixel art)" : "linear");
  if (rig.drawing_folder().size)
    out << ", found in " << Printable(std::string(rig.drawing_folder().data, rig.drawing_folder().size))
        << " (relative to the rig)";
  out << "\n";
  if (rig.has_atlas()) {
    out << "  texture atlas: " << rig.page_count() << " page(s) of " << rig.page(0).width << " x " << rig.page(0).height
        << " beside the rig (";
    for (std::uint32_t k = 0; k < rig.page_count(); ++k)
      out << (k ? ", " : "") << Printable(std::string(rig.page(k).name.data, rig.page(k).name.size));
    out << "), premultiplied; " << rig.part_count() * N << " part(s) x pose(s) of the body"
        << (rig.attachment_count() ? " and the attachments' on the same pages" : "") << "\n";
  } else if (!rig.uvs(0).empty()) {
    out << "  no texture atlas: a renderer uploads each part's drawing in each pose (" << rig.page_count()
        << " textures)\n";
  }
  out << "  load " << MedianLoadMicroseconds(bytes) << " us (median of 21 loads on this machine)\n"
      << "  kernel path " << IsaName(rig.isa()) << " (this build and CPU run:";
  for (Isa isa : {Isa::kScalar, Isa::kSse2, Isa::kAvx2, Isa::kAvx512, Isa::kNeon, Isa::kWasmSimd})
    if (IsaAvailable(isa)) out << ' ' << IsaName(isa);
  out << "; POSEMORPH_ISA chooses)\n";
}

// Each section's tag, size and what it holds.
void PrintSections(const std::string& file, const std::vector<unsigned char>& bytes, const Rig& rig,
                   std::ostream& out) {
  // Where the bytes go: the table as the runtime reads it.
  RigSection sections[format::kMaxSections];
  std::uint32_t section_count = 0;
  Error err;
  if (!ReadRigSections(bytes.data(), bytes.size(), sections, format::kMaxSections, &section_count, &err))
    throw BakeError(file, std::string("cannot read its section table: ") + err.message);
  out << "  sections (" << rig.format_major() << "." << rig.format_minor() << ", "
      << (rig.compact_encoding() ? "compact" : "exact") << " encoding):\n";
  for (std::uint32_t s = 0; s < section_count; ++s) {
    const RigSection& section = sections[s];
    std::string name(4, ' ');
    for (int k = 0; k < 4; ++k) name[std::size_t(k)] = char((section.tag >> (8 * k)) & 0xFFu);
    out << "    " << Printable(name) << ' ' << std::setw(9) << section.size << "  "
        << DescribeSection(section.tag, bytes.data() + section.offset, section.size) << "\n";
  }
}

// Folds of the in-betweens, as the bake's check finds them.
void PrintInbetweens(const std::string& file, const Rig& rig, std::ostream& out) {
  const InbetweenCheck ib = CheckInbetweens(rig, file);
  out << "  in-betweens: smallest triangle area " << ib.min_area_ratio << " of its smallest in a pose in the pose hull"
      << " (triangle " << ib.min_triangle << " at (" << ib.min_at.x() << ", " << ib.min_at.y() << "); " << ib.frames
      << " frames); " << ib.FoldsInHull() << " triangles fold in the hull";
  if (ib.folds.size() > ib.FoldsInHull())
    out << ", " << ib.folds.size() - ib.FoldsInHull() << " only on paths outside it";
  out << "\n";
  for (const InbetweenFold& f : ib.folds) out << "    " << DescribeFold(rig, f) << "\n";
}

// The ghosting measure, with the drawings from `images` (or where the rig
// says the bake found them); a line saying why not when they cannot be read.
void PrintGhosting(const std::string& file, const Rig& rig, const std::string* images, std::ostream& out) {
  if (rig.uvs(0).size == 0) {
    out << "  ghosting: not measured (the rig has no drawings)\n";
    return;
  }
  if (rig.part_count() > 1) {
    out << "  ghosting: not measured: the rig is drawn as parts, and the measure takes one drawing per pose\n";
    return;
  }
  std::vector<RgbaImage> drawings;
  const std::string folder = images ? *images : DefaultDrawingFolder(file, rig);
  try {
    drawings = ReadPoseDrawings(rig, file, folder, false);  // the drawings the bake measured, not the atlas's
  } catch (const BakeError& e) {
    out << "  ghosting: not measured: " << Printable(e.what()) << "\n";
    return;
  }
  std::vector<DrawingPixels> pixels;
  for (const RgbaImage& d : drawings) pixels.push_back({d.width, d.height, d.rgba.data()});
  const Ghosting g = MeasureGhosting(rig, pixels, file);
  out << "  ghosting (colour difference of adjacent poses' drawings at their midpoint, drawings in "
      << Printable(folder) << "): " << Printable(DescribeGhosting(g)) << "\n";
  out << "  ghosting over the pose hull (the in-between check's points where two drawings or more cross-fade): "
      << Printable(DescribeHullGhosting(g)) << "\n";
}

void PrintPosesAndPaths(const Rig& rig, std::ostream& out) {
  const std::uint32_t N = rig.pose_count();
  for (std::uint32_t i = 0; i < N; ++i) {
    out << "  pose " << i << " '" << std::string(rig.pose_name(i).data, rig.pose_name(i).size) << "' at ("
        << rig.pose_points()[2 * i] << ", " << rig.pose_points()[2 * i + 1] << ")";
    if (rig.pose_image(i).size) out << " image " << std::string(rig.pose_image(i).data, rig.pose_image(i).size);
    const DrawingCanvas canvas = rig.pose_canvas(i);
    if (canvas.width > 0)
      out << " canvas " << canvas.width << " x " << canvas.height << " origin at (" << canvas.pivot_x << ", "
          << canvas.pivot_y << ")";
    out << "\n";
  }
  // A layered character's parts, back to front, with their drawings.
  if (rig.part_count() > 1)
    for (std::uint32_t p : rig.draw_sequence()) {
      const PartView part = rig.part(p);
      out << "  part " << p << " '" << Printable(std::string(part.name.data, part.name.size)) << "': triangles "
          << part.first_triangle << ".." << part.first_triangle + part.triangle_count - 1 << ", draw order ";
      if (rig.draw_order_changes())  // per pose, '/'-separated
        for (std::uint32_t i = 0; i < N; ++i) out << (i ? "/" : "") << rig.part_draw_order(p, i);
      else
        out << part.draw_order;
      for (std::uint32_t i = 0; i < N; ++i)
        if (rig.part_image(p, i).size)
          out << (i ? ", " : "; images ")
              << Printable(std::string(rig.part_image(p, i).data, rig.part_image(p, i).size));
      out << "\n";
    }
  PrintPaths(rig, "", out);
  // Control channels: each later channel's poses and paths, and the
  // attachments it drives.
  for (std::uint32_t c = 1; c < rig.channel_count(); ++c) {
    const Rig& channel = *rig.channel_rig(c);
    out << "  channel " << c << " '" << Printable(std::string(rig.channel_name(c).data, rig.channel_name(c).size))
        << "': " << channel.pose_count() << " poses";
    for (std::uint32_t i = 0; i < channel.pose_count(); ++i)
      out << (i ? ", '" : " ('") << Printable(std::string(channel.pose_name(i).data, channel.pose_name(i).size))
          << "' at (" << channel.pose_points()[2 * i] << ", " << channel.pose_points()[2 * i + 1] << ")"
          << (i + 1 == channel.pose_count() ? ")" : "");
    out << "\n";
    PrintPaths(channel, "  ", out);
    for (std::uint32_t a = 0; a < rig.attachment_count(); ++a) {
      const AttachmentView v = rig.attachment(a);
      if (v.channel != c) continue;
      const PartView part = v.rig->part(0);
      out << "    attachment " << a << " '" << Printable(std::string(part.name.data, part.name.size))
          << "': " << v.rig->vertex_count() << " vertices, " << v.rig->triangle_count() << " triangles, draw order "
          << part.draw_order << ", pinned to triangle " << v.parent_triangle << " at (" << v.parent_weights[0] << ", "
          << v.parent_weights[1] << ", " << v.parent_weights[2] << ")\n";
    }
  }
}

std::string Name(StringView v) { return Printable(std::string(v.data, v.size)); }

void PrintTransition(const Rig& rig, const MachineTransitionView& t, const char* lead, std::ostream& out) {
  static const char* const kOps[] = {"", "not ", "==", "!=", "<", "<=", ">", ">="};
  out << lead << "-> '" << Name(rig.machine_states()[t.to].name) << "'";
  for (std::size_t k = 0; k < t.conditions.size; ++k) {
    const MachineConditionView& c = t.conditions[k];
    out << (k ? " and " : " when ");
    const std::string input = Name(rig.machine_inputs()[c.input].name);
    if (c.op == MachineOp::kIsTrue || c.op == MachineOp::kIsFalse)
      out << kOps[int(c.op)] << input;
    else
      out << input << ' ' << kOps[int(c.op)] << ' ' << c.value;
  }
  if (t.has_exit_time) out << (t.conditions.size ? ", " : " ") << "at exit time " << t.exit_time;
  out << ", mix " << t.mix << " s\n";
}

// The state machine (format 1.9): inputs, then each layer's states and transitions.
void PrintStateMachine(const Rig& rig, std::ostream& out) {
  if (rig.machine_layers().empty()) return;
  static const char* const kTypes[] = {"bool", "number", "trigger", "point"};
  out << "  state machine: " << rig.machine_inputs().size << " inputs";
  for (std::size_t i = 0; i < rig.machine_inputs().size; ++i) {
    const MachineInputView& in = rig.machine_inputs()[i];
    out << (i ? ", " : ": ") << kTypes[int(in.type)] << " '" << Name(in.name) << "'";
    if (in.type == MachineInputType::kBool) out << " = " << (in.default_x != 0 ? "true" : "false");
    if (in.type == MachineInputType::kNumber) out << " = " << in.default_x;
    if (in.type == MachineInputType::kPoint) out << " = (" << in.default_x << ", " << in.default_y << ")";
  }
  out << "\n";
  for (std::size_t l = 0; l < rig.machine_layers().size; ++l) {
    const MachineLayerView& layer = rig.machine_layers()[l];
    const Rig& channel = *rig.channel_rig(layer.channel);
    out << "    layer " << l << " (channel " << layer.channel;
    if (rig.channel_name(layer.channel).size) out << " '" << Name(rig.channel_name(layer.channel)) << "'";
    out << "), starts in '" << Name(rig.machine_states()[layer.initial].name) << "'\n";
    const MachineBehavioursView& b = layer.behaviours;
    if (b.blink)
      out << "      behaviour: blink toward '" << Name(channel.pose_name(b.blink_pose)) << "' every "
          << b.blink_interval << " s (jitter " << b.blink_jitter << "), " << b.blink_duration << " s, strength "
          << b.blink_strength << ", seed " << b.blink_seed << " + the character's index\n";
    if (b.breath)
      out << "      behaviour: breath, period " << b.breath_period << " s, offset (" << b.breath_x << ", " << b.breath_y
          << ")\n";
    if (b.look_at)
      out << "      behaviour: look-at"
          << (b.look_input >= 0 ? " point input '" + Name(rig.machine_inputs()[std::size_t(b.look_input)].name) + "'"
                                : std::string(" (target set by code)"))
          << ", smoothing " << b.look_smoothing << " s, strength " << b.look_strength << "\n";
    if (b.spring)
      out << "      behaviour: spring, " << b.spring_frequency << " Hz, damping " << b.spring_damping << ", strength "
          << b.spring_strength << "\n";
    for (std::size_t k = 0; k < layer.any.size; ++k) PrintTransition(rig, layer.any[k], "      from any state ", out);
    for (std::uint32_t i = layer.first_state; i < layer.first_state + layer.state_count; ++i) {
      const MachineStateView& st = rig.machine_states()[i];
      out << "      state '" << Name(st.name) << "': ";
      switch (st.kind) {
        case MachineStateKind::kStop:
          out << "stops at the channel's pose 0";
          break;
        case MachineStateKind::kPlay:
          out << "plays '" << Name(channel.path(st.path).name) << "'"
              << (st.loop < 0 ? ""
                  : st.loop   ? " looped"
                              : " once")
              << " at speed " << st.speed;
          break;
        case MachineStateKind::kPad:
          out << "follows point input '" << Name(rig.machine_inputs()[st.input].name) << "'";
          break;
        case MachineStateKind::kBlend:
          out << "along '" << Name(channel.path(st.path).name) << "' by number input '"
              << Name(rig.machine_inputs()[st.input].name) << "' (0..1)";
          break;
      }
      if (st.colour[0] != 1 || st.colour[1] != 1 || st.colour[2] != 1)
        out << ", tint (" << st.colour[0] << ", " << st.colour[1] << ", " << st.colour[2] << ")";
      if (st.colour[3] != 1) out << ", opacity " << st.colour[3];
      for (const MachinePartOpacityView& o : st.part_opacities)
        out << ", part '" << Name(rig.part(o.part).name) << "' at opacity " << o.opacity;
      out << "\n";
      for (std::size_t k = 0; k < st.transitions.size; ++k) PrintTransition(rig, st.transitions[k], "        ", out);
    }
  }
}

}  // namespace

int InfoCommand(const std::vector<std::string>& a, std::size_t from, std::ostream& out) {
  const Args args = Args::Parse(a, from, {"--images"}, {});
  if (args.positional.empty()) throw UsageError("no rig file given");
  const std::vector<unsigned char> bytes = ReadBytes(args.positional);
  const Rig rig = LoadRigFile(args.positional);
  PrintSummary(args.positional, bytes, rig, out);
  PrintSections(args.positional, bytes, rig, out);
  PrintInbetweens(args.positional, rig, out);
  PrintGhosting(args.positional, rig, args.Get("--images"), out);
  PrintPosesAndPaths(rig, out);
  PrintStateMachine(rig, out);
  return 0;
}

}  // namespace posemorph::bake::cli
