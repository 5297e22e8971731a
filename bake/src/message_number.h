// SPDX-License-Identifier: MIT
// How the bake's messages about a baked rig write its names and numbers
// (inbetween_check.cpp, mesh_quality.cpp): a rig's string as a std::string,
// a number to three significant digits with tiny values as 0.
#pragma once
#include <cmath>
#include <sstream>
#include <string>

#include "posemorph/rig.h"

namespace posemorph::bake {

inline std::string RigString(StringView s) { return std::string(s.data, s.size); }

inline std::string MessageNumber(double v) {
  std::ostringstream s;
  s.precision(3);
  s << (std::abs(v) < 5e-4 ? 0.0 : v);
  return s.str();
}

}  // namespace posemorph::bake
