// SPDX-License-Identifier: MIT
// The JSON of rig descriptions and mesh files, shared by their reader
// (rig_description.cpp) and writer (rig_description_writer.cpp).
#pragma once
#include <string>

#include <nlohmann/json.hpp>

namespace posemorph::bake {

// The parsed text, or BakeError(file, "invalid JSON: ...") with nlohmann's
// explanation.
nlohmann::json ParseDescriptionJson(const std::string& text, const std::string& file);

}  // namespace posemorph::bake
