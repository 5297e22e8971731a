// SPDX-License-Identifier: MIT
// Reading a rig description (JSON). Every problem names the file and the
// JSON path of the offending value.
#include "posemorph/bake/rig_description.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "description_json.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/input_file.h"
#include "posemorph/rig_format.h"

namespace posemorph::bake {

nlohmann::json ParseDescriptionJson(const std::string& text, const std::string& file) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    // Drop nlohmann's "[json.exception.parse_error.101] " tag; keep its explanation.
    std::string what = e.what();
    const auto tag_end = what.find("] ");
    if (what.rfind("[json.exception.", 0) == 0 && tag_end != std::string::npos) what.erase(0, tag_end + 2);
    throw BakeError(file, "invalid JSON: " + what);
  }
}

namespace {

constexpr double kMaxCoordinate = 1e9;

using nlohmann::json;

struct Reader {
  std::string file;

  [[noreturn]] void Fail(const std::string& where, const std::string& problem) const {
    throw BakeError(file, where.empty() ? problem : where + ": " + problem);
  }
  double Number(const json& j, const std::string& where) const {
    if (!j.is_number()) Fail(where, "expected a number");
    const double v = j.get<double>();
    if (!std::isfinite(v)) Fail(where, "number is not finite");
    return v;
  }
  std::uint32_t Index(const json& j, const std::string& where) const {
    if (!j.is_number_integer()) Fail(where, "expected a non-negative integer vertex index");
    if (j.is_number_unsigned() ? j.get<std::uint64_t>() > 0xFFFFFFFEull : true)
      Fail(where, "vertex index " + j.dump() + " is out of range");
    return std::uint32_t(j.get<std::uint64_t>());
  }
  Eigen::Vector2d Point(const json& j, const std::string& where) const {
    if (!j.is_array() || j.size() != 2) Fail(where, "expected [x, y]");
    return {Number(j[0], where + "[0]"), Number(j[1], where + "[1]")};
  }
  const json& Array(const json& j, const char* key, const std::string& where) const {
    if (!j.contains(key)) Fail(where, std::string("missing \"") + key + "\"");
    const json& a = j[key];
    if (!a.is_array()) Fail(where + "." + key, "expected an array");
    return a;
  }
  std::string String(const json& j, const std::string& where) const {
    if (!j.is_string()) Fail(where, "expected a string");
    return j.get<std::string>();
  }
  // Geometry (vertices, outlines, landmarks, uvs): coordinates within
  // +-kMaxCoordinate, so differences, areas and the mapping's integer grid
  // stay finite and exact.
  std::vector<Eigen::Vector2d> Points(const json& a, const std::string& where) const {
    std::vector<Eigen::Vector2d> out;
    out.reserve(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      const std::string w = where + "[" + std::to_string(i) + "]";
      out.push_back(Point(a[i], w));
      if (!(out.back().cwiseAbs().maxCoeff() <= kMaxCoordinate))
        Fail(w, "coordinate beyond +-1e9 (" + a[i].dump() + ")");
    }
    return out;
  }
  std::vector<std::array<std::uint32_t, 3>> ReadTriangles(const json& a, const std::string& where) const {
    std::vector<std::array<std::uint32_t, 3>> out;
    out.reserve(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      const std::string w = where + "[" + std::to_string(i) + "]";
      if (!a[i].is_array() || a[i].size() != 3) Fail(w, "expected [a, b, c]");
      out.push_back({Index(a[i][0], w), Index(a[i][1], w), Index(a[i][2], w)});
    }
    return out;
  }
};

std::string ReadText(const std::string& path, const std::string& referenced_from) {
  const std::vector<unsigned char> bytes = ReadInputFile(
      path, kMaxTextFileBytes, referenced_from.empty() ? "a rig description" : "a mesh file", referenced_from);
  return std::string(bytes.begin(), bytes.end());
}

// Keys the description may use, object by object; any other key is most
// likely a misspelt option, which would otherwise be ignored in silence.
void WarnUnknownKeys(const json& object, const std::string& where, std::initializer_list<const char*> known,
                     const std::string& file, std::vector<std::string>* warnings) {
  if (!object.is_object()) return;
  for (const auto& item : object.items()) {
    bool found = false;
    for (const char* k : known) found = found || item.key() == k;
    if (!found)
      warnings->push_back(file + ": " + (where.empty() ? "" : where + ": ") + "unknown key \"" + item.key() +
                          "\" ignored (bake/RIG_DESCRIPTION.md lists the keys)");
  }
}

void WarnUnknownKeys(const json& root, const std::string& file, std::vector<std::string>* warnings) {
  WarnUnknownKeys(
      root, "",
      {"posemorph", "name", "filter", "poses", "triangles", "parts", "glue", "mapping", "bake", "paths", "channels"},
      file, warnings);
  if (root.contains("parts") && root["parts"].is_array())
    for (std::size_t p = 0; p < root["parts"].size(); ++p) {
      const json& part = root["parts"][p];
      const std::string w = "parts[" + std::to_string(p) + "]";
      WarnUnknownKeys(part, w, {"name", "order", "triangles", "poses", "channel"}, file, warnings);
      if (part.is_object() && part.contains("poses") && part["poses"].is_array())
        for (std::size_t i = 0; i < part["poses"].size(); ++i)
          WarnUnknownKeys(part["poses"][i], w + ".poses[" + std::to_string(i) + "]",
                          {"name", "drawing", "layer", "origin", "outline", "landmarks", "features", "vertices", "mesh",
                           "uvs", "image"},
                          file, warnings);
    }
  if (root.contains("glue") && root["glue"].is_array())
    for (std::size_t g = 0; g < root["glue"].size(); ++g)
      WarnUnknownKeys(root["glue"][g], "glue[" + std::to_string(g) + "]", {"part", "to", "at"}, file, warnings);
  if (root.contains("mapping"))
    WarnUnknownKeys(root["mapping"], "mapping",
                    {"simplify_tolerance", "max_edge_length", "min_angle", "alpha_threshold", "curve_tolerance",
                     "spacing", "landmark_distance", "max_steiner_points", "max_vertices", "align_interiors",
                     "align_rigidity", "drop_shadows"},
                    file, warnings);
  if (root.contains("bake"))
    WarnUnknownKeys(
        root["bake"], "bake",
        {"grid_resolution", "margin", "epsilon", "sigma", "precision", "max_error", "pixels_per_unit", "allow_folds"},
        file, warnings);
  if (root.contains("channels") && root["channels"].is_array())
    for (std::size_t c = 0; c < root["channels"].size(); ++c) {
      const json& channel = root["channels"][c];
      const std::string w = "channels[" + std::to_string(c) + "]";
      WarnUnknownKeys(channel, w, {"name", "poses", "paths"}, file, warnings);
      if (channel.is_object() && channel.contains("poses") && channel["poses"].is_array())
        for (std::size_t i = 0; i < channel["poses"].size(); ++i)
          WarnUnknownKeys(channel["poses"][i], w + ".poses[" + std::to_string(i) + "]", {"name", "point"}, file,
                          warnings);
      if (channel.is_object() && channel.contains("paths") && channel["paths"].is_array())
        for (std::size_t i = 0; i < channel["paths"].size(); ++i)
          WarnUnknownKeys(channel["paths"][i], w + ".paths[" + std::to_string(i) + "]",
                          {"name", "loop", "interpolation", "keys"}, file, warnings);
    }
  const json no_poses = json::array();
  const json& poses = root.contains("poses") && root["poses"].is_array() ? root["poses"] : no_poses;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const std::string w = "poses[" + std::to_string(i) + "]";
    WarnUnknownKeys(poses[i], w,
                    {"name", "point", "drawing", "layer", "origin", "outline", "landmarks", "features", "vertices",
                     "mesh", "deform", "uvs", "image"},
                    file, warnings);
    if (poses[i].contains("deform")) {
      const json& d = poses[i]["deform"];
      WarnUnknownKeys(d, w + ".deform", {"from", "handles"}, file, warnings);
      if (d.contains("handles") && d["handles"].is_array())
        for (std::size_t h = 0; h < d["handles"].size(); ++h)
          WarnUnknownKeys(d["handles"][h], w + ".deform.handles[" + std::to_string(h) + "]", {"at", "vertex", "to"},
                          file, warnings);
    }
  }
  if (root.contains("paths") && root["paths"].is_array())
    for (std::size_t i = 0; i < root["paths"].size(); ++i)
      WarnUnknownKeys(root["paths"][i], "paths[" + std::to_string(i) + "]", {"name", "loop", "interpolation", "keys"},
                      file, warnings);
}

