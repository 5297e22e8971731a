// SPDX-License-Identifier: MIT
#include "posemorph/bake/command_line.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

namespace posemorph::bake {

std::optional<double> ParseNumber(const std::string& text) {
  // Digits, one point, an exponent: what a person types. Checked first, so
  // that strtod's extras (hexadecimal, "inf", leading spaces) are refused.
  std::size_t i = 0;
  const std::size_t n = text.size();
  if (i < n && (text[i] == '+' || text[i] == '-')) ++i;
  std::size_t digits = 0;
  while (i < n && std::isdigit(static_cast<unsigned char>(text[i]))) ++i, ++digits;
  if (i < n && text[i] == '.') {
    ++i;
    while (i < n && std::isdigit(static_cast<unsigned char>(text[i]))) ++i, ++digits;
  }
  if (digits == 0) return std::nullopt;
  if (i < n && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < n && (text[i] == '+' || text[i] == '-')) ++i;
    std::size_t exponent_digits = 0;
    while (i < n && std::isdigit(static_cast<unsigned char>(text[i]))) ++i, ++exponent_digits;
    if (exponent_digits == 0) return std::nullopt;
  }
  if (i != n) return std::nullopt;
  // from_chars: a decimal point whatever the locale says; out of range fails.
  const char* first = text.data() + (text[0] == '+' ? 1 : 0);
  double v = 0;
  const auto [end, error] = std::from_chars(first, text.data() + n, v);
  if (error != std::errc() || end != text.data() + n || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::optional<long long> ParseWholeNumber(const std::string& text, long long lo, long long hi) {
  const std::optional<double> v = ParseNumber(text);
  if (!v || *v != std::floor(*v) || *v < double(lo) || *v > double(hi)) return std::nullopt;
  return static_cast<long long>(*v);
}

std::optional<std::vector<double>> ParseNumbers(const std::string& text, char separator) {
  std::vector<double> out;
  std::size_t at = 0;
  for (;;) {
    const std::size_t end = std::min(text.find(separator, at), text.size());
    const std::optional<double> v = ParseNumber(text.substr(at, end - at));
    if (!v) return std::nullopt;
    out.push_back(*v);
    if (end == text.size()) return out;
    at = end + 1;
  }
}

}  // namespace posemorph::bake
