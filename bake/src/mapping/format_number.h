// SPDX-License-Identifier: MIT
// How the mapping's messages write a number: four significant digits.
#pragma once
#include <sstream>
#include <string>

namespace posemorph::bake::mapping {

inline std::string Format(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}

}  // namespace posemorph::bake::mapping