// A drawn pose: a drawing (PNG or SVG) or an outline, and its landmarks.
void ParseDrawnPose(const Reader& r, const json& jp, const std::string& w, const std::string& base_dir,
                    PoseDescription& pose) {
  pose.drawn = true;
  if (jp.contains("drawing")) {
    pose.drawing = r.String(jp["drawing"], w + ".drawing");
    pose.drawing_path = (std::filesystem::path(base_dir) / pose.drawing).string();
  } else {
    pose.outline = r.Points(r.Array(jp, "outline", w), w + ".outline");
    if (pose.outline.size() < 3) r.Fail(w + ".outline", "needs at least 3 points");
  }
  if (!jp.contains("landmarks"))
    r.Fail(w, "missing \"landmarks\": [[x, y], ...] on the outline; the first is the start point every pose shares");
  pose.landmarks = r.Points(r.Array(jp, "landmarks", w), w + ".landmarks");
  if (pose.landmarks.empty()) r.Fail(w + ".landmarks", "needs at least the start point");
  if (jp.contains("features")) pose.features = r.Points(r.Array(jp, "features", w), w + ".features");
  if (jp.contains("layer")) {
    const std::string& d = pose.drawing;
    if (d.size() < 4 || d.compare(d.size() - 4, 4, ".svg") != 0)
      r.Fail(w + ".layer", "only an SVG drawing has layers (a PNG part is its own file)");
    pose.layer = r.String(jp["layer"], w + ".layer");
    if (pose.layer.empty()) r.Fail(w + ".layer", "must not be empty (leave it out for the whole drawing)");
    pose.layer_required = true;
  }
  if (jp.contains("uvs")) r.Fail(w + ".uvs", "a drawn pose gets its uvs from its drawing; remove them");
  if (jp.contains("origin")) {
    if (!jp.contains("drawing"))
      r.Fail(w + ".origin", "only a drawing has an origin (an outline is in rig coordinates)");
    pose.origin = r.Point(jp["origin"], w + ".origin");
    if (!(std::abs(pose.origin.x()) <= 1e9 && std::abs(pose.origin.y()) <= 1e9))
      r.Fail(w + ".origin", "must lie within +-1e9 drawing units");
  }
}

