// SPDX-License-Identifier: MIT
#include "cli.h"

#include <algorithm>
#include <filesystem>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <new>
#include <set>
#include <sstream>

#include "posemorph/bake/bake.h"
#include "posemorph/bake/deform_poses.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/stage.h"
#include "posemorph/bake/input_file.h"
#include "posemorph/path.h"
#include "posemorph/rig.h"
#include "posemorph/rig_format.h"
#include "preview.h"
#include "textured_sheet.h"

namespace posemorph::bake {
namespace {

const char kUsage[] =
    "usage:\n"
    "  posemorph-bake RIG.json [-o RIG.pmrig] [--precision compact|exact] [--max-error PX] [--allow-folds]\n"
    "        bake a rig description (default output: RIG.pmrig; compact within 0.01 drawing pixels;\n"
    "        an in-between where a triangle turns over fails the bake unless --allow-folds)\n"
    "  posemorph-bake info RIG.pmrig              sizes, counts, factor fill, in-betweens, pose points, paths\n"
    "  posemorph-bake eval RIG.pmrig (--at X,Y | --path NAME [--time T | --frames K]) -o OUT.svg|.json|.obj\n"
    "        [--sigma S] [--no-shear-limit] [--linear]\n"
    "  posemorph-bake sheet RIG.pmrig -o OUT.svg [--columns C] [--rows R] [--no-shear-limit] [--linear]\n"
    "  posemorph-bake sheet RIG.pmrig --textured -o OUT.png [--images DIR] [--filter linear|nearest] ...\n"
    "        the same frames drawn with the drawings, cross-faded by the texture weights\n"
    "  posemorph-bake deform RIG.json --pose NAME -o MESH.json  write a deformation-made pose as a plain mesh file\n";

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::vector<unsigned char> ReadBytes(const std::string& path) { return ReadInputFile(path, kMaxRigFileBytes, "a baked rig"); }

Rig LoadRigFile(const std::string& path) {
  const std::vector<unsigned char> bytes = ReadBytes(path);
  Rig rig;
  Error err;
  if (!LoadRig(bytes.data(), bytes.size(), &rig, &err))
    throw BakeError(path, std::string("not a valid rig (") + ErrorCodeName(err.code) + "): " + err.message);
  return rig;
}

void WriteText(const std::string& path, const std::string& text) {
  WriteFileAtomic(path, std::vector<unsigned char>(text.begin(), text.end()));
}

std::string Extension(const std::string& path) {
  const auto dot = path.rfind('.');
  if (dot == std::string::npos || path.find('/', dot) != std::string::npos) return "";
  std::string e = path.substr(dot + 1);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e;
}

double ParseNumber(const std::string& flag, const std::string& s) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != s.size() || !std::isfinite(v)) throw UsageError(flag + ": \"" + s + "\" is not a finite number");
  return v;
}

int ParseCount(const std::string& flag, const std::string& s, int lo, int hi) {
  const double v = ParseNumber(flag, s);
  if (v != std::floor(v) || v < lo || v > hi)
    throw UsageError(flag + ": expected a whole number in " + std::to_string(lo) + ".." + std::to_string(hi));
  return int(v);
}

// Flags after the positional argument: "--name value" pairs and switches.
struct Args {
  std::string positional;
  std::vector<std::pair<std::string, std::string>> options;
  std::set<std::string> switches;

  static Args Parse(const std::vector<std::string>& a, std::size_t from, const std::set<std::string>& with_value,
                    const std::set<std::string>& switch_names) {
    Args out;
    for (std::size_t i = from; i < a.size(); ++i) {
      if (with_value.count(a[i])) {
        if (i + 1 >= a.size()) throw UsageError(a[i] + " needs a value");
        out.options.push_back({a[i], a[i + 1]});
        ++i;
      } else if (switch_names.count(a[i])) {
        out.switches.insert(a[i]);
      } else if (!a[i].empty() && a[i][0] == '-') {
        throw UsageError("unknown option " + a[i]);
      } else if (out.positional.empty()) {
        out.positional = a[i];
      } else {
        throw UsageError("unexpected argument " + a[i]);
      }
    }
    return out;
  }
  const std::string* Get(const std::string& name) const {
    for (const auto& [k, v] : options)
      if (k == name) return &v;
    return nullptr;
  }
};

