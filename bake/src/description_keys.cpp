// SPDX-License-Identifier: MIT
// Keys the rig description may use, object by object: any other key is most
// likely a misspelt option, which would otherwise be ignored in silence.
#include "description_reader.h"

namespace posemorph::bake::description {

namespace {

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

}  // namespace

void WarnUnknownKeys(const json& root, const std::string& file, std::vector<std::string>* warnings) {
  WarnUnknownKeys(root, "",
                  {"posemorph", "name", "filter", "anchor", "facing", "poses", "triangles", "parts", "glue", "mapping",
                   "bake", "paths", "channels", "state_machine", "import", "atlas"},
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
                     "align_rigidity", "drop_shadows", "working_size", "map_again", "retry_seconds"},
                    file, warnings);
  if (root.contains("bake"))
    WarnUnknownKeys(
        root["bake"], "bake",
        {"grid_resolution", "margin", "epsilon", "sigma", "precision", "max_error", "pixels_per_unit", "allow_folds"},
        file, warnings);
  if (root.contains("state_machine") && root["state_machine"].is_object()) {
    const json& m = root["state_machine"];
    WarnUnknownKeys(m, "state_machine", {"inputs", "layers"}, file, warnings);
    if (m.contains("inputs") && m["inputs"].is_array())
      for (std::size_t i = 0; i < m["inputs"].size(); ++i)
        WarnUnknownKeys(m["inputs"][i], "state_machine.inputs[" + std::to_string(i) + "]", {"name", "type", "default"},
                        file, warnings);
    if (m.contains("layers") && m["layers"].is_array())
      for (std::size_t l = 0; l < m["layers"].size(); ++l) {
        const json& layer = m["layers"][l];
        const std::string w = "state_machine.layers[" + std::to_string(l) + "]";
        WarnUnknownKeys(layer, w, {"channel", "initial", "states", "transitions", "behaviours"}, file, warnings);
        if (layer.is_object() && layer.contains("behaviours") && layer["behaviours"].is_object()) {
          const json& b = layer["behaviours"];
          const std::string wb = w + ".behaviours";
          if (b.contains("blink"))
            WarnUnknownKeys(b["blink"], wb + ".blink", {"pose", "interval", "jitter", "duration", "strength", "seed"},
                            file, warnings);
          if (b.contains("breath")) WarnUnknownKeys(b["breath"], wb + ".breath", {"period", "offset"}, file, warnings);
          if (b.contains("look_at"))
            WarnUnknownKeys(b["look_at"], wb + ".look_at", {"target", "smoothing", "strength"}, file, warnings);
          if (b.contains("spring"))
            WarnUnknownKeys(b["spring"], wb + ".spring", {"frequency", "damping", "strength"}, file, warnings);
        }
        if (!layer.is_object()) continue;
        if (layer.contains("states") && layer["states"].is_array())
          for (std::size_t i = 0; i < layer["states"].size(); ++i)
            WarnUnknownKeys(
                layer["states"][i], w + ".states[" + std::to_string(i) + "]",
                {"name", "play", "loop", "speed", "pad", "blend", "by", "stop", "colour", "opacity", "parts"}, file,
                warnings);
        if (layer.contains("transitions") && layer["transitions"].is_array())
          for (std::size_t i = 0; i < layer["transitions"].size(); ++i)
            WarnUnknownKeys(layer["transitions"][i], w + ".transitions[" + std::to_string(i) + "]",
                            {"from", "to", "when", "mix", "exit_time"}, file, warnings);
      }
  }
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
                          {"name", "loop", "interpolation", "keys", "events"}, file, warnings);
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
      WarnUnknownKeys(root["paths"][i], "paths[" + std::to_string(i) + "]",
                      {"name", "loop", "interpolation", "keys", "events"}, file, warnings);
}

}  // namespace posemorph::bake::description
