// SPDX-License-Identifier: MIT
// libFuzzer harness: the rig loader, then frames. The header's file size and
// CRC-32 are rewritten after every mutation so mutated bytes reach the
// section parsers and the compact decoder instead of stopping at the
// checksum. A rig that loads must give finite weights, positions and uvs at
// every pose point and at points far outside the pose space; anything else
// aborts (a finding).
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "posemorph/jobs.h"
#include "posemorph/rig.h"
#include "posemorph/rig_format.h"

namespace {

using namespace posemorph;

void RequireFinite(const double* v, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) std::abort();
}

void Frame(const Rig& rig, double x, double y, std::vector<double>& raw, std::vector<double>& limited,
           std::vector<double>& texture, std::vector<double>& work, std::vector<double>& positions) {
  WeightsJob weights;
  weights.rig = &rig;
  weights.x = x, weights.y = y;
  weights.raw = MakeSpan(raw), weights.limited = MakeSpan(limited), weights.texture = MakeSpan(texture);
  if (!weights.Run()) std::abort();  // a loaded rig and right-sized spans: Run may not fail
  RequireFinite(raw.data(), raw.size());
  RequireFinite(limited.data(), limited.size());
  RequireFinite(texture.data(), texture.size());
  MorphJob morph;
  morph.rig = &rig;
  morph.weights = MakeSpan(raw), morph.limited_weights = MakeSpan(limited);
  morph.workspace = MakeSpan(work), morph.positions = MakeSpan(positions);
  if (!morph.Run()) std::abort();
  RequireFinite(positions.data(), positions.size());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<unsigned char> bytes(data, data + size);
  if (bytes.size() >= format::kHeaderSize) {
    const std::uint64_t file_size = bytes.size();
    std::memcpy(bytes.data() + format::kOffFileSize, &file_size, 8);
    const std::uint32_t crc = format::Crc32(bytes.data() + format::kHeaderSize, bytes.size() - format::kHeaderSize);
    std::memcpy(bytes.data() + format::kOffChecksum, &crc, 4);
  }
  Rig rig;
  Error err;
  if (!LoadRig(bytes.data(), bytes.size(), &rig, &err)) {
    if (err.message[0] == 0) std::abort();  // every refusal says why
    return 0;
  }
  const std::size_t n = rig.pose_count();
  std::vector<double> raw(n), limited(n), texture(n), work(rig.morph_workspace_size()),
      positions(2 * std::size_t(rig.vertex_count()));
  const double far[][2] = {{0, 0}, {0.5, 0.5}, {-3, 2}, {1e6, -1e6}, {1e300, 1e300}};
  for (const auto& p : far) Frame(rig, p[0], p[1], raw, limited, texture, work, positions);
  for (std::uint32_t i = 0; i < n; ++i) {
    const auto point = rig.pose_points();
    Frame(rig, point.data[2 * i], point.data[2 * i + 1], raw, limited, texture, work, positions);
  }
  for (std::uint32_t i = 0; i < n; ++i) {  // empty when the rig has none
    const auto uv = rig.uvs(i);
    for (std::size_t k = 0; k < uv.size; ++k)
      if (!std::isfinite(uv.data[k])) std::abort();
  }
  return 0;
}