EvalOptions ReadEvalOptions(const Args& args) {
  EvalOptions o;
  if (const std::string* s = args.Get("--sigma")) {
    o.sigma = ParseNumber("--sigma", *s);
    if (o.sigma < 0 || o.sigma > 1) throw UsageError("--sigma must be in [0, 1]");
  }
  o.shear_limit = !args.switches.count("--no-shear-limit");
  o.interpolation = args.switches.count("--linear") ? Interpolation::kLinear : Interpolation::kRigid;
  return o;
}

std::string Printable(const std::string& message);

int Bake(const std::vector<std::string>& a, std::size_t from, std::ostream& out, std::ostream& err) {
  const Args args = Args::Parse(a, from, {"-o", "--precision", "--max-error"}, {"--allow-folds"});
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
  BakeStage reading("reading the rig description");
  RigDescription rig = ReadRigDescription(args.positional);
  if (const std::string* p = args.Get("--precision")) {
    if (*p != "compact" && *p != "exact") throw UsageError("--precision must be compact or exact");
    rig.parameters.compact = *p == "compact";
  }
  if (const std::string* e = args.Get("--max-error")) {
    rig.parameters.max_error_px = ParseNumber("--max-error", *e);
    if (!(rig.parameters.max_error_px >= 1e-6) || rig.parameters.max_error_px > 10)
      throw UsageError("--max-error must be in [1e-6, 10] pixels");
  }
  if (args.switches.count("--allow-folds")) rig.parameters.allow_folds = true;
  BakeReport report;
  const std::vector<unsigned char> bytes = BakeRig(rig, &report);
  BakeStage writing("writing the output");
  WriteFileAtomic(output, bytes);
  out << "baked " << args.positional << " -> " << output << ": " << report.vertices << " vertices, " << report.triangles
      << " triangles, " << report.poses << " poses, " << report.paths << " paths, " << report.bytes << " bytes, "
      << "nnz(L) " << report.factor_nonzeros << ", grid " << report.grid_cells_x << "x" << report.grid_cells_y << ", "
      << report.seconds * 1e3 << " ms; max pose reproduction error " << report.max_reproduction_error
      << " of the rig size\n";
  if (report.compact_report.fell_back)
    err << "posemorph-bake: warning: " << args.positional << ": no compact encoding stays within " << report.max_error_px
        << " px of the exact rig; wrote the exact encoding (" << report.bytes << " bytes)\n";
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
      << " at (" << ib.min_at.x() << ", " << ib.min_at.y() << ")); " << ib.folds.size() << " folded triangles; " << ib.seconds * 1e3 << " ms\n";
  for (const std::string& w : report.warnings) err << "posemorph-bake: warning: " << Printable(w) << "\n";
  const MappingReport& m = report.mapping;
  for (const std::string& w : rig.warnings) err << "posemorph-bake: warning: " << Printable(w) << "\n";
  for (const std::string& w : m.warnings) err << "posemorph-bake: warning: " << Printable(w) << "\n";
  if (m.mapped) {
    out << "mapped drawings: outlines";
    for (std::size_t v : m.outline_vertices) out << " " << v;
    out << " vertices; " << m.matched_vertices << " matched boundary points -> " << m.boundary_vertices
        << " after simplification (max error " << m.simplification_error << "); " << m.steiner_points
        << " Steiner points; " << m.vertices << " vertices, " << m.triangles << " triangles after refinement; "
        << "min angle " << m.min_angle_degrees << " degrees over all poses; " << m.seconds * 1e3 << " ms\n";
  }
  return 0;
}

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
  auto u32 = [&](std::size_t at) { std::uint32_t v = 0; if (at + 4 <= size) std::memcpy(&v, d + at, 4); return v; };
  auto f64 = [&](std::size_t at) { double v = 0; if (at + 8 <= size) std::memcpy(&v, d + at, 8); return v; };
  std::ostringstream s;
  namespace f = format;
  if (tag == f::kQuantPositions) s << "positions: step " << f64(0) << " rig units, differences Exp-Golomb coded (order " << u32(8) << ")";
  else if (tag == f::kQuantTriangles) s << "vertex indices: differences Exp-Golomb coded (order " << u32(0) << ")";
  else if (tag == f::kQuantPermutation) s << u32(0) << "-bit fill-reducing order (factor computed at load)";
  else if (tag == f::kQuantTurns) s << u32(4) << "-bit whole turns of the rotation angles (angles, stretches computed at load)";
  else if (tag == f::kQuantGrid) s << "weight grid: step " << f64(0) << ", predicted, Exp-Golomb coded, " << u32(8) << " poses stored";
  else if (tag == f::kAffineUVs) s << "uvs as affine maps of a pose's positions";
  else if (tag == f::kCompactInfo)
    s << "error budget " << f64(0) << " px; measured max " << f64(8) << " px, at the pose points " << f64(16) << " px ("
      << f64(24) << " px per rig unit)";
  else if (tag == f::kMeta) s << "counts, grid geometry";
  else if (tag == f::kTriangles || tag == f::kPermutation || tag == f::kFactorColumns || tag == f::kFactorRows || tag == f::kPaths) s << "u32";
  else if (tag == f::kUVs) s << "f32 uvs";
  else if (tag == f::kStrings) s << "names and image references";
  else s << "f64";
  return s.str();
}

