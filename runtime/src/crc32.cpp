// SPDX-License-Identifier: MIT
// CRC-32 (IEEE 802.3, reflected, polynomial 0xEDB88320), as in PNG and zip.
// It detects every burst error of up to 32 bits, so every single-byte change.
// Eight bytes per step ("slicing by 8"): table[k][b] is the CRC register
// contribution of byte b followed by k zero bytes, so the eight lookups of a
// step are independent of each other.
#include <array>
#include <cstring>

#include "posemorph/rig_format.h"

namespace posemorph::format {
namespace {

using Tables = std::array<std::array<std::uint32_t, 256>, 8>;

constexpr Tables MakeTables() {
  Tables t{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    t[0][i] = c;
  }
  for (int k = 1; k < 8; ++k)
    for (std::uint32_t i = 0; i < 256; ++i) t[k][i] = (t[k - 1][i] >> 8) ^ t[0][t[k - 1][i] & 0xFFu];
  return t;
}
constexpr Tables kTables = MakeTables();

}  // namespace

std::uint32_t Crc32(const unsigned char* data, std::uint64_t size, std::uint32_t crc) {
  crc = ~crc;
  std::uint64_t i = 0;
  for (; i + 8 <= size; i += 8) {
    std::uint32_t lo, hi;  // little-endian, as the loader requires
    std::memcpy(&lo, data + i, 4);
    std::memcpy(&hi, data + i + 4, 4);
    lo ^= crc;
    crc = kTables[7][lo & 0xFFu] ^ kTables[6][(lo >> 8) & 0xFFu] ^ kTables[5][(lo >> 16) & 0xFFu] ^
          kTables[4][lo >> 24] ^ kTables[3][hi & 0xFFu] ^ kTables[2][(hi >> 8) & 0xFFu] ^
          kTables[1][(hi >> 16) & 0xFFu] ^ kTables[0][hi >> 24];
  }
  for (; i < size; ++i) crc = kTables[0][(crc ^ data[i]) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}

}  // namespace posemorph::format
