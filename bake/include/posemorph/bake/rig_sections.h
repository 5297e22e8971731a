// SPDX-License-Identifier: MIT
// A rig file's sections in memory, in file order: what the bake's steps hand
// each other (SerialiseRig writes the exact sections, CompactRig re-encodes
// them, BakeCharacter adds CHAN to the body's), until WriteRig lays them out
// once as a file (runtime/FORMAT.md: header, section table, each section
// aligned, the checksum). The bake never reads its own bytes back to get
// them.
#pragma once
#include <cstdint>
#include <cstring>
#include <vector>

namespace posemorph::bake {

struct RigSections {
  struct Section {
    std::uint32_t tag = 0;  // format::kMeta, format::kTriangles, ... (posemorph/rig_format.h)
    std::vector<unsigned char> bytes;
  };
  std::vector<Section> sections;

  void Add(std::uint32_t tag, std::vector<unsigned char> bytes) { sections.push_back({tag, std::move(bytes)}); }
  // A section of fixed-size little-endian values, as the host holds them (every target is little-endian).
  template <typename T>
  void AddArray(std::uint32_t tag, const std::vector<T>& values) {
    std::vector<unsigned char> bytes(values.size() * sizeof(T));
    if (!values.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
    Add(tag, std::move(bytes));
  }
  // The first section with this tag; nullptr when there is none.
  const std::vector<unsigned char>* Find(std::uint32_t tag) const {
    for (const Section& s : sections)
      if (s.tag == tag) return &s.bytes;
    return nullptr;
  }
};

// The file's bytes: the one place the bake writes a rig's layout.
std::vector<unsigned char> WriteRig(const RigSections& rig);
// The size WriteRig's bytes will have, without writing them.
std::uint64_t RigFileSize(const RigSections& rig);

}  // namespace posemorph::bake
