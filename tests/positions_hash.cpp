// SPDX-License-Identifier: MIT
// The native runtime's answer for one character at a point: the FNV-1a
// 64-bit hash of its draw list's float positions (default options), as the
// web example's page computes it, so a test can compare them bit for bit.
//   posemorph-positions-hash RIG.pmrig X Y
// And for a crowd of whole characters, as the bindings compute it
// (integrations/README.md, "The character digest"):
//   posemorph-positions-hash RIG.pmrig --characters K
// A rig that does not load: its file and the loader's message on stderr,
// exit 1 (the bindings' tests compare their errors with it).
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include "posemorph/posemorph.h"

namespace {

struct Fnv {
  std::uint64_t h = 14695981039346656037ull;
  void Bytes(const void* p, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  }
  void U32(std::uint32_t v) {
    const unsigned char b[4] = {static_cast<unsigned char>(v), static_cast<unsigned char>(v >> 8),
                                static_cast<unsigned char>(v >> 16), static_cast<unsigned char>(v >> 24)};
    Bytes(b, 4);
  }
  void F32(float f) {
    std::uint32_t v;
    std::memcpy(&v, &f, 4);
    U32(v);
  }
};

// The character digest: K characters, character k's body at path 0 at
// 0.37 k s (pose k mod N's point without paths), channel c >= 1 at its path
// 0 at 0.23 k c s (its first pose's point without paths); default draw
// options, no transforms. FNV-1a 64 over the body positions (floats), the
// attachments' positions (floats), then per character and list (body,
// attachments in order) its drawing count and each drawing's pose and
// weight, then its draw steps (list, part); every value 4 bytes little-endian.
int CharacterDigest(const pm_rig* rig, std::size_t count) {
  pm_rig_info info;
  pm_rig_get_info(rig, &info);
  const std::uint32_t channels = pm_rig_channel_count(rig);
  std::vector<double> points(2 * count), channel_points(2 * count * (channels - 1));
  for (std::size_t k = 0; k < count; ++k) {
    if (info.path_count)
      pm_path_sample(rig, 0, 0.37 * double(k), &points[2 * k], &points[2 * k + 1]);
    else
      pm_rig_pose_point(rig, std::uint32_t(k % info.pose_count), &points[2 * k], &points[2 * k + 1]);
    for (std::uint32_t c = 1; c < channels; ++c) {
      double* p = &channel_points[2 * (k * (channels - 1) + (c - 1))];
      if (pm_channel_path_count(rig, c)) {
        pm_channel_path_sample(rig, c, 0, 0.23 * double(k) * c, &p[0], &p[1]);
      } else {
        std::uint32_t n = 0;
        pm_rig_channel_poses(rig, c, &n, nullptr, 0);
        std::vector<double> all(2 * std::size_t(n));
        pm_rig_channel_poses(rig, c, &n, all.data(), all.size());
        p[0] = all[0], p[1] = all[1];
      }
    }
  }
  pm_character_buffer_sizes sizes;
  if (pm_character_buffers(rig, count, &sizes) != PM_OK) return std::fprintf(stderr, "no buffers\n"), 1;
  std::vector<double> work(sizes.workspace_doubles);
  std::vector<float> positions(sizes.position_floats), attached_positions(sizes.attached_position_floats);
  std::vector<pm_draw_list> lists(count), attached(sizes.attached_lists);
  pm_character_inputs in{};
  in.points = points.data();
  in.channel_points = channels > 1 ? channel_points.data() : nullptr;
  if (pm_character_draw_lists(rig, nullptr, count, &in, work.data(), work.size(), positions.data(), positions.size(),
                              attached_positions.data(), attached_positions.size(), lists.data(), lists.size(),
                              attached.data(), attached.size()) != PM_OK)
    return std::fprintf(stderr, "posemorph-positions-hash: evaluation failed\n"), 1;
  Fnv f;
  for (float v : positions) f.F32(v);
  for (float v : attached_positions) f.F32(v);
  const std::uint32_t A = pm_rig_attachment_count(rig);
  std::uint32_t total_steps = 0;
  for (std::size_t k = 0; k < count; ++k) {
    for (std::uint32_t l = 0; l <= A; ++l) {
      const pm_draw_list& d = l == 0 ? lists[k] : attached[k * A + l - 1];
      f.U32(d.drawing_count);
      for (std::uint32_t i = 0; i < d.drawing_count; ++i) f.U32(d.drawings[i].pose), f.F32(d.drawings[i].weight);
    }
    pm_draw_step steps[1 + 64 + 64];
    const std::uint32_t n = pm_character_draw_steps(rig, &lists[k], A ? &attached[k * A] : nullptr, steps, 129);
    for (std::uint32_t s = 0; s < n && s < 129; ++s) f.U32(steps[s].list), f.U32(steps[s].part);
    total_steps += n;
  }
  std::printf("character-fnv1a64=%016" PRIx64 " characters=%zu steps=%u\n", f.h, count, total_steps);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4)
    return std::fprintf(stderr, "usage: posemorph-positions-hash RIG.pmrig X Y | RIG.pmrig --characters K\n"), 2;
  std::ifstream in(argv[1], std::ios::binary);
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  pm_rig* rig = nullptr;
  pm_error err;
  if (pm_rig_load(bytes.data(), bytes.size(), &rig, &err) != PM_OK)
    return std::fprintf(stderr, "%s: %s\n", argv[1], err.message), 1;
  if (std::strcmp(argv[2], "--characters") == 0) {
    const long count = std::atol(argv[3]);
    const int status = count > 0 && count <= 4096 ? CharacterDigest(rig, std::size_t(count)) : 2;
    pm_rig_free(rig);
    return status;
  }
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