int Info(const std::vector<std::string>& a, std::size_t from, std::ostream& out) {
  const Args args = Args::Parse(a, from, {}, {});
  if (args.positional.empty()) throw UsageError("no rig file given");
  const std::vector<unsigned char> bytes = ReadBytes(args.positional);
  const Rig rig = LoadRigFile(args.positional);
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
  out << args.positional << ": " << bytes.size() << " bytes (" << double(bytes.size()) / V << " per vertex), arena "
      << rig.arena_bytes() << " bytes\n"
      << "  vertices " << V << ", triangles " << T << ", poses " << N << ", paths " << rig.path_count()
      << (rig.uvs(0).empty() ? ", no uvs" : ", uvs") << "\n"
      << "  factor: n " << rig.factor().n << ", nnz(K lower) " << k_lower << ", nnz(L) " << l_strict + (V - 1)
      << " (fill " << double(l_strict + V - 1) / double(k_lower) << "x)\n"
      << "  weight grid: " << g.cells_x << " x " << g.cells_y << " cells of " << g.cell << ", origin (" << g.origin_x
      << ", " << g.origin_y << ")\n"
      << "  rig size " << rig.size() << ", default sigma " << rig.default_sigma() << ", drawings sampled "
      << (rig.texture_filter() == TextureFilter::kNearest ? "nearest (pixel art)" : "linear") << "\n"
      << "  load " << MedianLoadMicroseconds(bytes) << " us (median of 21 loads on this machine)\n"
      << "  kernel path " << IsaName(rig.isa()) << " (this build and CPU run:";
  for (Isa isa : {Isa::kScalar, Isa::kSse2, Isa::kAvx2, Isa::kAvx512, Isa::kNeon, Isa::kWasmSimd})
    if (IsaAvailable(isa)) out << ' ' << IsaName(isa);
  out << "; POSEMORPH_ISA chooses)\n";
  // Where the bytes go (the loader has validated the table already).
  std::uint32_t sections = 0;
  std::memcpy(&sections, bytes.data() + format::kOffSectionCount, 4);
  format::Meta meta{};
  out << "  sections (" << (rig.format_major()) << "." << rig.format_minor() << ", ";
  for (std::uint32_t s = 0; s < sections; ++s) {
    const unsigned char* e = bytes.data() + format::kHeaderSize + std::size_t(s) * format::kSectionEntrySize;
    std::uint32_t tag = 0;
    std::memcpy(&tag, e, 4);
    std::uint64_t offset = 0;
    std::memcpy(&offset, e + 8, 8);
    if (tag == format::kMeta) std::memcpy(&meta, bytes.data() + offset, sizeof(meta));
  }
  const bool compact = (meta.flags & format::kMetaFlagCompact) != 0;
  out << (compact ? "compact" : "exact") << " encoding):\n";
  for (std::uint32_t s = 0; s < sections; ++s) {
    const unsigned char* e = bytes.data() + format::kHeaderSize + std::size_t(s) * format::kSectionEntrySize;
    std::uint32_t tag = 0;
    std::uint64_t offset = 0, size = 0;
    std::memcpy(&tag, e, 4);
    std::memcpy(&offset, e + 8, 8);
    std::memcpy(&size, e + 16, 8);
    out << "    " << std::string(reinterpret_cast<const char*>(e), 4) << ' ' << std::setw(9) << size << "  "
        << DescribeSection(tag, bytes.data() + offset, size) << "\n";
  }
  const InbetweenCheck ib = CheckInbetweens(rig, args.positional);
  out << "  in-betweens: smallest triangle area " << ib.min_area_ratio << " of its smallest in a pose in the pose hull"
      << " (triangle " << ib.min_triangle << " at (" << ib.min_at.x() << ", " << ib.min_at.y() << "); " << ib.frames
      << " frames); " << ib.FoldsInHull() << " triangles fold in the hull";
  if (ib.folds.size() > ib.FoldsInHull()) out << ", " << ib.folds.size() - ib.FoldsInHull() << " only on paths outside it";
  out << "\n";
  for (const InbetweenFold& f : ib.folds) out << "    " << DescribeFold(rig, f) << "\n";
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
  for (std::uint32_t p = 0; p < rig.path_count(); ++p) {
    const PathView path = rig.path(p);
    const double duration = path.keys[3 * (path.key_count() - 1)] - path.keys[0];
    out << "  path '" << std::string(path.name.data, path.name.size) << "': " << path.key_count() << " keys, "
        << duration << " s, " << (path.interpolation == PathInterpolation::kCatmullRom ? "catmull-rom" : "linear")
        << (path.loop ? ", loops" : "") << "\n";
  }
  return 0;
}