// "deform": {"from": POSE, "handles": [...]} (paper section 3.2).
DeformDescription ParseDeform(const Reader& r, const json& jp, const std::string& w) {
  DeformDescription deform;
  const json& jd = jp["deform"];
  const std::string wd = w + ".deform";
  if (!jd.is_object()) r.Fail(wd, "expected {\"from\": POSE, \"handles\": [...]}");
  if (!jd.contains("from")) r.Fail(wd, "missing \"from\" (the name of the pose to deform)");
  deform.from = r.String(jd["from"], wd + ".from");
  const json& handles = r.Array(jd, "handles", wd);
  for (std::size_t h = 0; h < handles.size(); ++h) {
    const std::string wh = wd + ".handles[" + std::to_string(h) + "]";
    const json& jh = handles[h];
    if (!jh.is_object() || jh.contains("at") == jh.contains("vertex") || !jh.contains("to"))
      r.Fail(wh, "expected {\"at\": [x, y], \"to\": [x, y]} or {\"vertex\": index, \"to\": [x, y]}");
    HandleDescription handle;
    handle.by_vertex = jh.contains("vertex");
    if (handle.by_vertex)
      handle.vertex = r.Index(jh["vertex"], wh + ".vertex");
    else
      handle.at = r.Point(jh["at"], wh + ".at");
    handle.to = r.Point(jh["to"], wh + ".to");
    deform.handles.push_back(handle);
  }
  return deform;
}

// "mesh": a mesh file's vertices. Its triangles become the rig's `triangles`
// when the description has none yet (`have_triangles`), and must equal them
// otherwise.
std::vector<Eigen::Vector2d> ParseMeshFile(const Reader& r, const json& jp, const std::string& w,
                                           const std::string& file, const std::string& base_dir,
                                           std::vector<std::array<std::uint32_t, 3>>* triangles, bool* have_triangles) {
  std::vector<Eigen::Vector2d> vertices;
  const std::string rel = r.String(jp["mesh"], w + ".mesh");
  const std::string path = (std::filesystem::path(base_dir) / rel).string();
  Reader mr{path};
  const json mesh = ParseDescriptionJson(ReadText(path, file), path);
  if (!mesh.is_object()) mr.Fail("", "expected a mesh object {\"vertices\": [...], \"triangles\": [...]}");
  vertices = mr.Points(mr.Array(mesh, "vertices", ""), "vertices");
  if (mesh.contains("triangles")) {
    auto t = mr.ReadTriangles(mr.Array(mesh, "triangles", ""), "triangles");
    if (!*have_triangles) {
      *triangles = std::move(t);
      *have_triangles = true;
    } else if (t != *triangles) {
      mr.Fail("triangles", "differ from the rig's triangle list; all poses share one connectivity");
    }
  }
  return vertices;
}

// One entry of "poses", or of a part's "poses" (`rig_pose`: the rig's pose
// it draws, whose name and point it takes; `w` where it is); a mesh file may
// give the rig (or the part) its triangles (ParseMeshFile).
PoseDescription ParsePose(const Reader& r, const json& jp, std::size_t i, const std::string& file,
                          const std::string& base_dir, std::vector<std::array<std::uint32_t, 3>>* triangles,
                          bool* have_triangles, const PoseDescription* rig_pose = nullptr, std::string w = "") {
  if (w.empty()) w = "poses[" + std::to_string(i) + "]";
  if (!jp.is_object()) r.Fail(w, "expected an object");
  PoseDescription pose;
  if (rig_pose) {
    pose.name = rig_pose->name;
    pose.point = rig_pose->point;
    if (jp.contains("name") && r.String(jp["name"], w + ".name") != pose.name)
      r.Fail(w + ".name", "is \"" + jp["name"].get<std::string>() + "\", but the rig's pose " + std::to_string(i) +
                              " is '" + pose.name + "': a part lists its poses in the rig's order");
    if (jp.contains("point")) r.Fail(w + ".point", "a part's pose takes its point from the rig's \"poses\"; remove it");
  } else {
    pose.name = jp.contains("name") ? r.String(jp["name"], w + ".name") : "pose" + std::to_string(i);
    if (!jp.contains("point")) r.Fail(w, "missing \"point\" (its place in pose space)");
    pose.point = r.Point(jp["point"], w + ".point");
  }
  if (int(jp.contains("vertices")) + int(jp.contains("mesh")) + int(jp.contains("deform")) +
          int(jp.contains("drawing")) + int(jp.contains("outline")) !=
      1)
    r.Fail(w,
           "give exactly one of \"vertices\", \"mesh\" (a mesh file), \"deform\", \"drawing\" (PNG or SVG) "
           "or \"outline\"");
  if (jp.contains("drawing") || jp.contains("outline")) {
    ParseDrawnPose(r, jp, w, base_dir, pose);
  } else if (jp.contains("origin")) {
    r.Fail(w + ".origin", "only a drawing has an origin");
  } else if (jp.contains("layer")) {
    r.Fail(w + ".layer", "only an SVG drawing has layers");
  } else if (jp.contains("features")) {
    r.Fail(w + ".features",
           "only a drawn pose (a drawing or an outline) has features; a mesh's vertices correspond already");
  } else if (jp.contains("deform")) {
    pose.deformed = true;
    pose.deform = ParseDeform(r, jp, w);
  } else if (jp.contains("vertices")) {
    pose.vertices = r.Points(r.Array(jp, "vertices", w), w + ".vertices");
  } else {
    pose.vertices = ParseMeshFile(r, jp, w, file, base_dir, triangles, have_triangles);
  }
  if (jp.contains("image")) pose.image = r.String(jp["image"], w + ".image");
  if (jp.contains("uvs")) {
    for (const Eigen::Vector2d& uv : r.Points(r.Array(jp, "uvs", w), w + ".uvs")) pose.uvs.push_back(uv.cast<float>());
  }
  return pose;
}

