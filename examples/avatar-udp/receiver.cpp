// SPDX-License-Identifier: MIT
// The receiving peer of a networked avatar: it holds the same rig as the
// sender, gets 4 bytes of pose-space point per frame, and draws the
// character from them. It answers each frame with a hash of the vertex
// positions it computed, so the sender can prove both drew the same bits.
//
//   avatar_receiver RIG.pmrig PORT     (listens on 127.0.0.1:PORT; stops on DONE or 5 s of silence)
#include <cstdio>
#include <cstdlib>

#include "wire.h"

int main(int argc, char** argv) {
  if (argc != 3) return std::fprintf(stderr, "usage: avatar_receiver RIG.pmrig PORT\n"), 2;
  posemorph::Rig rig;
  if (!wire::LoadRigFile("avatar_receiver", argv[1], &rig)) return 1;
  const int port = std::atoi(argv[2]);
  const int s = wire::OpenSocket(std::uint16_t(port), 5000);
  if (port <= 0 || port > 65535 || s < 0)
    return std::fprintf(stderr, "avatar_receiver: cannot listen on 127.0.0.1:%s\n", argv[2]), 1;
  wire::Avatar avatar(rig);

  unsigned char m[64], reply[16];
  sockaddr_in from{};
  socklen_t from_size = sizeof from;
  bool agreed = false;
  std::uint32_t frames = 0;
  for (;;) {
    const ssize_t n = recvfrom(s, m, sizeof m, 0, reinterpret_cast<sockaddr*>(&from), &from_size);
    if (n < 0) return std::fprintf(stderr, "avatar_receiver: no message for 5 s, stopping\n"), 1;
    const auto answer = [&](std::size_t bytes) {
      sendto(s, reply, bytes, 0, reinterpret_cast<sockaddr*>(&from), from_size);
    };
    if (wire::Is(m, std::size_t(n), "HELO") && n == 16) {
      // The handshake: the same file (CRC-32), format and mesh, or nothing.
      agreed = wire::Get32(m + 4) == rig.checksum() && wire::Get32(m + 8) == wire::FormatVersion(rig) &&
               wire::Get32(m + 12) == rig.vertex_count();
      std::memcpy(reply, agreed ? "OKAY" : "DIFF", 4);
      answer(4);
      if (!agreed)
        return std::fprintf(stderr, "avatar_receiver: the sender holds another rig (CRC-32 %08x, ours %08x)\n",
                            wire::Get32(m + 4), rig.checksum()),
               1;
    } else if (wire::Is(m, std::size_t(n), "FRAM") && n == wire::kFrameBytes && agreed) {
      const std::uint64_t h = avatar.DrawPacked(m + 8);  // a game would render avatar.job.output[0] now
      std::memcpy(reply, "ACKN", 4);
      std::memcpy(reply + 4, m + 4, 4);  // the sequence number
      wire::Put32(reply + 8, std::uint32_t(h));
      wire::Put32(reply + 12, std::uint32_t(h >> 32));
      answer(16);
      ++frames;
    } else if (wire::Is(m, std::size_t(n), "DONE")) {
      std::fprintf(stderr, "avatar_receiver: drew %u frames\n", frames);
      close(s);
      return 0;
    }  // anything else is ignored: UDP brings what it brings
  }
}
