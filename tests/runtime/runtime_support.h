// SPDX-License-Identifier: MIT
// Helpers for tests that need the runtime alone (no bake, no Eigen), so they
// build for every target: aarch64, Windows, WebAssembly. Rigs come from files
// baked by the native build into build/<preset>/rigs/ (POSEMORPH_TEST_RIGS
// overrides the folder, as the cross-target runs in .ci/run do).
#pragma once
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "posemorph/jobs.h"
#include "posemorph/rig.h"
#include "posemorph/rig_format.h"

namespace posemorph::test {

inline std::string TestRigFolder() {
  if (const char* env = std::getenv("POSEMORPH_TEST_RIGS")) return env;
#ifdef POSEMORPH_TEST_RIGS
  return POSEMORPH_TEST_RIGS;
#else
  return "rigs";
#endif
}

inline std::vector<unsigned char> ReadFileBytes(const std::string& path) {
  std::vector<unsigned char> bytes;
  if (std::FILE* f = std::fopen(path.c_str(), "rb")) {
    unsigned char buffer[65536];
    std::size_t n;
    while ((n = std::fread(buffer, 1, sizeof(buffer), f)) > 0) bytes.insert(bytes.end(), buffer, buffer + n);
    std::fclose(f);
  }
  return bytes;
}

// The bytes of a baked test rig (snake, worm-line, gingerbread, pip, sprout, small).
inline std::vector<unsigned char> TestRigBytes(const std::string& name) {
  const std::string path = TestRigFolder() + "/" + name + ".pmrig";
  std::vector<unsigned char> bytes = ReadFileBytes(path);
  REQUIRE_MESSAGE(!bytes.empty(), "cannot read " << path << " (set POSEMORPH_TEST_RIGS)");
  return bytes;
}

// `bytes` with a value written at `offset` and the checksum recomputed, so
// that only the loader's checks stand between the value and the jobs.
template <typename T>
std::vector<unsigned char> WithValue(std::vector<unsigned char> bytes, std::size_t offset, T value) {
  std::memcpy(bytes.data() + offset, &value, sizeof(T));
  const std::uint32_t crc = format::Crc32(bytes.data() + format::kHeaderSize, bytes.size() - format::kHeaderSize);
  std::memcpy(bytes.data() + format::kOffChecksum, &crc, 4);
  return bytes;
}

inline Rig LoadTestRig(const std::string& name, Isa isa = Isa::kAuto) {
  const std::vector<unsigned char> bytes = TestRigBytes(name);
  Rig rig;
  Error err;
  LoadOptions options;
  options.isa = isa;
  REQUIRE_MESSAGE(LoadRig(bytes.data(), bytes.size(), &rig, &err, options), name << ": " << err.message);
  return rig;
}

struct Weights {
  std::vector<double> raw, limited, texture;
};

inline Weights WeightsAt(const Rig& rig, double x, double y, double sigma = 0, bool limit_weights = true) {
  Weights w;
  w.raw.resize(rig.pose_count());
  w.limited.resize(rig.pose_count());
  w.texture.resize(rig.pose_count());
  WeightsJob job;
  job.rig = &rig;
  job.x = x, job.y = y, job.sigma = sigma, job.limit_weights = limit_weights;
  job.raw = MakeSpan(w.raw), job.limited = MakeSpan(w.limited), job.texture = MakeSpan(w.texture);
  REQUIRE(job.Run());
  return w;
}

inline std::vector<double> Morph(const Rig& rig, const std::vector<double>& w, const std::vector<double>& ws,
                                 Interpolation mode = Interpolation::kRigid) {
  std::vector<double> work(rig.morph_workspace_size()), x(2 * std::size_t(rig.vertex_count()));
  MorphJob job;
  job.rig = &rig;
  job.weights = MakeSpan(w), job.limited_weights = MakeSpan(ws);
  job.interpolation = mode;
  job.workspace = MakeSpan(work), job.positions = MakeSpan(x);
  REQUIRE(job.Run());
  return x;
}

inline std::vector<double> MorphAt(const Rig& rig, double px, double py, bool limit_weights = true) {
  const Weights w = WeightsAt(rig, px, py, 0, limit_weights);
  return Morph(rig, w.raw, w.limited);
}

// Smallest signed triangle area of positions x, relative to the same triangle at rest.
inline double MinAreaRatio(const Rig& rig, const std::vector<double>& x) {
  const auto t = rig.triangles();
  const double* r = rig.pose_positions(0).data;
  double worst = 1e300;
  auto area = [&](const double* p, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    return 0.5 * ((p[2 * b] - p[2 * a]) * (p[2 * c + 1] - p[2 * a + 1]) -
                  (p[2 * c] - p[2 * a]) * (p[2 * b + 1] - p[2 * a + 1]));
  };
  for (std::uint32_t k = 0; k < rig.triangle_count(); ++k) {
    const std::uint32_t a = t[3 * k], b = t[3 * k + 1], c = t[3 * k + 2];
    worst = std::min(worst, area(x.data(), a, b, c) / area(r, a, b, c));
  }
  return worst;
}

// The offset (entry field 8) or size (field 16) of the first section with
// `tag` in a rig file's table (0 when none), read directly: it works on
// bytes a test has mutated.
inline std::uint64_t SectionField(const std::vector<unsigned char>& bytes, std::uint32_t tag, std::size_t field) {
  std::uint32_t sections = 0;
  std::memcpy(&sections, bytes.data() + format::kOffSectionCount, 4);
  for (std::uint32_t s = 0; s < sections; ++s) {
    const unsigned char* e = bytes.data() + format::kHeaderSize + std::size_t(s) * format::kSectionEntrySize;
    std::uint32_t t;
    std::memcpy(&t, e, 4);
    if (t == tag) {
      std::uint64_t value;
      std::memcpy(&value, e + field, 8);
      return value;
    }
  }
  return 0;
}
inline std::size_t SectionOffset(const std::vector<unsigned char>& bytes, std::uint32_t tag) {
  return std::size_t(SectionField(bytes, tag, 8));
}
inline std::uint64_t SectionSize(const std::vector<unsigned char>& bytes, std::uint32_t tag) {
  return SectionField(bytes, tag, 16);
}

inline void PutU32(unsigned char* at, std::uint32_t v) { std::memcpy(at, &v, 4); }
inline void PutF64(unsigned char* at, double v) { std::memcpy(at, &v, 8); }

// A copy of `bytes` changed by `mutate` is refused at load (checksum not
// verified, so that the change reaches the section's checks) with a
// message that contains `problem`.
template <typename Mutate>
void ExpectRefused(const std::vector<unsigned char>& bytes, Mutate mutate, const std::string& problem) {
  std::vector<unsigned char> b = bytes;
  mutate(b.data());
  LoadOptions options;
  options.verify_checksum = false;
  Rig rig;
  Error err;
  CAPTURE(problem);
  CHECK_FALSE(LoadRig(b.data(), b.size(), &rig, &err, options));
  CAPTURE(err.message);
  CHECK(std::string(err.message).find(problem) != std::string::npos);
  CHECK_FALSE(rig.loaded());
}

}  // namespace posemorph::test