void ParseMapping(const Reader& r, const json& m, MappingParameters* parameters) {
  if (!m.is_object()) r.Fail("mapping", "expected an object");
  MappingParameters& p = *parameters;
  auto number = [&](const char* key, double& v, double lo, double hi, const char* range) {
    if (!m.contains(key)) return;
    v = r.Number(m[key], std::string("mapping.") + key);
    if (!(v >= lo && v <= hi)) r.Fail(std::string("mapping.") + key, std::string("must be in ") + range);
  };
  number("simplify_tolerance", p.simplify_tolerance, 0, 1e6, "[0, 1e6] (0: automatic)");
  number("max_edge_length", p.max_edge_length, 0, 1e9, "[0, 1e9] (0: automatic)");
  number("min_angle", p.min_angle, 0, 35, "[0, 35] degrees");
  number("alpha_threshold", p.alpha_threshold, 1.0 / 255, 1, "[1/255, 1]");
  number("curve_tolerance", p.curve_tolerance, 1e-6, 1e6, "[1e-6, 1e6]");
  number("spacing", p.spacing, 0, 1e9, "0 (automatic) or [1e-6, 1e9]");
  if (p.spacing > 0 && p.spacing < 1e-6) r.Fail("mapping.spacing", "must be 0 (automatic) or in [1e-6, 1e9]");
  number("landmark_distance", p.landmark_distance, 0, 1, "[0, 1]");
  number("align_rigidity", p.align_rigidity, 1e-6, 1e6, "[1e-6, 1e6]");
  if (m.contains("drop_shadows")) {
    if (!m["drop_shadows"].is_boolean()) r.Fail("mapping.drop_shadows", "expected true or false");
    p.drop_shadows = m["drop_shadows"].get<bool>();
  }
  if (m.contains("align_interiors")) {
    if (!m["align_interiors"].is_boolean()) r.Fail("mapping.align_interiors", "expected true or false");
    p.align_interiors = m["align_interiors"].get<bool>();
  }
  if (m.contains("max_steiner_points")) {
    if (!m["max_steiner_points"].is_number_integer() || m["max_steiner_points"].get<long long>() < 0 ||
        m["max_steiner_points"].get<long long>() > 100000)
      r.Fail("mapping.max_steiner_points", "expected an integer in 0..100000");
    p.max_steiner_points = int(m["max_steiner_points"].get<long long>());
  }
  if (m.contains("max_vertices")) {
    if (!m["max_vertices"].is_number_integer() || m["max_vertices"].get<long long>() < 16 ||
        m["max_vertices"].get<long long>() > 100000)
      r.Fail("mapping.max_vertices", "expected an integer in 16..100000");
    p.max_vertices = int(m["max_vertices"].get<long long>());
  }
}

