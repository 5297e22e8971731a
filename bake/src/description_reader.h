// SPDX-License-Identifier: MIT
// The rig description reader's parts (rig_description.cpp and the
// description_*.cpp files, one object of the schema each): the Reader that
// names the file and the JSON path in every message, and the parsers they
// share.
#pragma once
#include <array>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "posemorph/bake/error.h"
#include "posemorph/bake/rig_description.h"

namespace posemorph::bake::description {

constexpr double kMaxCoordinate = 1e9;

using json = nlohmann::json;

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

// A rig description or mesh file's text, read within the limits.
std::string ReadText(const std::string& path, const std::string& referenced_from);

// Warnings for keys the schema does not have (description_keys.cpp).
void WarnUnknownKeys(const json& root, const std::string& file, std::vector<std::string>* warnings);

// Poses (description_poses.cpp): one entry of "poses", or of a part's
// "poses" (rig_pose: the rig's pose it belongs to); which poses are drawn
// decides where the triangles come from (`w`: the object that holds them,
// "" for the rig); with "parts", the rig's poses give a name and a point.
PoseDescription ParsePose(const Reader& r, const json& jp, std::size_t i, const std::string& file,
                          const std::string& base_dir, std::vector<std::array<std::uint32_t, 3>>* triangles,
                          bool* have_triangles, const PoseDescription* rig_pose = nullptr, std::string w = "");
void CheckPoseKinds(const Reader& r, const std::vector<PoseDescription>& poses, bool have_triangles,
                    const std::string& w = "");
std::vector<PoseDescription> ParseLayeredPoses(const Reader& r, const json& poses, const std::string& prefix = "");

// "parts" and "glue" (description_parts.cpp).
std::vector<PartDescription> ParseParts(const Reader& r, const json& parts,
                                        const std::vector<ChannelDescription>& channels, const std::string& file,
                                        const std::string& base_dir);
std::vector<GlueDescription> ParseGlue(const Reader& r, const json& glue, const std::vector<PartDescription>& parts,
                                       const std::vector<ChannelDescription>& channels);

// "mapping", "bake" and one entry of "paths" (description_parameters.cpp).
void ParseMapping(const Reader& r, const json& m, MappingParameters* parameters);
void ParseBakeParameters(const Reader& r, const json& b, BakeParameters* parameters);
PathDescription ParsePath(const Reader& r, const json& jp, std::size_t i, const std::vector<PathDescription>& earlier,
                          const std::string& prefix = "");

// "state_machine" (description_state_machine.cpp), read after the poses,
// channels and paths it names.
StateMachineDescription ParseStateMachine(const Reader& r, const json& j, const RigDescription& rig);

}  // namespace posemorph::bake::description
