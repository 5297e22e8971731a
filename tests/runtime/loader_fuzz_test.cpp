// SPDX-License-Identifier: MIT
// Hostile bytes: every truncation and every single-byte change of a small
// valid rig must be rejected or load to a rig the jobs evaluate safely. Run
// under the debug preset, AddressSanitizer and UBSan watch every access.
#include <cstring>

#include "posemorph/path.h"
#include "posemorph/rig_format.h"
#include "runtime_support.h"

using namespace posemorph;
using namespace posemorph::test;

namespace {

// tests/runtime/rigs/small.json, baked: 4 vertices, 2 poses, uvs, a path.
std::vector<unsigned char> SmallRigBytes() { return TestRigBytes("small"); }

// Loads, and when that works, evaluates a few frames: whatever loads must be safe to run.
bool LoadAndUse(const std::vector<unsigned char>& bytes, bool checksum) {
  Rig rig;
  Error err;
  LoadOptions options;
  options.verify_checksum = checksum;
  if (!LoadRig(bytes.data(), bytes.size(), &rig, &err, options)) {
    CHECK(err.code != ErrorCode::kOk);
    CHECK(std::strlen(err.message) > 0);
    return false;
  }
  const std::uint32_t N = rig.pose_count();
  std::vector<double> raw(N), limited(N), tex(N), work(rig.morph_workspace_size()), x(2 * rig.vertex_count());
  const double points[][2] = {{0, 0}, {1, 0.5}, {-5, 7}, {0.3, 0.2}};
  for (const auto& p : points) {
    WeightsJob wj;
    wj.rig = &rig, wj.x = p[0], wj.y = p[1], wj.sigma = 0.5;
    wj.raw = MakeSpan(raw), wj.limited = MakeSpan(limited), wj.texture = MakeSpan(tex);
    REQUIRE(wj.Run());
    MorphJob mj;
    mj.rig = &rig, mj.weights = MakeSpan(raw), mj.limited_weights = MakeSpan(limited);
    mj.workspace = MakeSpan(work), mj.positions = MakeSpan(x);
    mj.Run();  // may refuse non-finite weights from a corrupted grid; must not crash
  }
  for (std::uint32_t i = 0; i < rig.path_count(); ++i) {
    double px, py;
    SamplePath(rig, i, 0.7, &px, &py);
  }
  return true;
}

}  // namespace

TEST_CASE("the small fuzz rig loads and evaluates") {
  const auto bytes = SmallRigBytes();
  CHECK(LoadAndUse(bytes, true));
  MESSAGE("fuzz rig: " << bytes.size() << " bytes");
}

TEST_CASE("every truncation is rejected") {
  const auto bytes = SmallRigBytes();
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    std::vector<unsigned char> cut(bytes.begin(), bytes.begin() + n);
    CAPTURE(n);
    CHECK_FALSE(LoadAndUse(cut, true));
    CHECK_FALSE(LoadAndUse(cut, false));
  }
  // And extra bytes after a valid rig.
  std::vector<unsigned char> longer = bytes;
  longer.push_back(0);
  CHECK_FALSE(LoadAndUse(longer, true));
}

TEST_CASE("every single-byte change is rejected by the checksum, and safe without it") {
  const auto bytes = SmallRigBytes();
  std::size_t loaded_without_checksum = 0, tried = 0;
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    for (unsigned mask : {0xFFu, 0x01u, 0x02u, 0x04u, 0x08u, 0x10u, 0x20u, 0x40u, 0x80u}) {
      std::vector<unsigned char> bad = bytes;
      bad[i] ^= static_cast<unsigned char>(mask);
      CAPTURE(i);
      CAPTURE(mask);
      // The checksum field covers bytes 64.., so a change inside the header
      // itself can only be caught by the header's own checks.
      const bool in_header = i < format::kHeaderSize;
      if (!in_header || i >= format::kOffChecksum)
        CHECK_FALSE(LoadAndUse(bad, true));
      else
        LoadAndUse(bad, true);
      loaded_without_checksum += LoadAndUse(bad, false);
      ++tried;
    }
  }
  MESSAGE(tried << " changed rigs; " << loaded_without_checksum << " still loaded (and ran) without the checksum");
}

TEST_CASE("oversized counts are rejected before anything is allocated") {
  const auto bytes = SmallRigBytes();
  // Find META through the section table and overwrite each count with huge values.
  std::uint64_t meta = 0;
  std::uint32_t sections;
  std::memcpy(&sections, bytes.data() + format::kOffSectionCount, 4);
  for (std::uint32_t s = 0; s < sections; ++s) {
    std::uint32_t tag;
    std::memcpy(&tag, bytes.data() + format::kHeaderSize + 24 * s, 4);
    if (tag == format::kMeta) std::memcpy(&meta, bytes.data() + format::kHeaderSize + 24 * s + 8, 8);
  }
  REQUIRE(meta != 0);
  for (std::size_t field = 0; field < 7; ++field)
    for (std::uint32_t value : {0u, 1u, 0x7FFFFFFFu, 0xFFFFFFFFu, 1u << 22}) {
      std::vector<unsigned char> bad = bytes;
      std::memcpy(bad.data() + meta + 4 * field, &value, 4);
      const std::uint32_t crc = format::Crc32(bad.data() + format::kHeaderSize, bad.size() - format::kHeaderSize);
      std::memcpy(bad.data() + format::kOffChecksum, &crc, 4);
      CAPTURE(field);
      CAPTURE(value);
      Rig rig;
      Error err;
      const bool ok = LoadRig(bad.data(), bad.size(), &rig, &err);
      std::uint32_t original;
      std::memcpy(&original, bytes.data() + meta + 4 * field, 4);
      if (value != original) CHECK_FALSE(ok);
    }
}

TEST_CASE("loader messages name the problem") {
  const auto bytes = SmallRigBytes();
  Rig rig;
  Error err;
  CHECK_FALSE(LoadRig(bytes.data(), 10, &rig, &err));
  CHECK(err.code == ErrorCode::kTruncated);
  std::vector<unsigned char> bad = bytes;
  bad[0] = 'X';
  CHECK_FALSE(LoadRig(bad.data(), bad.size(), &rig, &err));
  CHECK(err.code == ErrorCode::kBadMagic);
  bad = bytes;
  bad[bad.size() - 1] ^= 1;
  CHECK_FALSE(LoadRig(bad.data(), bad.size(), &rig, &err));
  CHECK(err.code == ErrorCode::kBadChecksum);
  CHECK(std::string(err.message).find("checksum") != std::string::npos);
  CHECK_FALSE(rig.loaded());
  CHECK_FALSE(LoadRig(nullptr, 100, &rig, &err));
  CHECK(err.code == ErrorCode::kInvalidArgument);
}

TEST_CASE("CRC-32 matches the standard check value at every alignment and length") {
  // The check value of CRC-32/ISO-HDLC: CRC of the ASCII digits "123456789".
  const unsigned char digits[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  CHECK(format::Crc32(digits, 9) == 0xCBF43926u);
  // Eight bytes at a time and one at a time agree for every split.
  std::vector<unsigned char> bytes(100);
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>(i * 37 + 11);
  const std::uint32_t whole = format::Crc32(bytes.data(), bytes.size());
  for (std::size_t cut = 0; cut <= bytes.size(); ++cut)
    CHECK(format::Crc32(bytes.data() + cut, bytes.size() - cut, format::Crc32(bytes.data(), cut)) == whole);
}
