// SPDX-License-Identifier: MIT
// Saving into the rig description: gestures as paths, edited poses as deformations, written back atomically.
#include "window_impl.h"

namespace posemorph::viewer::window_impl {

// Reads the rig description, lets `change` add to it (returning what it
// added), and writes it back atomically (bake::WriteFileAtomic: a unique
// temporary beside it, then a rename).
void Viewer::ChangeDescription(const char* what, const std::function<std::string(nlohmann::json&)>& change) {
  if (options_.description.empty()) {
    status_ = std::string("start with --description RIG.json to save ") + what;
    return;
  }
  try {
    std::ifstream in(options_.description);
    if (!in) throw std::runtime_error("cannot open " + options_.description);
    nlohmann::json d = nlohmann::json::parse(in);
    const std::string added = change(d);
    const std::string text = d.dump(2) + "\n";
    bake::WriteFileAtomic(options_.description, std::vector<unsigned char>(text.begin(), text.end()));
    status_ = "saved " + added + " into " + options_.description + " (bake again to use it)";
  } catch (const std::exception& e) {
    status_ = std::string("cannot save: ") + e.what();
  }
}

// A name "<stem>-K" that no entry of d[list] has yet.
std::string FreshName(const nlohmann::json& d, const char* list, const std::string& stem, int* counter) {
  std::string name;
  do name = stem + "-" + std::to_string(++*counter);
  while (d.contains(list) && std::any_of(d[list].begin(), d[list].end(),
                                         [&](const nlohmann::json& e) { return e.value("name", "") == name; }));
  return name;
}

void Viewer::SavePose() {
  ChangeDescription("poses", [&](nlohmann::json& d) {
    const std::string name = FreshName(d, "poses", "edit", &edit_.saved);
    const StringView from = rig_.pose_name(std::uint32_t(edit_.pose));
    nlohmann::json handles = nlohmann::json::array();
    for (std::size_t k = 0; k < edit_.handles.size(); ++k)
      handles.push_back({{"vertex", edit_.handles[k]}, {"to", {edit_.targets[k].x(), edit_.targets[k].y()}}});
    d["poses"].push_back({{"name", name},
                          {"point", {scene_.x, scene_.y}},
                          {"deform", {{"from", std::string(from.data, from.size)}, {"handles", handles}}}});
    return "pose \"" + name + "\" at the pad's point";
  });
}

}  // namespace posemorph::viewer::window_impl