int Eval(const std::vector<std::string>& a, std::size_t from, std::ostream& out) {
  const Args args = Args::Parse(a, from, {"-o", "--at", "--path", "--time", "--frames", "--sigma"},
                                {"--no-shear-limit", "--linear"});
  if (args.positional.empty()) throw UsageError("no rig file given");
  const std::string* output = args.Get("-o");
  if (!output) throw UsageError("eval needs -o OUT.svg|.json|.obj");
  const std::string ext = Extension(*output);
  if (ext != "svg" && ext != "json" && ext != "obj") throw UsageError("-o " + *output + ": use .svg, .json or .obj");
  const std::string *at = args.Get("--at"), *path_name = args.Get("--path");
  if (!at == !path_name) throw UsageError("give exactly one of --at X,Y or --path NAME");
  const EvalOptions options = ReadEvalOptions(args);
  double at_x = 0, at_y = 0;
  if (at) {
    const auto comma = at->find(',');
    if (comma == std::string::npos) throw UsageError("--at: expected X,Y");
    at_x = ParseNumber("--at", at->substr(0, comma));
    at_y = ParseNumber("--at", at->substr(comma + 1));
  }
  const Rig rig = LoadRigFile(args.positional);

  std::vector<Frame> frames;
  char label[96];
  if (at) {
    const double x = at_x, y = at_y;
    frames.push_back(EvaluateFrame(rig, x, y, options));
    std::snprintf(label, sizeof label, "(%.3g, %.3g)", x, y);
    frames.back().label = label;
  } else {
    const int index = rig.FindPath(path_name->c_str());
    if (index < 0) throw BakeError(args.positional, "has no path named '" + *path_name + "'");
    const PathView path = rig.path(std::uint32_t(index));
    const double t0 = path.keys[0], t1 = path.keys[3 * (path.key_count() - 1)];
    std::vector<double> times;
    if (const std::string* t = args.Get("--time")) {
      if (args.Get("--frames")) throw UsageError("give --time or --frames, not both");
      times.push_back(ParseNumber("--time", *t));
    } else {
      const int k = args.Get("--frames") ? ParseCount("--frames", *args.Get("--frames"), 1, 1000) : 16;
      // A looping path's end is its start again; spread frames over one period.
      for (int i = 0; i < k; ++i) times.push_back(t0 + (t1 - t0) * i / (path.loop ? k : std::max(1, k - 1)));
    }
    for (double t : times) {
      double x, y;
      SamplePath(path, t, &x, &y);
      frames.push_back(EvaluateFrame(rig, x, y, options));
      std::snprintf(label, sizeof label, "t=%.3g (%.2f, %.2f)", t, x, y);
      frames.back().label = label;
    }
  }
  if (ext == "obj" && frames.size() != 1) throw UsageError("an OBJ file holds one frame; use --time or --at");
  const std::string title = args.positional + (at ? " at " + *at : " path " + *path_name);
  WriteText(*output, ext == "svg" ? FramesSvg(rig, frames, title) : ext == "json" ? FramesJson(rig, frames) : FrameObj(rig, frames[0]));
  out << "wrote " << *output << " (" << frames.size() << (frames.size() == 1 ? " frame)\n" : " frames)\n");
  return 0;
}

