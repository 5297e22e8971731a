// SPDX-License-Identifier: MIT
// What the avatar sender and receiver say to each other over UDP, and the
// few socket calls they share. Every message starts with a 4-byte tag.
//   HELO  sender -> receiver: the rig's CRC-32, format version, vertex count
//   OKAY / DIFF  receiver -> sender: same rig, or not (then both stop)
//   FRAM  sender -> receiver: sequence number + the pose-space point in 4 bytes
//   ACKN  receiver -> sender: sequence number + a 64-bit hash of the vertex
//         positions it drew (so the sender can check they match its own)
//   DONE  sender -> receiver: the end
// Integers are little-endian on the wire, written byte by byte.
#pragma once
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstring>

#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "posemorph/draw_list.h"
#include "posemorph/quantize.h"
#include "posemorph/rig.h"

namespace wire {

constexpr std::size_t kFrameBytes = 4 + 4 + 4;  // tag, sequence, point

inline void Put32(unsigned char* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = (unsigned char)(v >> (8 * i));
}
inline std::uint32_t Get32(const unsigned char* p) {
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
}
inline bool Is(const unsigned char* m, std::size_t n, const char tag[4]) {
  return n >= 4 && std::memcmp(m, tag, 4) == 0;
}

// FNV-1a over the bytes of the positions: equal hashes <=> (practically) equal bits.
inline std::uint64_t Hash(const float* x, std::size_t n) {
  std::uint64_t h = 14695981039346656037ull;
  const unsigned char* b = reinterpret_cast<const unsigned char*>(x);
  for (std::size_t i = 0; i < n * sizeof(float); ++i) h = (h ^ b[i]) * 1099511628211ull;
  return h;
}

// A UDP socket on 127.0.0.1 that gives up waiting after `timeout_ms`.
inline int OpenSocket(std::uint16_t bind_port, int timeout_ms) {
  const int s = socket(AF_INET, SOCK_DGRAM, 0);
  if (s < 0) return -1;
  timeval tv{timeout_ms / 1000, (timeout_ms % 1000) * 1000};
  setsockopt(s, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(bind_port);
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    close(s);
    return -1;
  }
  return s;
}
inline sockaddr_in Loopback(std::uint16_t port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  return a;
}

// One character's frame at a pose-space point, with the buffers it needs (sized from the rig once).
struct Avatar {
  const posemorph::Rig& rig;
  posemorph::CharacterBuffers sizes = posemorph::CharacterBuffers::For(rig, 1);
  std::vector<double> block = std::vector<double>(sizes.bytes / sizeof(double) + 1);
  posemorph::DrawListJob job;
  double point[2] = {0, 0};
  explicit Avatar(const posemorph::Rig& r) : rig(r) {
    sizes.Bind(rig, block.data(), block.size() * sizeof(double), &job);
    job.points = {point, 2};
  }
  // Draws at the point 4 wire bytes stand for; returns the hash of the positions.
  std::uint64_t DrawPacked(const unsigned char bytes[4]) {
    posemorph::DequantizePoint(rig.grid(), posemorph::UnpackPoint(bytes), &point[0], &point[1]);
    job.Run();
    return Hash(job.positions.data, job.positions.size);
  }
};

inline std::uint32_t FormatVersion(const posemorph::Rig& rig) {
  return std::uint32_t(rig.format_major()) << 16 | rig.format_minor();
}

// Loads a rig file; false with a message naming it.
inline bool LoadRigFile(const char* program, const std::string& path, posemorph::Rig* rig) {
  std::ifstream in(path, std::ios::binary);
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  posemorph::Error err;
  if (!in.good() && bytes.empty())
    return std::fprintf(stderr, "%s: %s: cannot read the file\n", program, path.c_str()), false;
  if (!posemorph::LoadRig(bytes.data(), bytes.size(), rig, &err))
    return std::fprintf(stderr, "%s: %s: %s\n", program, path.c_str(), err.message), false;
  return true;
}

}  // namespace wire
