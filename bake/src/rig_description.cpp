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
#include "description_reader.h"
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

using namespace description;  // NOLINT(google-build-using-namespace): the reader's own parts

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
    for (std::size_t j = 1; j < channel.poses.size(); ++j)
      for (std::size_t i = 0; i < j; ++i)
        if (channel.poses[i].name == channel.poses[j].name)
          r.Fail(w + ".poses[" + std::to_string(j) + "].name",
                 "channel '" + channel.name + "' names two poses '" + channel.poses[j].name + "' (poses " +
                     std::to_string(i) + " and " + std::to_string(j) + "): each pose of a channel has its own name");
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

namespace description {

std::string ReadText(const std::string& path, const std::string& referenced_from) {
  const std::vector<unsigned char> bytes = ReadInputFile(
      path, kMaxTextFileBytes, referenced_from.empty() ? "a rig description" : "a mesh file", referenced_from);
  return std::string(bytes.begin(), bytes.end());
}

}  // namespace description

using description::Reader;

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
  if (root.contains("anchor")) {
    rig.anchor = r.Point(root["anchor"], "anchor");
    if (!(rig.anchor.cwiseAbs().maxCoeff() <= 1e9)) r.Fail("anchor", "expected a point within +-1e9");
    rig.anchor_given = true;
  }
  if (root.contains("facing")) {
    const std::string f = r.String(root["facing"], "facing");
    if (f != "left" && f != "right") r.Fail("facing", "expected \"left\" or \"right\" (the way the drawings face)");
    rig.facing_left = f == "left";
  }
  if (root.contains("atlas")) {
    const json& a = root["atlas"];
    rig.atlas_given = true;
    if (a.is_boolean()) {
      rig.atlas.enabled = a.get<bool>();
    } else if (a.is_object()) {
      for (const auto& [key, value] : a.items()) {
        const std::string where = "atlas." + key;
        if (key != "max_page_size" && key != "padding")
          r.Fail(where, "unknown key (expected \"max_page_size\" or \"padding\")");
        const double v = r.Number(value, where);
        if (key == "max_page_size") {
          if (!(v >= 64 && v <= 16384) || std::floor(std::log2(v)) != std::log2(v))
            r.Fail(where, "expected a power of two from 64 to 16384 pixels");
          rig.atlas.max_page_size = std::uint32_t(v);
        } else {
          if (!(v >= 0 && v <= 64) || std::floor(v) != v) r.Fail(where, "expected a whole number of pixels, 0 to 64");
          rig.atlas.padding = std::uint32_t(v);
        }
      }
    } else {
      r.Fail("atlas", "expected false, true or {\"max_page_size\": 2048, \"padding\": 2}");
    }
  }
  if (root.contains("import")) {
    const json& im = root["import"];
    if (!im.is_object() || !im.contains("files") || !im["files"].is_array() || im["files"].empty())
      r.Fail("import", "expected {\"files\": [LAYERED, ...], \"channels\": bool, \"flatten\": bool}");
    for (std::size_t k = 0; k < im["files"].size(); ++k)
      rig.import.files.push_back(
          (std::filesystem::path(base_dir) / r.String(im["files"][k], "import.files[" + std::to_string(k) + "]"))
              .string());
    for (const char* flag : {"channels", "flatten"})
      if (im.contains(flag)) {
        if (!im[flag].is_boolean()) r.Fail(std::string("import.") + flag, "expected true or false");
        (std::string(flag) == "channels" ? rig.import.channels : rig.import.flatten) = im[flag].get<bool>();
      }
  }
  bool have_triangles = root.contains("triangles");
  if (root.contains("channels")) ParseChannels(r, root, &rig);
  if (root.contains("parts")) {
    if (rig.channels.empty()) rig.channels.push_back({"", ParseLayeredPoses(r, r.Array(root, "poses", "")), {}});
    if (have_triangles) r.Fail("triangles", "with \"parts\", each part has its own triangles; remove it");
    rig.poses = rig.channels[0].poses;
    rig.parts = ParseParts(r, r.Array(root, "parts", ""), rig.channels, file, base_dir);
    for (std::size_t c = 1; c < rig.channels.size(); ++c) {
      bool driven = false;
      for (const PartDescription& part : rig.parts) driven = driven || part.channel == c;
      if (!driven)
        r.Fail("channels[" + std::to_string(c) + "]", "channel '" + rig.channels[c].name +
                                                          "' drives no part: give a part \"channel\": \"" +
                                                          rig.channels[c].name + "\", or remove the channel");
    }
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
  if (root.contains("state_machine")) rig.state_machine = ParseStateMachine(r, root["state_machine"], rig);
  WarnUnknownKeys(root, file, &rig.warnings);
  return rig;
}

RigDescription ReadRigDescription(const std::string& path) {
  const std::string text = ReadText(path, "");
  return ParseRigDescription(text, path, std::filesystem::path(path).parent_path().string());
}

}  // namespace posemorph::bake