int Sheet(const std::vector<std::string>& a, std::size_t from, std::ostream& out) {
  const Args args = Args::Parse(a, from, {"-o", "--columns", "--rows", "--sigma", "--images", "--filter"},
                                {"--no-shear-limit", "--linear", "--textured"});
  if (args.positional.empty()) throw UsageError("no rig file given");
  const std::string* output = args.Get("-o");
  const bool textured = args.switches.count("--textured") > 0;
  if (!output || Extension(*output) != (textured ? "png" : "svg"))
    throw UsageError(textured ? "sheet --textured needs -o OUT.png" : "sheet needs -o OUT.svg");
  if (!textured && (args.Get("--images") || args.Get("--filter"))) throw UsageError("--images and --filter go with --textured");
  const int columns = args.Get("--columns") ? ParseCount("--columns", *args.Get("--columns"), 2, 32) : 7;
  const int rows = args.Get("--rows") ? ParseCount("--rows", *args.Get("--rows"), 1, 32) : 5;
  const Rig rig = LoadRigFile(args.positional);
  if (textured) {
    TextureFilter filter = rig.texture_filter();
    if (const std::string* f = args.Get("--filter")) {
      if (*f != "linear" && *f != "nearest") throw UsageError("--filter wants linear or nearest");
      filter = *f == "nearest" ? TextureFilter::kNearest : TextureFilter::kLinear;
    }
    std::string images = std::filesystem::path(args.positional).parent_path().string();
    if (const std::string* i = args.Get("--images")) images = *i;
    if (images.empty()) images = ".";
    const std::vector<RgbaImage> drawings = ReadPoseDrawings(rig, args.positional, images);
    TexturedSheetLayout layout;
    const RgbaImage sheet = TexturedSheet(rig, drawings, columns, rows, ReadEvalOptions(args), filter, 160, &layout);
    WriteFileAtomic(*output, EncodePng(sheet, *output));
    out << "wrote " << *output << " (" << sheet.width << " x " << sheet.height << ": " << rig.pose_count()
        << " poses, then " << columns << "x" << layout.rows << " samples, drawings sampled "
        << (filter == TextureFilter::kNearest ? "nearest" : "linear") << ")\n";
    return 0;
  }
  WriteText(*output, ContactSheetSvg(rig, args.positional + ": poses across pose space", columns, rows, ReadEvalOptions(args)));
  out << "wrote " << *output << " (" << rig.pose_count() << " poses, " << columns << "x" << rows << " samples)\n";
  return 0;
}

int Deform(const std::vector<std::string>& a, std::size_t from, std::ostream& out) {
  const Args args = Args::Parse(a, from, {"-o", "--pose"}, {});
  if (args.positional.empty()) throw UsageError("no rig description given");
  const std::string *output = args.Get("-o"), *name = args.Get("--pose");
  if (!output || !name) throw UsageError("deform needs --pose NAME and -o MESH.json");
  const RigDescription rig = ReadRigDescription(args.positional);
  const PoseMeshes meshes = ResolvePoseMeshes(rig);
  const auto it = std::find_if(rig.poses.begin(), rig.poses.end(), [&](const PoseDescription& p) { return p.name == *name; });
  if (it == rig.poses.end()) throw BakeError(args.positional, "has no pose named '" + *name + "'");
  const Points& vertices = meshes.poses[std::size_t(it - rig.poses.begin())].vertices;
  // The same mesh-file format a description's "mesh" reads, so the pose can be
  // edited by hand and used in place of its "deform" entry.
  std::ostringstream json;
  json.precision(17);
  json << "{\"vertices\": [";
  for (std::size_t v = 0; v < vertices.size(); ++v)
    json << (v ? ", [" : "[") << vertices[v].x() << ", " << vertices[v].y() << "]";
  json << "],\n \"triangles\": [";
  for (std::size_t t = 0; t < meshes.triangles.size(); ++t)
    json << (t ? ", [" : "[") << meshes.triangles[t][0] << ", " << meshes.triangles[t][1] << ", " << meshes.triangles[t][2] << "]";
  json << "]}\n";
  WriteText(*output, json.str());
  out << "wrote " << *output << " (pose '" << *name << "', " << vertices.size() << " vertices"
      << (it->deformed ? ", made from '" + it->deform.from + "'" : std::string(", given directly")) << ")\n";
  return 0;
}

