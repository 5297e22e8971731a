// SPDX-License-Identifier: MIT
// The native runtime's answer for one character at a point: the FNV-1a
// 64-bit hash of its draw list's float positions (default options), as the
// web example's page computes it, so a test can compare them bit for bit.
//   posemorph-positions-hash RIG.pmrig X Y
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <vector>

#include "posemorph/posemorph.h"

int main(int argc, char** argv) {
  if (argc != 4) return std::fprintf(stderr, "usage: posemorph-positions-hash RIG.pmrig X Y\n"), 2;
  std::ifstream in(argv[1], std::ios::binary);
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  pm_rig* rig = nullptr;
  pm_error err;
  if (pm_rig_load(bytes.data(), bytes.size(), &rig, &err) != PM_OK)
    return std::fprintf(stderr, "posemorph-positions-hash: %s: %s\n", argv[1], err.message), 1;
  std::size_t work_size = 0, position_size = 0;
  pm_draw_list_buffers(rig, 1, &work_size, &position_size);
  std::vector<double> work(work_size);
  std::vector<float> positions(position_size);
  const double point[2] = {std::atof(argv[2]), std::atof(argv[3])};
  pm_draw_list list;
  if (pm_draw_lists(rig, nullptr, 1, point, nullptr, work.data(), work.size(), positions.data(), positions.size(),
                    &list, 1) != PM_OK)
    return std::fprintf(stderr, "posemorph-positions-hash: evaluation failed\n"), 1;
  std::uint64_t h = 14695981039346656037ull;
  const auto* b = reinterpret_cast<const unsigned char*>(positions.data());
  for (std::size_t i = 0; i < positions.size() * sizeof(float); ++i) h = (h ^ b[i]) * 1099511628211ull;
  std::printf("positions-fnv1a64=%016" PRIx64 "\n", h);
  pm_rig_free(rig);
  return 0;
}
