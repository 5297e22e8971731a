// SPDX-License-Identifier: MIT
// A RigDescription as rig-description JSON (the inverse of ParseRigDescription).
#pragma once
#include <string>

#include <nlohmann/json.hpp>

#include "posemorph/bake/rig_description.h"

namespace posemorph::samples {

inline std::string DescriptionJson(const bake::RigDescription& rig) {
  using nlohmann::json;
  // Rounded to 1e-9: readable files, and what the file says is what gets baked.
  auto round = [](double v) { return std::round(v * 1e9) / 1e9; };
  json root;
  root["posemorph"] = 1;
  root["name"] = rig.name;
  root["triangles"] = rig.triangles;
  json poses = json::array();
  for (const auto& p : rig.poses) {
    json jp;
    jp["name"] = p.name;
    jp["point"] = {p.point.x(), p.point.y()};
    if (p.deformed) {
      json handles = json::array();
      for (const auto& h : p.deform.handles) {
        json jh = h.by_vertex ? json{{"vertex", h.vertex}} : json{{"at", {h.at.x(), h.at.y()}}};
        jh["to"] = {h.to.x(), h.to.y()};
        handles.push_back(std::move(jh));
      }
      jp["deform"] = {{"from", p.deform.from}, {"handles", std::move(handles)}};
    } else {
      json v = json::array();
      for (const auto& q : p.vertices) v.push_back({round(q.x()), round(q.y())});
      jp["vertices"] = std::move(v);
    }
    poses.push_back(std::move(jp));
  }
  root["poses"] = std::move(poses);
  root["bake"] = {{"grid_resolution", rig.parameters.grid_resolution},
                  {"margin", rig.parameters.margin},
                  {"epsilon", rig.parameters.epsilon},
                  {"sigma", rig.parameters.sigma}};
  json paths = json::array();
  for (const auto& path : rig.paths)
    paths.push_back({{"name", path.name},
                     {"loop", path.loop},
                     {"interpolation", path.catmull_rom ? "catmull-rom" : "linear"},
                     {"keys", path.keys}});
  root["paths"] = std::move(paths);
  return root.dump() + "\n";
}

}  // namespace posemorph::samples
