// SPDX-License-Identifier: MIT
// Numbers from a command line: one parser, so that posemorph-bake and
// posemorph-view accept and refuse the same text. Nothing here throws.
#pragma once
#include <optional>
#include <string>
#include <vector>

namespace posemorph::bake {

// A finite number and nothing else: "2", "-0.5", "1e-3"; not "", " 1", "1x",
// "0x10", "inf" or "nan". Independent of the C locale's decimal point.
std::optional<double> ParseNumber(const std::string& text);

// ParseNumber's number when it is whole and within [lo, hi] ("3", "3.0", "1e2").
std::optional<long long> ParseWholeNumber(const std::string& text, long long lo, long long hi);

// Numbers separated by `separator` ("0.4,0.6" -> {0.4, 0.6}; "640x480" with
// 'x'), each as ParseNumber reads it; nullopt if any is not a number.
std::optional<std::vector<double>> ParseNumbers(const std::string& text, char separator);

}  // namespace posemorph::bake
