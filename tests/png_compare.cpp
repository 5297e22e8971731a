// SPDX-License-Identifier: MIT
// Compares two PNG frames the way the frame tests do (a pixel differs when
// a channel is off by more than 3 of 255) and fails when more than a share
// of pixels differ. Used where a frame from another renderer (an example)
// is checked against posemorph-view's.
//   posemorph-png-compare A.png B.png MAX-SHARE
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "rig_renderer.h"

int main(int argc, char** argv) {
  if (argc != 4) return std::fprintf(stderr, "usage: posemorph-png-compare A.png B.png MAX-SHARE\n"), 2;
  std::vector<unsigned char> a, b;
  std::uint32_t aw = 0, ah = 0, bw = 0, bh = 0;
  std::string problem;
  if (!posemorph::viewer::ReadPng(argv[1], &a, &aw, &ah, &problem) ||
      !posemorph::viewer::ReadPng(argv[2], &b, &bw, &bh, &problem))
    return std::fprintf(stderr, "posemorph-png-compare: %s\n", problem.c_str()), 1;
  if (aw != bw || ah != bh)
    return std::fprintf(stderr, "posemorph-png-compare: %ux%u against %ux%u\n", aw, ah, bw, bh), 1;
  const posemorph::viewer::FrameDifference d = posemorph::viewer::CompareFrames(a, b);
  const double share = d.share();
  std::printf("%zu of %u pixels (%.3f%%) differ by more than 3, worst %d\n", d.differing, aw * ah, 100 * share,
              d.worst);
  return share <= std::atof(argv[3]) ? 0 : 1;
}
