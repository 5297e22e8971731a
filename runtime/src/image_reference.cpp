// SPDX-License-Identifier: MIT
#include "posemorph/image_reference.h"

namespace posemorph {

bool ImageReferenceStaysInside(StringView reference) {
  const char* s = reference.data;
  const std::size_t n = reference.size;
  if (n == 0 || !s || s[0] == '/') return false;
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c < 0x20 || c == 0x7F || c == '\\' || c == ':') return false;
  }
  // Components between '/': none may be "..".
  std::size_t start = 0;
  while (start <= n) {
    std::size_t end = start;
    while (end < n && s[end] != '/') ++end;
    if (end - start == 2 && s[start] == '.' && s[start + 1] == '.') return false;
    start = end + 1;
  }
  return true;
}

}  // namespace posemorph