void ParseBakeParameters(const Reader& r, const json& b, BakeParameters* parameters) {
  if (!b.is_object()) r.Fail("bake", "expected an object");
  BakeParameters& p = *parameters;
  if (b.contains("grid_resolution")) {
    if (!b["grid_resolution"].is_number_integer()) r.Fail("bake.grid_resolution", "expected an integer");
    const auto v = b["grid_resolution"].get<long long>();
    // 256 bakes within 1 GB (the snake: 690 MB, 6 s; 384 took 1.75 GB, 18 s).
    if (v < 2 || v > 256) r.Fail("bake.grid_resolution", "must be in 2..256 (finer grids need more than 1 GB to bake)");
    p.grid_resolution = int(v);
    p.grid_resolution_given = true;
  }
  if (b.contains("margin")) p.margin = r.Number(b["margin"], "bake.margin");
  if (b.contains("epsilon")) p.epsilon = r.Number(b["epsilon"], "bake.epsilon");
  if (b.contains("sigma")) p.sigma = r.Number(b["sigma"], "bake.sigma");
  if (p.margin < 0 || p.margin > 10) r.Fail("bake.margin", "must be in [0, 10]");
  if (!(p.epsilon > 0) || p.epsilon > 1e3) r.Fail("bake.epsilon", "must be in (0, 1000]");
  if (p.sigma < 0 || p.sigma > 1) r.Fail("bake.sigma", "must be in [0, 1]");
  if (b.contains("precision")) {
    const std::string v = r.String(b["precision"], "bake.precision");
    if (v != "compact" && v != "exact") r.Fail("bake.precision", "expected \"compact\" or \"exact\"");
    p.compact = v == "compact";
  }
  if (b.contains("allow_folds")) {
    if (!b["allow_folds"].is_boolean()) r.Fail("bake.allow_folds", "expected true or false");
    p.allow_folds = b["allow_folds"].get<bool>();
  }
  if (b.contains("max_error")) p.max_error_px = r.Number(b["max_error"], "bake.max_error");
  if (!(p.max_error_px >= 1e-6) || p.max_error_px > 10) r.Fail("bake.max_error", "must be in [1e-6, 10] pixels");
  if (b.contains("pixels_per_unit")) {
    p.pixels_per_unit = r.Number(b["pixels_per_unit"], "bake.pixels_per_unit");
    if (!(p.pixels_per_unit > 0) || p.pixels_per_unit > 1e6) r.Fail("bake.pixels_per_unit", "must be in (0, 1e6]");
  }
}

// One entry of "paths"; `earlier` are the ones before it (names are unique).
PathDescription ParsePath(const Reader& r, const json& jp, std::size_t i, const std::vector<PathDescription>& earlier,
                          const std::string& prefix = "") {
  const std::string w = prefix + "paths[" + std::to_string(i) + "]";
  if (!jp.is_object()) r.Fail(w, "expected an object");
  PathDescription path;
  if (!jp.contains("name")) r.Fail(w, "missing \"name\"");
  path.name = r.String(jp["name"], w + ".name");
  if (jp.contains("loop")) {
    if (!jp["loop"].is_boolean()) r.Fail(w + ".loop", "expected true or false");
    path.loop = jp["loop"].get<bool>();
  }
  if (jp.contains("interpolation")) {
    const std::string mode = r.String(jp["interpolation"], w + ".interpolation");
    if (mode != "linear" && mode != "catmull-rom")
      r.Fail(w + ".interpolation", "\"" + mode + "\" is not \"linear\" or \"catmull-rom\"");
    path.catmull_rom = mode == "catmull-rom";
  }
  const json& keys = r.Array(jp, "keys", w);
  if (keys.empty()) r.Fail(w + ".keys", "needs at least one key");
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const std::string wk = w + ".keys[" + std::to_string(k) + "]";
    if (!keys[k].is_array() || keys[k].size() != 3) r.Fail(wk, "expected [time, x, y]");
    path.keys.push_back({r.Number(keys[k][0], wk), r.Number(keys[k][1], wk), r.Number(keys[k][2], wk)});
    for (double v : path.keys[k])
      if (!(std::fabs(v) <= format::kMaxPathValue))
        r.Fail(wk, "times and coordinates must lie within +-1e12 (the runtime's limit)");
    if (k > 0 && !(path.keys[k][0] > path.keys[k - 1][0])) r.Fail(wk, "key times must increase strictly");
  }
  for (const PathDescription& other : earlier)
    if (other.name == path.name) r.Fail(w + ".name", "path \"" + path.name + "\" is defined twice");
  return path;
}

// Which poses are drawn decides where the triangles come from (`w`: the
// object that holds them, "" for the rig).
void CheckPoseKinds(const Reader& r, const std::vector<PoseDescription>& poses, bool have_triangles,
                    const std::string& w = "") {
  const std::string prefix = w.empty() ? "" : w + ".";
  bool any_drawn = false, all_meshed = true;
  for (const PoseDescription& p : poses) any_drawn |= p.drawn, all_meshed &= p.drawn || p.deformed;
  if (any_drawn && have_triangles)
    r.Fail(prefix + "triangles",
           "drawn poses get their triangles from the mapping; remove \"triangles\" and mesh files");
  if (any_drawn && !all_meshed)
    r.Fail(prefix + "poses",
           "when one pose is drawn, every pose must be drawn (\"drawing\" or \"outline\") or deformed");
  if (!have_triangles && !any_drawn)
    r.Fail(prefix + "triangles", "missing: give \"triangles\" or a mesh file that has them");
}

