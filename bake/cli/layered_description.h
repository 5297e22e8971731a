// SPDX-License-Identifier: MIT
// The layered description `posemorph-bake init` writes (layered_description.cpp):
// parts, their order and glue found from where the drawings overlap, per
// control channel; and the number and string forms init writes with.
#pragma once
#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace posemorph::bake::cli {

// A JSON string literal, escaped by nlohmann-json.
std::string Quoted(const std::string& s);
// A pose-space coordinate, short and exact enough: 4 decimals, no "-0".
std::string Coordinate(double v);
// Pose k of n on the pad: pose 0 at the centre, the others on the unit
// circle, clockwise from the top (four others: up, right, down, left).
std::array<double, 2> PadPoint(std::size_t k, std::size_t n);

// A layered character's drawings for the description: per channel (the
// first drives the body; a rig without channels has one, unnamed), its
// poses and parts and each part's drawing in each pose.
struct ChannelDrawings {
  std::string name;  // "": a rig without channels
  std::vector<std::string> poses, parts;
  std::vector<std::vector<std::string>> path, reference;  // [pose][part]: to read, and as the description names it
  // One SVG drawing per pose whose top-level groups are the parts, each
  // named like its part (the bake's default `layer`); false: a drawing per part.
  bool svg_layers = false;
};

// The layered description: the first channel's parts back to front by size
// (the largest part, the root of the glue, behind: a smaller part drawn
// over a larger one is usually in front of it, like eyes on a head), glued
// in the tree of their largest overlaps in the first pose, each joint where
// the two are drawn over each other in every pose, each part's start
// landmark on its outline nearest its joint (the root's: its lowest point).
// A later channel's parts (a face's eyes and mouth) in front of them all,
// each glued to the first channel's part it overlaps most in both
// channels' first poses (which share one canvas), its joint in each of its
// drawings where it is drawn over that part's first drawing.
std::string LayeredDescription(const std::string& name, const std::vector<ChannelDrawings>& channels);

}  // namespace posemorph::bake::cli
