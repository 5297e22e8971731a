// SPDX-License-Identifier: MIT
// The rig description's "parts" and "glue".
#include "description_reader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "posemorph/rig_format.h"

namespace posemorph::bake::description {

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

}  // namespace posemorph::bake::description
