// CRC-32 (IEEE 802.3, reflected, polynomial 0xEDB88320), as in PNG and zip.
// It detects every burst error of up to 32 bits, so every single-byte change.
#include <array>

#include "posemorph/rig_format.h"

namespace posemorph::format {
namespace {

constexpr std::array<std::uint32_t, 256> MakeTable() {
  std::array<std::uint32_t, 256> table{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    table[i] = c;
  }
  return table;
}
constexpr std::array<std::uint32_t, 256> kTable = MakeTable();

}  // namespace

std::uint32_t Crc32(const unsigned char* data, std::uint64_t size, std::uint32_t crc) {
  crc = ~crc;
  for (std::uint64_t i = 0; i < size; ++i) crc = kTable[(crc ^ data[i]) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}

}  // namespace posemorph::format
