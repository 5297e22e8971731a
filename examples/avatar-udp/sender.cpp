// SPDX-License-Identifier: MIT
// The sending peer of a networked avatar: it plays one of the rig's paths
// and sends each frame's pose-space point in 4 bytes (plus a sequence
// number). It draws its own character from the *dequantised* point, exactly
// what the receiver gets, so both peers draw the same frame; the receiver's
// answer carries a hash of its vertex positions, which must equal ours.
//
//   avatar_sender RIG.pmrig PORT [PATH] [FRAMES]   (sends to 127.0.0.1:PORT)
// Exit status 0 only when the handshake agreed and every frame matched bit for bit.
#include <cstdio>
#include <cstdlib>

#include "posemorph/path.h"
#include "wire.h"

namespace {

// Sends `m` until an answer starting with one of the tags comes (UDP may drop either way).
ssize_t Ask(int s, const sockaddr_in& to, const unsigned char* m, std::size_t n, unsigned char* answer,
            std::size_t capacity, const char* tag1, const char* tag2 = nullptr) {
  for (int attempt = 0; attempt < 20; ++attempt) {
    sendto(s, m, n, 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
    for (;;) {
      const ssize_t got = recv(s, answer, capacity, 0);
      if (got < 0) break;  // timed out: send again
      if (wire::Is(answer, std::size_t(got), tag1) || (tag2 && wire::Is(answer, std::size_t(got), tag2))) return got;
    }
  }
  return -1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3 || argc > 5) return std::fprintf(stderr, "usage: avatar_sender RIG.pmrig PORT [PATH] [FRAMES]\n"), 2;
  posemorph::Rig rig;
  if (!wire::LoadRigFile("avatar_sender", argv[1], &rig)) return 1;
  const int port = std::atoi(argv[2]);
  const int frames = argc > 4 ? std::atoi(argv[4]) : 120;
  const int path = argc > 3 ? rig.FindPath(argv[3]) : (rig.path_count() > 0 ? 0 : -1);
  if (port <= 0 || port > 65535 || frames < 1 || frames > 100000)
    return std::fprintf(stderr, "avatar_sender: PORT wants 1..65535 and FRAMES 1..100000\n"), 2;
  if (path < 0) return std::fprintf(stderr, "avatar_sender: %s: no such path\n", argc > 3 ? argv[3] : "(any)"), 1;
  const int s = wire::OpenSocket(0, 100);  // any local port; answers within 100 ms or we send again
  if (s < 0) return std::fprintf(stderr, "avatar_sender: cannot open a UDP socket\n"), 1;
  const sockaddr_in to = wire::Loopback(std::uint16_t(port));

  // Handshake: the receiver must hold the very same rig.
  unsigned char m[16], answer[64];
  std::memcpy(m, "HELO", 4);
  wire::Put32(m + 4, rig.checksum());
  wire::Put32(m + 8, wire::FormatVersion(rig));
  wire::Put32(m + 12, rig.vertex_count());
  const ssize_t hello = Ask(s, to, m, 16, answer, sizeof answer, "OKAY", "DIFF");
  if (hello < 0) return std::fprintf(stderr, "avatar_sender: no receiver answers on 127.0.0.1:%d\n", port), 1;
  if (wire::Is(answer, std::size_t(hello), "DIFF"))
    return std::fprintf(stderr, "avatar_sender: the receiver holds another rig (ours: CRC-32 %08x)\n", rig.checksum()),
           1;

  wire::Avatar avatar(rig);
  const posemorph::PathView p = rig.path(std::uint32_t(path));
  const double t0 = p.start_time(), t1 = p.end_time();
  int matched = 0;
  for (int f = 0; f < frames; ++f) {
    double x = 0, y = 0;
    posemorph::SamplePath(p, t0 + (t1 - t0) * f / frames, &x, &y);
    std::memcpy(m, "FRAM", 4);
    wire::Put32(m + 4, std::uint32_t(f));
    posemorph::PackPoint(posemorph::QuantizePoint(rig.grid(), x, y), m + 8);  // the 4 bytes an avatar costs
    const std::uint64_t ours = avatar.DrawPacked(m + 8);
    ssize_t got = -1;
    do got = Ask(s, to, m, wire::kFrameBytes, answer, sizeof answer, "ACKN");
    while (got == 16 && wire::Get32(answer + 4) != std::uint32_t(f));  // a late answer to an earlier frame
    if (got != 16) return std::fprintf(stderr, "avatar_sender: frame %d: the receiver stopped answering\n", f), 1;
    const std::uint64_t theirs = wire::Get32(answer + 8) | std::uint64_t(wire::Get32(answer + 12)) << 32;
    if (theirs != ours)
      std::fprintf(stderr, "avatar_sender: frame %d: the receiver drew other vertices (hash %016llx, ours %016llx)\n",
                   f, (unsigned long long)theirs, (unsigned long long)ours);
    else
      ++matched;
  }
  std::memcpy(m, "DONE", 4);
  sendto(s, m, 4, 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
  close(s);
  std::printf(
      "avatar_sender: %d of %d frames drawn bit for bit alike by both peers; %zu bytes per frame "
      "(4 point + 4 sequence + 4 tag), %zu with UDP and IPv4 headers\n",
      matched, frames, wire::kFrameBytes, wire::kFrameBytes + 8 + 20);
  return matched == frames ? 0 : 1;
}
