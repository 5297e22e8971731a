// SPDX-License-Identifier: MIT
// The rig description's poses: drawn, given as meshes, or deformed.
#include "description_json.h"
#include "description_reader.h"

#include <cmath>
#include <filesystem>

namespace posemorph::bake::description {

namespace {

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

}  // namespace

// One entry of "poses", or of a part's "poses" (`rig_pose`: the rig's pose
// it draws, whose name and point it takes; `w` where it is); a mesh file may
// give the rig (or the part) its triangles (ParseMeshFile).
PoseDescription ParsePose(const Reader& r, const json& jp, std::size_t i, const std::string& file,
                          const std::string& base_dir, std::vector<std::array<std::uint32_t, 3>>* triangles,
                          bool* have_triangles, const PoseDescription* rig_pose, std::string w) {
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

// Which poses are drawn decides where the triangles come from (`w`: the
// object that holds them, "" for the rig).
void CheckPoseKinds(const Reader& r, const std::vector<PoseDescription>& poses, bool have_triangles,
                    const std::string& w) {
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
std::vector<PoseDescription> ParseLayeredPoses(const Reader& r, const json& poses, const std::string& prefix) {
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

}  // namespace posemorph::bake::description