// With "parts", the rig's poses give a name and a point each; what they look
// like is in every part's "poses".
std::vector<PoseDescription> ParseLayeredPoses(const Reader& r, const json& poses, const std::string& prefix = "") {
  std::vector<PoseDescription> out;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const std::string w = prefix + "poses[" + std::to_string(i) + "]";
    const json& jp = poses[i];
    if (!jp.is_object()) r.Fail(w, "expected an object");
    for (const char* key : {"drawing", "layer", "outline", "vertices", "mesh", "deform", "image", "uvs", "landmarks",
                            "features", "origin"})
      if (jp.contains(key))
        r.Fail(w + "." + key,
               "with \"parts\", a rig's pose gives its name and point only; what it looks like goes "
               "in each part's \"poses\"");
    PoseDescription pose;
    pose.name = jp.contains("name") ? r.String(jp["name"], w + ".name") : "pose" + std::to_string(i);
    if (!jp.contains("point")) r.Fail(w, "missing \"point\" (its place in pose space)");
    pose.point = r.Point(jp["point"], w + ".point");
    out.push_back(std::move(pose));
  }
  return out;
}

// "parts": [{"name", "order", "triangles", "poses"}, ...], each pose as in
// the rig's "poses" less the name and point.
std::vector<PartDescription> ParseParts(const Reader& r, const json& parts,
                                        const std::vector<ChannelDescription>& channels, const std::string& file,
                                        const std::string& base_dir) {
  if (parts.empty()) r.Fail("parts", "needs at least one part");
  if (parts.size() > format::kMaxParts)
    r.Fail("parts", std::to_string(parts.size()) + " parts, more than the rig format's limit of " +
                        std::to_string(format::kMaxParts));
  std::vector<PartDescription> out;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    const std::string w = "parts[" + std::to_string(p) + "]";
    const json& jp = parts[p];
    if (!jp.is_object()) r.Fail(w, "expected an object");
    PartDescription part;
    if (!jp.contains("name")) r.Fail(w, "missing \"name\"");
    part.name = r.String(jp["name"], w + ".name");
    if (jp.contains("channel")) {
      if (channels.size() < 2) r.Fail(w + ".channel", "the rig has no \"channels\"; remove it");
      const std::string name = r.String(jp["channel"], w + ".channel");
      part.channel = channels.size();
      for (std::size_t c = 0; c < channels.size(); ++c)
        if (channels[c].name == name) part.channel = c;
      if (part.channel == channels.size()) r.Fail(w + ".channel", "no channel is named '" + name + "'");
    }
    const std::vector<PoseDescription>& poses = channels[part.channel].poses;
    const std::string rig_poses = channels.size() < 2 ? "the rig" : "its channel '" + channels[part.channel].name + "'";
    if (part.name.empty()) r.Fail(w + ".name", "must not be empty");
    for (const PartDescription& other : out)
      if (other.name == part.name) r.Fail(w + ".name", "part '" + part.name + "' is defined twice");
    part.order = int(p);
    if (jp.contains("order")) {
      // One order, or one per pose (an arm that passes behind the body).
      const auto read_order = [&](const json& v, const std::string& where) {
        if (!v.is_number_integer() || std::llabs(v.get<long long>()) > 1000000)
          r.Fail(where, "expected an integer in -1000000..1000000 (lower draws first)");
        return int(v.get<long long>());
      };
      const json& order = jp["order"];
      if (order.is_array()) {
        if (order.size() != poses.size())
          r.Fail(w + ".order", "part '" + part.name + "' has " + std::to_string(order.size()) + " draw orders, " +
                                   rig_poses + " " + std::to_string(poses.size()) +
                                   " poses: give one order, or one per pose");
        for (std::size_t i = 0; i < order.size(); ++i)
          part.pose_orders.push_back(read_order(order[i], w + ".order[" + std::to_string(i) + "]"));
        part.order = part.pose_orders[0];
      } else {
        part.order = read_order(order, w + ".order");
      }
    }
    bool have_triangles = jp.contains("triangles");
    if (have_triangles) part.triangles = r.ReadTriangles(r.Array(jp, "triangles", w), w + ".triangles");
    const json& jposes = r.Array(jp, "poses", w);
    if (jposes.size() != poses.size())
      r.Fail(w + ".poses", "part '" + part.name + "' has " + std::to_string(jposes.size()) + " poses, " + rig_poses +
                               " " + std::to_string(poses.size()) +
                               ": every part is drawn in every pose (one that should " +
                               "vanish is drawn tiny, or hidden behind another by its order)");
    for (std::size_t i = 0; i < jposes.size(); ++i)
      part.poses.push_back(ParsePose(
          r, jposes[i], i, file, base_dir, &part.triangles, &have_triangles, &poses[i],
          "part '" + part.name + "', pose '" + poses[i].name + "': " + w + ".poses[" + std::to_string(i) + "]"));
    CheckPoseKinds(r, part.poses, have_triangles, w);
    // An SVG drawing shared by the parts: each takes the layer of its name.
    for (PoseDescription& pose : part.poses)
      if (pose.drawn && pose.layer.empty() && pose.drawing.size() >= 4 &&
          pose.drawing.compare(pose.drawing.size() - 4, 4, ".svg") == 0)
        pose.layer = part.name;
    for (const PoseDescription& pose : part.poses)
      if (pose.deformed)
        r.Fail(w + ".poses",
               "a part's pose is drawn or given as vertices (\"deform\" is not yet "
               "supported in parts)");
    out.push_back(std::move(part));
  }
  return out;
}

