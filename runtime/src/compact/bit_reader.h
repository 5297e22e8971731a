// SPDX-License-Identifier: MIT
// Reading the compact sections' bit streams: fixed-width unsigned integers
// packed least significant bit first, and order-k Exp-Golomb codes (the
// weight grid's prediction residuals). Every read is bounded by the stream's
// size; reading past the end sets `overrun` and yields zeros.
#pragma once
#include <cstdint>
#include <cstring>

namespace posemorph::detail {

// Index of the lowest set bit of a non-zero word.
inline unsigned LowestSetBit(std::uint64_t word) {
#if defined(__GNUC__) || defined(__clang__)
  return unsigned(__builtin_ctzll(word));
#else
  unsigned i = 0;
  while (((word >> i) & 1u) == 0) ++i;
  return i;
#endif
}

class BitReader {
 public:
  BitReader(const unsigned char* data, std::uint64_t bytes) : data_(data), bits_(bytes * 8) {}

  // `width` bits (0..32) at bit position `at`, without moving the cursor.
  std::uint32_t At(std::uint64_t at, unsigned width) const {
    if (width == 0) return 0;
    if (at + width > bits_) return 0;
    return std::uint32_t((Word(at >> 3) >> (at & 7)) & ((std::uint64_t(1) << width) - 1));
  }

  std::uint32_t Read(unsigned width) {
    if (pos_ + width > bits_) {
      overrun = true;
      pos_ = bits_;
      return 0;
    }
    const std::uint32_t v = At(pos_, width);
    pos_ += width;
    return v;
  }

  // Order-k Exp-Golomb: z zero bits, a one, then z + k bits m; the value is
  // 2^(z+k) + m - 2^k. At most max_zeros (<= 56) zeros.
  std::uint64_t ReadGolomb(unsigned k, unsigned max_zeros) {
    // The next up to 57 bits, first in the lowest: the zeros end at the
    // lowest set bit.
    const std::uint64_t word = Word(pos_ >> 3) >> (pos_ & 7);
    const unsigned zeros = LowestSetBit(word | (std::uint64_t(1) << 57));
    if (zeros > max_zeros || pos_ + zeros + 1 > bits_) {
      overrun = true;
      pos_ = bits_;
      return 0;
    }
    const unsigned width = zeros + k;
    if (zeros + 1 + width <= 57 && pos_ + zeros + 1 + width <= bits_) {  // all in the word already read
      const std::uint64_t m = (word >> (zeros + 1)) & ((std::uint64_t(1) << width) - 1);
      pos_ += zeros + 1 + width;
      return (std::uint64_t(1) << width) + m - (std::uint64_t(1) << k);
    }
    pos_ += zeros + 1;
    std::uint64_t m = 0;
    if (width > 32) {
      m = std::uint64_t(Read(width - 32)) << 32;
      m |= Read(32);
    } else {
      m = Read(width);
    }
    return (std::uint64_t(1) << width) + m - (std::uint64_t(1) << k);
  }

  std::uint64_t position() const { return pos_; }
  std::uint64_t size_bits() const { return bits_; }
  bool overrun = false;

 private:
  // The 8 bytes from `byte` (zeros past the end), little-endian; a fixed-size
  // copy (one load) except in the last 8 bytes.
  std::uint64_t Word(std::uint64_t byte) const {
    std::uint64_t word = 0;
    const std::uint64_t size = bits_ / 8;
    if (byte + 8 <= size) {
      std::memcpy(&word, data_ + byte, 8);  // little-endian targets only
    } else if (byte < size) {
      std::memcpy(&word, data_ + byte, std::size_t(size - byte));
    }
    return word;
  }

  const unsigned char* data_;
  std::uint64_t bits_;
  std::uint64_t pos_ = 0;
};

// Bytes a stream of `count` values of `width` bits takes.
inline std::uint64_t PackedBytes(std::uint64_t count, unsigned width) { return (count * width + 7) / 8; }

}  // namespace posemorph::detail
