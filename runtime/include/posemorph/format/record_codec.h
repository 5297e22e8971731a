// SPDX-License-Identifier: MIT
// The rig format's record codec: each fixed-size record (records.h,
// machine_records.h) lists its fields once (Fields), and these walk that
// list to write it (EncodeRecord), read it (DecodeRecord, ReadRecord) and
// size it (EncodedSize), little-endian whatever the host; doubles are
// IEEE-754 binary64. PM_FORMAT_RECORD and PM_FORMAT_FIELD fix a record's
// size and its fields' offsets by static_assert.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace posemorph::format {

// ---- encoding ---------------------------------------------------------------

// Writes each field little-endian, one after another.
struct FieldEncoder {
  unsigned char* at;
  void Put(std::uint64_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) *at++ = static_cast<unsigned char>(v >> (8 * i));
  }
  void operator()(const std::uint8_t& v) { Put(v, 1); }
  void operator()(const std::uint16_t& v) { Put(v, 2); }
  void operator()(const std::uint32_t& v) { Put(v, 4); }
  void operator()(const std::int32_t& v) { Put(static_cast<std::uint32_t>(v), 4); }
  void operator()(const std::uint64_t& v) { Put(v, 8); }
  void operator()(const double& v) {
    std::uint64_t bits;
    std::memcpy(&bits, &v, 8);
    Put(bits, 8);
  }
  template <typename T, std::size_t K>
  void operator()(const T (&values)[K]) {
    for (const T& v : values) (*this)(v);
  }
};

// Reads each field little-endian, one after another.
struct FieldDecoder {
  const unsigned char* at;
  std::uint64_t Get(int bytes) {
    std::uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) v |= std::uint64_t(*at++) << (8 * i);
    return v;
  }
  void operator()(std::uint8_t& v) { v = static_cast<std::uint8_t>(Get(1)); }
  void operator()(std::uint16_t& v) { v = static_cast<std::uint16_t>(Get(2)); }
  void operator()(std::uint32_t& v) { v = static_cast<std::uint32_t>(Get(4)); }
  void operator()(std::int32_t& v) { v = static_cast<std::int32_t>(static_cast<std::uint32_t>(Get(4))); }
  void operator()(std::uint64_t& v) { v = Get(8); }
  void operator()(double& v) {
    const std::uint64_t bits = Get(8);
    std::memcpy(&v, &bits, 8);
  }
  template <typename T, std::size_t K>
  void operator()(T (&values)[K]) {
    for (T& v : values) (*this)(v);
  }
};

// Counts the bytes the fields take in the file (compile time).
struct FieldSizer {
  std::size_t size = 0;
  template <typename T>
  constexpr void operator()(const T&) {
    size += sizeof(T);
  }
};

template <typename R>
constexpr std::size_t EncodedSize() {
  R r{};
  FieldSizer s;
  R::Fields(r, s);
  return s.size;
}

// The record's kSize bytes at `out`.
template <typename R>
void EncodeRecord(const R& r, unsigned char* out) {
  FieldEncoder e{out};
  R::Fields(r, e);
}

// The record at `in` (kSize readable bytes).
template <typename R>
R DecodeRecord(const unsigned char* in) {
  R r{};
  FieldDecoder d{in};
  R::Fields(r, d);
  return r;
}

// The record at `offset` of `size` bytes at `data`; false, writing nothing,
// when it does not lie wholly inside them.
template <typename R>
bool ReadRecord(const unsigned char* data, std::uint64_t size, std::uint64_t offset, R* out) {
  if (offset > size || size - offset < R::kSize) return false;
  *out = DecodeRecord<R>(data + offset);
  return true;
}

// Record i of a table of records starting at `data` (bounds checked by the caller).
template <typename R>
R DecodeEntry(const unsigned char* data, std::uint64_t i) {
  return DecodeRecord<R>(data + i * R::kSize);
}

}  // namespace posemorph::format

// Each record's size, field list and C++ layout agree: the fields are
// listed in declaration order with no padding, at these offsets.
#define PM_FORMAT_RECORD(R)                                                         \
  static_assert(sizeof(R) == R::kSize, #R ": the struct is not its record's size"); \
  static_assert(EncodedSize<R>() == R::kSize, #R ": the field list is not the record's size")
#define PM_FORMAT_FIELD(R, field, at) static_assert(offsetof(R, field) == (at), #R "::" #field " is not at byte " #at)