// A message as the terminal will show it: control characters (and UTF-8's
// C1 controls) escaped as \xNN, so that a name in a file cannot drive the
// terminal; longer than 1000 characters, its middle elided (a 900 KB pose
// name once came out whole), keeping the file at the start and the problem
// at the end.
std::string Printable(const std::string& message) {
  std::string s;
  char hex[8];
  for (std::size_t i = 0; i < message.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(message[i]);
    const bool c1 = c == 0xC2 && i + 1 < message.size() && static_cast<unsigned char>(message[i + 1]) >= 0x80 &&
                    static_cast<unsigned char>(message[i + 1]) <= 0x9F;
    if (c < 0x20 || c == 0x7F) {
      std::snprintf(hex, sizeof(hex), "\\x%02x", c);
      s += hex;
    } else if (c1) {
      std::snprintf(hex, sizeof(hex), "\\x%02x", static_cast<unsigned char>(message[++i]));
      s += hex;
    } else {
      s += char(c);
    }
  }
  const std::size_t keep = 480;
  if (s.size() > 2 * keep + 40)
    s = s.substr(0, keep) + " [... " + std::to_string(s.size() - 2 * keep) + " characters ...] " + s.substr(s.size() - keep);
  return s;
}

// The file a command works on, for messages that do not name one.
std::string InputOf(const std::vector<std::string>& a) {
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i] == "info" || a[i] == "eval" || a[i] == "sheet" || a[i] == "deform" || a[i] == "bake") continue;
    if (!a[i].empty() && a[i][0] == '-') {
      ++i;  // an option and its value
      continue;
    }
    return a[i];
  }
  return "posemorph-bake";
}

}  // namespace

int RunBakeCommand(const std::vector<std::string>& a, std::ostream& out, std::ostream& err) {
  // Where a failure without context of its own happened (out of memory, an
  // unexpected exception): the bake stage, or the command.
  auto where = [&]() {
    const std::string stage = CurrentBakeStage();
    return stage.empty() ? std::string() : " while " + stage;
  };
  try {
    BakeStage command("running the command");
    if (a.empty()) throw UsageError("no command given");
    const std::string& cmd = a[0];
    if (cmd == "-h" || cmd == "--help" || cmd == "help") {
      out << kUsage;
      return 0;
    }
    if (cmd == "info") return Info(a, 1, out);
    if (cmd == "eval") return Eval(a, 1, out);
    if (cmd == "sheet") return Sheet(a, 1, out);
    if (cmd == "deform") return Deform(a, 1, out);
    if (cmd == "bake") return Bake(a, 1, out, err);
    return Bake(a, 0, out, err);
  } catch (const UsageError& e) {
    // One line naming the problem; the whole usage only when nothing was given.
    if (a.empty()) err << kUsage;
    else err << "posemorph-bake: " << Printable(e.what()) << " (posemorph-bake --help lists the commands and options)\n";
    return 2;
  } catch (const BakeError& e) {
    err << "posemorph-bake: error: " << Printable(e.what()) << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    err << "posemorph-bake: error: " << Printable(InputOf(a)) << ": out of memory" << where()
        << " (the input asks for more than this machine has)\n";
    return 1;
  } catch (const std::exception& e) {
    err << "posemorph-bake: error: " << Printable(InputOf(a)) << ": internal error" << where() << ": "
        << Printable(e.what()) << "\n";
    return 1;
  }
}

}  // namespace posemorph::bake
