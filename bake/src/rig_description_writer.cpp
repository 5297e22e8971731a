// SPDX-License-Identifier: MIT
// Writing rig descriptions and mesh files (JSON): the inverse of
// rig_description.cpp, with the same keys (bake/RIG_DESCRIPTION.md).
#include <algorithm>

#include <cmath>

#include <nlohmann/json.hpp>

#include "description_json.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/rig_description.h"

namespace posemorph::bake {
namespace {

using nlohmann::json;

json PointJson(const Eigen::Vector2d& p) { return json::array({p.x(), p.y()}); }

json PointsJson(const std::vector<Eigen::Vector2d>& points) {
  json a = json::array();
  for (const Eigen::Vector2d& p : points) a.push_back(PointJson(p));
  return a;
}

json DeformJson(const DeformDescription& deform) {
  json handles = json::array();
  for (const HandleDescription& h : deform.handles) {
    json jh = h.by_vertex ? json{{"vertex", h.vertex}} : json{{"at", PointJson(h.at)}};
    jh["to"] = PointJson(h.to);
    handles.push_back(std::move(jh));
  }
  return {{"from", deform.from}, {"handles", std::move(handles)}};
}

json PoseJson(const PoseDescription& pose) {
  json j = {{"name", pose.name}, {"point", PointJson(pose.point)}};
  if (pose.drawn) {
    if (!pose.drawing.empty()) {
      j["drawing"] = pose.drawing;
      if (pose.origin != Eigen::Vector2d::Zero()) j["origin"] = PointJson(pose.origin);
    } else {
      j["outline"] = PointsJson(pose.outline);
    }
    j["landmarks"] = PointsJson(pose.landmarks);
    if (!pose.features.empty()) j["features"] = PointsJson(pose.features);
  } else if (pose.deformed) {
    j["deform"] = DeformJson(pose.deform);
  } else {
    j["vertices"] = PointsJson(pose.vertices);
  }
  if (!pose.image.empty()) j["image"] = pose.image;
  if (!pose.drawn && !pose.uvs.empty()) {
    json uvs = json::array();
    for (const Eigen::Vector2f& uv : pose.uvs) uvs.push_back(json::array({double(uv.x()), double(uv.y())}));
    j["uvs"] = std::move(uvs);
  }
  return j;
}

json PathJson(const PathDescription& path) {
  json j = {{"name", path.name},
            {"loop", path.loop},
            {"interpolation", path.catmull_rom ? "catmull-rom" : "linear"},
            {"keys", path.keys}};
  if (!path.events.empty()) {
    json events = json::array();
    for (const auto& [time, name] : path.events) events.push_back(json::array({time, name}));
    j["events"] = std::move(events);
  }
  return j;
}

json BakeJson(const BakeParameters& p) {
  const BakeParameters d;
  json j = {{"margin", p.margin}, {"epsilon", p.epsilon}, {"sigma", p.sigma}};
  // Written when given (or changed): left out, the bake chooses it for the
  // sprite (grid_resolution.h), as it did for the description read.
  if (p.grid_resolution_given || p.grid_resolution != d.grid_resolution) j["grid_resolution"] = p.grid_resolution;
  if (p.compact != d.compact) j["precision"] = p.compact ? "compact" : "exact";
  if (p.max_error_px != d.max_error_px) j["max_error"] = p.max_error_px;
  if (p.pixels_per_unit != d.pixels_per_unit) j["pixels_per_unit"] = p.pixels_per_unit;
  if (p.allow_folds != d.allow_folds) j["allow_folds"] = p.allow_folds;
  return j;
}

// Only the parameters that differ from their defaults; null if none does.
json MappingJson(const MappingParameters& p) {
  const MappingParameters d;
  json j = json::object();
  auto put = [&](const char* key, auto value, auto default_value) {
    if (value != default_value) j[key] = value;
  };
  put("simplify_tolerance", p.simplify_tolerance, d.simplify_tolerance);
  put("max_edge_length", p.max_edge_length, d.max_edge_length);
  put("min_angle", p.min_angle, d.min_angle);
  put("alpha_threshold", p.alpha_threshold, d.alpha_threshold);
  put("curve_tolerance", p.curve_tolerance, d.curve_tolerance);
  put("spacing", p.spacing, d.spacing);
  put("landmark_distance", p.landmark_distance, d.landmark_distance);
  put("max_steiner_points", p.max_steiner_points, d.max_steiner_points);
  put("max_vertices", p.max_vertices, d.max_vertices);
  put("align_interiors", p.align_interiors, d.align_interiors);
  put("drop_shadows", p.drop_shadows, d.drop_shadows);
  put("align_rigidity", p.align_rigidity, d.align_rigidity);
  put("working_size", p.working_size, d.working_size);
  put("map_again", p.map_again, d.map_again);
  put("retry_seconds", p.retry_seconds, d.retry_seconds);
  return j.empty() ? json() : j;
}

template <class Json>
Json& ListIn(Json& root, const char* key, const std::string& file) {
  if (!root.contains(key)) root[key] = Json::array();
  if (!root[key].is_array()) throw BakeError(file, std::string(key) + ": expected an array");
  return root[key];
}

// "STEM-K" for the smallest K >= 1 that no entry of `list` is named.
template <class Json>
std::string FreshName(const Json& list, const std::string& stem) {
  for (long k = 1;; ++k) {
    const std::string name = stem + "-" + std::to_string(k);
    if (std::none_of(list.begin(), list.end(), [&](const Json& e) {
          return e.is_object() && e.contains("name") && e["name"].is_string() && e["name"] == name;
        }))
      return name;
  }
}

}  // namespace

std::string RigDescriptionText(const RigDescription& rig) {
  json root;
  root["posemorph"] = 1;
  root["name"] = rig.name;
  if (rig.nearest_filter) root["filter"] = "nearest";
  if (rig.anchor_given) root["anchor"] = {rig.anchor.x(), rig.anchor.y()};
  if (rig.facing_left) root["facing"] = "left";
  if (rig.atlas_given) {
    if (!rig.atlas.enabled)
      root["atlas"] = false;
    else
      root["atlas"] = {{"max_page_size", rig.atlas.max_page_size}, {"padding", rig.atlas.padding}};
  }
  const bool any_drawn = std::any_of(rig.poses.begin(), rig.poses.end(), [](const auto& p) { return p.drawn; });
  if (!any_drawn) root["triangles"] = rig.triangles;
  json poses = json::array();
  for (const PoseDescription& pose : rig.poses) poses.push_back(PoseJson(pose));
  root["poses"] = std::move(poses);
  if (json mapping = MappingJson(rig.mapping); !mapping.is_null()) root["mapping"] = std::move(mapping);
  root["bake"] = BakeJson(rig.parameters);
  json paths = json::array();
  for (const PathDescription& path : rig.paths) paths.push_back(PathJson(path));
  root["paths"] = std::move(paths);
  return root.dump() + "\n";
}

std::string MeshFileText(const std::vector<Eigen::Vector2d>& vertices,
                         const std::vector<std::array<std::uint32_t, 3>>& triangles) {
  return json{{"vertices", PointsJson(vertices)}, {"triangles", triangles}}.dump() + "\n";
}

namespace {

using ordered = nlohmann::ordered_json;

// An array without objects in it, written on one line: [1, 2], [[1, 2], [3, 4]].
bool Flat(const ordered& j) {
  if (!j.is_array()) return !j.is_object();
  return std::all_of(j.begin(), j.end(), [](const ordered& e) { return Flat(e); });
}
std::string Inline(const ordered& j) {
  if (!j.is_array()) return j.dump(-1, ' ', false, ordered::error_handler_t::replace);
  std::string s = "[";
  for (std::size_t i = 0; i < j.size(); ++i) s += (i ? ", " : "") + Inline(j[i]);
  return s + "]";
}
// Objects one key a line, indented by two; a flat array on one line, or one
// element a line when that line would pass 100 characters.
void Write(const ordered& j, int indent, std::string& out) {
  const std::string pad(std::size_t(indent) + 2, ' ');
  if (j.is_object() && !j.empty()) {
    out += "{\n";
    std::size_t k = 0;
    for (auto it = j.begin(); it != j.end(); ++it, ++k) {
      out += pad + ordered(it.key()).dump(-1, ' ', false, ordered::error_handler_t::replace) + ": ";
      Write(it.value(), indent + 2, out);
      out += k + 1 < j.size() ? ",\n" : "\n";
    }
    out += std::string(std::size_t(indent), ' ') + "}";
  } else if (j.is_array() && !j.empty() && !(Flat(j) && Inline(j).size() + std::size_t(indent) <= 100)) {
    out += "[\n";
    for (std::size_t i = 0; i < j.size(); ++i) {
      out += pad;
      Write(j[i], indent + 2, out);
      out += i + 1 < j.size() ? ",\n" : "\n";
    }
    out += std::string(std::size_t(indent), ' ') + "]";
  } else {
    out += Inline(j);
  }
}

// The description's JSON in its own key order (the text is checked by the
// reader's parser first, for its messages).
ordered Ordered(const std::string& text, const std::string& file) {
  const json checked = ParseDescriptionJson(text, file);
  if (!checked.is_object()) throw BakeError(file, "expected a JSON object at the top level");
  return ordered::parse(text);
}

}  // namespace

std::string DescriptionJsonText(const std::string& text, const std::string& file) {
  std::string out;
  Write(Ordered(text, file), 0, out);
  return out + "\n";
}

std::string MovePosePoint(const std::string& text, const std::string& file, const std::string& pose, double x,
                          double y) {
  ordered root = Ordered(text, file);
  ordered* home = &root;
  if (root.contains("channels")) {
    if (!root["channels"].is_array() || root["channels"].empty() || !root["channels"][0].is_object())
      throw BakeError(file, "channels: expected an array of channel objects");
    home = &root["channels"][0];
  }
  if (!home->contains("poses") || !(*home)["poses"].is_array())
    throw BakeError(file, std::string(home == &root ? "" : "channels[0].") + "poses: expected an array");
  bool found = false;
  for (ordered& p : (*home)["poses"])
    if (p.is_object() && p.contains("name") && p["name"] == pose) {
      // Four decimals: the pad's resolution, and a short number to read.
      p["point"] = ordered::array({std::round(x * 1e4) / 1e4 + 0.0, std::round(y * 1e4) / 1e4 + 0.0});
      found = true;
    }
  if (!found) throw BakeError(file, "has no pose named '" + pose + "' to move");
  std::string out;
  Write(root, 0, out);
  return out + "\n";
}

std::string SetDrawnPoints(const std::string& text, const std::string& file, const std::string& part,
                           const std::string& key, const std::vector<std::vector<Eigen::Vector2d>>& lists) {
  if (key != "landmarks" && key != "features") throw BakeError(file, "no list '" + key + "' to set");
  ordered root = Ordered(text, file);
  if (root.contains("channels"))
    throw BakeError(file, "a rig with channels: place its landmarks and features in the description by hand");
  ordered* poses = nullptr;
  std::string where = "poses";
  if (part.empty()) {
    if (root.contains("poses") && root["poses"].is_array()) poses = &root["poses"];
  } else if (root.contains("parts") && root["parts"].is_array()) {
    for (std::size_t q = 0; q < root["parts"].size(); ++q) {
      ordered& p = root["parts"][q];
      if (p.is_object() && p.contains("name") && p["name"] == part && p.contains("poses") && p["poses"].is_array())
        poses = &p["poses"], where = "parts[" + std::to_string(q) + "].poses";
    }
  }
  if (!poses) throw BakeError(file, part.empty() ? "has no poses array" : "has no part named '" + part + "'");
  if (poses->size() != lists.size())
    throw BakeError(file,
                    where + " has " + std::to_string(poses->size()) + " poses, not " + std::to_string(lists.size()));
  for (std::size_t i = 0; i < lists.size(); ++i) {
    ordered& pose = (*poses)[i];
    if (!pose.is_object()) throw BakeError(file, where + "[" + std::to_string(i) + "]: expected an object");
    ordered points = ordered::array();
    // Three decimals: a thousandth of a drawing pixel.
    for (const Eigen::Vector2d& p : lists[i])
      points.push_back(ordered::array({std::round(p.x() * 1e3) / 1e3 + 0.0, std::round(p.y() * 1e3) / 1e3 + 0.0}));
    if (points.empty() && key == "features")
      pose.erase(key);
    else
      pose[key] = std::move(points);
  }
  std::string out;
  Write(root, 0, out);
  return out + "\n";
}

DescriptionAddition AddToRigDescription(const std::string& text, const std::string& file,
                                        const std::vector<PoseDescription>& poses,
                                        const std::vector<PathDescription>& paths) {
  ordered root = Ordered(text, file);
  DescriptionAddition added;
  // A rig with control channels keeps its poses and paths in its channels:
  // a path goes to the first channel's (the body's, which the pad and the
  // gestures drive); a pose would need a drawing per part, which only the
  // description's author can give.
  ordered* paths_home = &root;
  if (root.contains("channels")) {
    if (!root["channels"].is_array() || root["channels"].empty() || !root["channels"][0].is_object())
      throw BakeError(file, "channels: expected an array of channel objects");
    if (!poses.empty())
      throw BakeError(file,
                      "a rig with channels takes a new pose as a pose of its channel and of each of its parts; "
                      "add it to the description by hand");
    paths_home = &root["channels"][0];
  }
  if (root.contains("parts") && !poses.empty())
    throw BakeError(file,
                    "a layered rig takes a new pose as a pose of each of its parts, with its drawings; add it to the "
                    "description by hand");
  for (PoseDescription pose : poses) {
    ordered& list = ListIn(root, "poses", file);
    pose.name = FreshName(list, pose.name);
    added.pose_names.push_back(pose.name);
    list.push_back(ordered::parse(PoseJson(pose).dump()));
  }
  for (PathDescription path : paths) {
    ordered& list = ListIn(*paths_home, "paths", file);
    path.name = FreshName(list, path.name);
    added.path_names.push_back(path.name);
    list.push_back(ordered::parse(PathJson(path).dump()));
  }
  Write(root, 0, added.text);
  added.text += "\n";
  return added;
}

}  // namespace posemorph::bake