// "glue": [{"part", "to", "at"}, ...]: the parts and the glue between them
// make a tree (every part reached from every other, in one way only).
std::vector<GlueDescription> ParseGlue(const Reader& r, const json& glue, const std::vector<PartDescription>& parts,
                                       const std::vector<ChannelDescription>& channels) {
  std::vector<GlueDescription> out;
  std::vector<std::size_t> root(parts.size());
  for (std::size_t p = 0; p < parts.size(); ++p) root[p] = p;
  auto find = [&](std::size_t p) {
    while (root[p] != p) p = root[p] = root[root[p]];
    return p;
  };
  auto index_of = [&](const std::string& name, const std::string& w) {
    for (std::size_t p = 0; p < parts.size(); ++p)
      if (parts[p].name == name) return p;
    r.Fail(w, "no part is named '" + name + "'");
  };
  for (std::size_t g = 0; g < glue.size(); ++g) {
    const std::string w = "glue[" + std::to_string(g) + "]";
    const json& jg = glue[g];
    if (!jg.is_object() || !jg.contains("part") || !jg.contains("to") || !jg.contains("at"))
      r.Fail(w, "expected {\"part\": NAME, \"to\": NAME, \"at\": [x, y] or one [x, y] per pose}");
    GlueDescription e;
    e.part = r.String(jg["part"], w + ".part");
    e.to = r.String(jg["to"], w + ".to");
    e.part_index = index_of(e.part, w + ".part");
    e.to_index = index_of(e.to, w + ".to");
    if (e.part_index == e.to_index) r.Fail(w, "part '" + e.part + "' is glued to itself");
    const PartDescription& attached = parts[e.part_index];
    const std::size_t pose_count = attached.poses.size();
    if (parts[e.to_index].channel != 0)
      r.Fail(w + ".to", "part '" + e.to + "' is driven by channel '" + channels[parts[e.to_index].channel].name +
                            "': a part is glued to a part of the first channel ('" + channels[0].name +
                            "'), which carries the others");
    if (attached.channel != 0)
      for (const GlueDescription& other : out)
        if (other.part_index == e.part_index)
          r.Fail(w, "part '" + e.part + "' (channel '" + channels[attached.channel].name +
                        "') is glued twice: a part of another channel hangs from one joint");
    const json& at = jg["at"];
    if (at.is_array() && at.size() == 2 && at[0].is_number()) {
      e.at.push_back(r.Point(at, w + ".at"));
    } else {
      if (!at.is_array() || at.size() != pose_count)
        r.Fail(w + ".at", "expected [x, y] or one [x, y] per pose (" + std::to_string(pose_count) + ")");
      e.at = r.Points(at, w + ".at");
    }
    if (attached.channel != 0) {
      out.push_back(std::move(e));
      continue;
    }
    const std::size_t a = find(e.part_index), b = find(e.to_index);
    if (a == b)
      r.Fail(w, "gluing '" + e.part + "' to '" + e.to + "' closes a cycle: they are glued together already " +
                    "(directly or through other parts), and a cycle of glue over-constrains the joints; remove one");
    root[a] = b;
    out.push_back(std::move(e));
  }
  std::size_t first = 0;
  while (first < parts.size() && parts[first].channel != 0) ++first;
  if (first == parts.size()) r.Fail("parts", "no part is driven by the first channel ('" + channels[0].name + "')");
  for (std::size_t p = 0; p < parts.size(); ++p) {
    if (parts[p].channel != 0) {
      bool glued = false;
      for (const GlueDescription& e : out) glued = glued || e.part_index == p;
      if (!glued)
        r.Fail("glue", "part '" + parts[p].name + "' (channel '" + channels[parts[p].channel].name +
                           "') is glued to nothing: glue it to a part of channel '" + channels[0].name + "'");
    } else if (find(p) != find(first)) {
      r.Fail("glue", "part '" + parts[p].name + "' is not glued to part '" + parts[first].name +
                         "' (directly or through other parts): a character's parts are one piece");
    }
  }
  return out;
}

