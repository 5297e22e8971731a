// SPDX-License-Identifier: MIT
// What a game does with an installed or embedded posemorph: load a rig,
// sample its first path, evaluate one frame, print a hash of the positions
// (scripts/consumer-test.sh checks every way of building gives the same).
#include <cstdio>
#include <vector>

#include "posemorph/jobs.h"
#include "posemorph/path.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s RIG.pmrig\n", argv[0]);
    return 2;
  }
  std::vector<unsigned char> bytes;
  if (std::FILE* f = std::fopen(argv[1], "rb")) {
    for (int c; (c = std::fgetc(f)) != EOF;) bytes.push_back(static_cast<unsigned char>(c));
    std::fclose(f);
  }
  posemorph::Rig rig;
  posemorph::Error err;
  if (!posemorph::LoadRig(bytes.data(), bytes.size(), &rig, &err)) {
    std::fprintf(stderr, "%s: %s\n", argv[1], err.message);
    return 1;
  }
  double px = 0, py = 0;
  if (rig.path_count()) posemorph::SamplePath(rig, 0, 0.5, &px, &py);
  std::vector<double> w(rig.pose_count()), ws(w.size()), work(rig.morph_workspace_size()), x(2 * rig.vertex_count());
  posemorph::WeightsJob weights;
  weights.rig = &rig, weights.x = px, weights.y = py;
  weights.raw = posemorph::MakeSpan(w), weights.limited = posemorph::MakeSpan(ws);
  posemorph::MorphJob morph;
  morph.rig = &rig, morph.weights = posemorph::MakeSpan(w), morph.limited_weights = posemorph::MakeSpan(ws);
  morph.workspace = posemorph::MakeSpan(work), morph.positions = posemorph::MakeSpan(x);
  if (!weights.Run() || !morph.Run()) return 1;
  unsigned long long h = 0xcbf29ce484222325ull;  // FNV-1a 64 over the positions' bytes
  for (double v : x) {
    const unsigned char* p = reinterpret_cast<const unsigned char*>(&v);
    for (unsigned i = 0; i < sizeof v; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
  }
  std::printf("%u vertices, path %s, frame %016llx\n", rig.vertex_count(), posemorph::IsaName(rig.isa()), h);
  return 0;
}
