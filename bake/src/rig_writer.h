// SPDX-License-Identifier: MIT
// Serialising sections into the runtime's binary layout (runtime/FORMAT.md).
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

class RigWriter {
 public:
  void Add(std::uint32_t tag, std::vector<unsigned char> bytes) { sections_.push_back({tag, std::move(bytes)}); }
  template <typename T>
  void AddArray(std::uint32_t tag, const std::vector<T>& values) {
    std::vector<unsigned char> bytes(values.size() * sizeof(T));
    if (!values.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
    Add(tag, std::move(bytes));
  }
  std::vector<unsigned char> Finish() const;

 private:
  struct Section {
    std::uint32_t tag;
    std::vector<unsigned char> bytes;
  };
  std::vector<Section> sections_;
};

// Appends a u32 length and the bytes of s.
void AppendString(std::vector<unsigned char>& out, const std::string& s);

}  // namespace posemorph::bake