// "channels": [{"name", "poses": [{"name", "point"}, ...], "paths"}, ...]:
// two or more pose spaces; the first is the rig's ("poses" and "paths" go
// in it), each part names its channel.
void ParseChannels(const Reader& r, const json& root, RigDescription* rig) {
  if (!root.contains("parts"))
    r.Fail("channels", "a rig with channels is drawn as parts: give \"parts\", each naming its channel");
  if (root.contains("poses"))
    r.Fail("poses", "with \"channels\", each channel lists its poses: move them into channels[0].poses");
  if (root.contains("paths"))
    r.Fail("paths", "with \"channels\", each channel lists its paths: move them into channels[0].paths");
  const json& channels = r.Array(root, "channels", "");
  if (channels.size() < 2 || channels.size() > format::kMaxChannels)
    r.Fail("channels", std::to_string(channels.size()) + " channels: give 2 to " +
                           std::to_string(format::kMaxChannels) + " (the rig format's limit), or none");
  for (std::size_t c = 0; c < channels.size(); ++c) {
    const std::string w = "channels[" + std::to_string(c) + "]";
    const json& jc = channels[c];
    if (!jc.is_object()) r.Fail(w, "expected an object");
    ChannelDescription channel;
    if (!jc.contains("name")) r.Fail(w, "missing \"name\"");
    channel.name = r.String(jc["name"], w + ".name");
    if (channel.name.empty() || channel.name.size() > format::kMaxChannelName)
      r.Fail(w + ".name", "must be 1 to " + std::to_string(format::kMaxChannelName) + " bytes");
    for (const ChannelDescription& other : rig->channels)
      if (other.name == channel.name) r.Fail(w + ".name", "channel '" + channel.name + "' is defined twice");
    channel.poses = ParseLayeredPoses(r, r.Array(jc, "poses", w), w + ".");
    if (channel.poses.size() < 2 || channel.poses.size() > format::kMaxPoses)
      r.Fail(w + ".poses", "channel '" + channel.name + "' has " + std::to_string(channel.poses.size()) +
                               " poses: a channel needs 2 to " + std::to_string(format::kMaxPoses));
    if (jc.contains("paths")) {
      const json& paths = r.Array(jc, "paths", w);
      for (std::size_t i = 0; i < paths.size(); ++i) {
        PathDescription path = ParsePath(r, paths[i], i, channel.paths, w + ".");
        channel.paths.push_back(std::move(path));
      }
    }
    rig->channels.push_back(std::move(channel));
  }
}

}  // namespace

RigDescription ParseRigDescription(const std::string& text, const std::string& file, const std::string& base_dir) {
  Reader r{file};
  const json root = ParseDescriptionJson(text, file);
  if (!root.is_object()) r.Fail("", "expected a JSON object at the top level");
  if (!root.contains("posemorph") || !root["posemorph"].is_number_integer() || root["posemorph"].get<int>() != 1)
    r.Fail("posemorph", "missing or unsupported schema version (this bake reads \"posemorph\": 1)");

  RigDescription rig;
  rig.file = file;
  if (root.contains("name")) rig.name = r.String(root["name"], "name");
  if (root.contains("filter")) {
    const std::string f = r.String(root["filter"], "filter");
    if (f != "linear" && f != "nearest") r.Fail("filter", "expected \"linear\" or \"nearest\" (pixel art)");
    rig.nearest_filter = f == "nearest";
  }
  bool have_triangles = root.contains("triangles");
  if (root.contains("channels")) ParseChannels(r, root, &rig);
  if (root.contains("parts")) {
    if (rig.channels.empty()) rig.channels.push_back({"", ParseLayeredPoses(r, r.Array(root, "poses", "")), {}});
    if (have_triangles) r.Fail("triangles", "with \"parts\", each part has its own triangles; remove it");
    rig.poses = rig.channels[0].poses;
    rig.parts = ParseParts(r, r.Array(root, "parts", ""), rig.channels, file, base_dir);
    if (rig.parts.size() > 1 || rig.channels.size() > 1) {
      std::size_t attachments = 0;
      for (const PartDescription& part : rig.parts) attachments += part.channel != 0;
      if (attachments > format::kMaxAttachments)
        r.Fail("parts", std::to_string(attachments) + " parts are driven by channels after the first, more than " +
                            "the rig format's limit of " + std::to_string(format::kMaxAttachments));
    }
    if (root.contains("glue"))
      rig.glue = ParseGlue(r, r.Array(root, "glue", ""), rig.parts, rig.channels);
    else if (rig.parts.size() > 1)
      r.Fail("", "missing \"glue\": the parts must be glued together at joints");
  } else {
    if (root.contains("glue")) r.Fail("glue", "only a rig with \"parts\" has glue");
    if (have_triangles) rig.triangles = r.ReadTriangles(r.Array(root, "triangles", ""), "triangles");
    const json& poses = r.Array(root, "poses", "");
    for (std::size_t i = 0; i < poses.size(); ++i)
      rig.poses.push_back(ParsePose(r, poses[i], i, file, base_dir, &rig.triangles, &have_triangles));
    CheckPoseKinds(r, rig.poses, have_triangles);
  }
  if (root.contains("mapping")) ParseMapping(r, root["mapping"], &rig.mapping);
  if (root.contains("bake")) ParseBakeParameters(r, root["bake"], &rig.parameters);
  if (root.contains("paths")) {
    const json& paths = r.Array(root, "paths", "");
    for (std::size_t i = 0; i < paths.size(); ++i) rig.paths.push_back(ParsePath(r, paths[i], i, rig.paths));
  }
  if (rig.channels.size() > 1) {
    rig.paths = rig.channels[0].paths;
  } else {
    rig.channels.clear();
  }
  WarnUnknownKeys(root, file, &rig.warnings);
  return rig;
}

RigDescription ReadRigDescription(const std::string& path) {
  const std::string text = ReadText(path, "");
  return ParseRigDescription(text, path, std::filesystem::path(path).parent_path().string());
}

}  // namespace posemorph::bake
