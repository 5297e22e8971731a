// SPDX-License-Identifier: MIT
// The rig description's "mapping" and "bake" parameters and its "paths".
#include "description_reader.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "posemorph/rig_format.h"

namespace posemorph::bake::description {

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
  number("retry_seconds", p.retry_seconds, 0, 86400, "[0, 86400] seconds (0: no limit)");
  if (m.contains("map_again")) {
    if (!m["map_again"].is_boolean()) r.Fail("mapping.map_again", "expected true or false");
    p.map_again = m["map_again"].get<bool>();
  }
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
  if (m.contains("working_size")) {
    const json& w = m["working_size"];
    if (!w.is_number_integer() ||
        !(w.get<long long>() == 0 || (w.get<long long>() >= 32 && w.get<long long>() <= 16384)))
      r.Fail("mapping.working_size", "expected 0 (full resolution) or an integer in 32..16384 (pixels)");
    p.working_size = int(w.get<long long>());
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
                          const std::string& prefix) {
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
  if (jp.contains("events")) {
    const json& events = r.Array(jp, "events", w);
    const double first = path.keys.front()[0], last = path.keys.back()[0];
    for (std::size_t e = 0; e < events.size(); ++e) {
      const std::string we = w + ".events[" + std::to_string(e) + "]";
      if (!events[e].is_array() || events[e].size() != 2) r.Fail(we, "expected [time, \"name\"]");
      const double time = r.Number(events[e][0], we);
      const std::string name = r.String(events[e][1], we + " name");
      if (name.empty()) r.Fail(we, "an event needs a name");
      if (!(time >= first && time <= last)) {
        std::ostringstream range;
        range << "time " << time << " is outside path \"" << path.name << "\"'s keys [" << first << ", " << last << "]";
        r.Fail(we, range.str());
      }
      path.events.emplace_back(time, name);
    }
    std::stable_sort(path.events.begin(), path.events.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
  }
  for (const PathDescription& other : earlier)
    if (other.name == path.name) r.Fail(w + ".name", "path \"" + path.name + "\" is defined twice");
  return path;
}

}  // namespace posemorph::bake::description
