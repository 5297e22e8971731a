// SPDX-License-Identifier: MIT
// Serialising records and strings into the runtime's binary layout
// (runtime/FORMAT.md); the file around them is WriteRig (rig_sections.h).
#pragma once
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "posemorph/format/records.h"

namespace posemorph::bake {

// A record's bytes in the file's layout (posemorph/format/records.h).
template <typename R>
std::vector<unsigned char> RecordBytes(const R& record) {
  std::vector<unsigned char> out(R::kSize);
  format::EncodeRecord(record, out.data());
  return out;
}

// Appends a record's bytes.
template <typename R>
void AppendRecord(std::vector<unsigned char>& out, const R& record) {
  const std::size_t at = out.size();
  out.resize(at + R::kSize);
  format::EncodeRecord(record, out.data() + at);
}

// Appends a u32 length and the bytes of s.
void AppendString(std::vector<unsigned char>& out, const std::string& s);

}  // namespace posemorph::bake
