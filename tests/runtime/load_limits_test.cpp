// SPDX-License-Identifier: MIT
// LoadLimits: bounds for rigs from untrusted sources. Every sample loads
// within LoadLimits::Untrusted(); a rig beyond one bound is refused with
// kTooLarge and a message naming it, for the body and for a character's
// attachments (each alone and all together), and RigMemorySize refuses it
// too, so a game learns before it gives memory.
#include <doctest/doctest.h>

#include <cstring>
#include <string>
#include <vector>

#include "posemorph/format/records.h"
#include "posemorph/rig.h"
#include "posemorph/rig_format.h"
#include "runtime_support.h"

using namespace posemorph;
using posemorph::test::TestRigBytes;

namespace {

// The load's error with these limits ("" when it loads).
std::string Refusal(const std::vector<unsigned char>& bytes, const LoadLimits& limits) {
  LoadOptions options;
  options.limits = limits;
  Rig rig;
  Error err;
  if (LoadRig(bytes.data(), bytes.size(), &rig, &err, options)) return "";
  CHECK(err.code == ErrorCode::kTooLarge);
  std::size_t needed = 0;
  Error size_err;
  CHECK(!RigMemorySize(bytes.data(), bytes.size(), &needed, &size_err, options));
  CHECK(std::string(size_err.message) == err.message);
  return err.message;
}

}  // namespace

TEST_CASE("load limits: every sample loads within the untrusted bounds") {
  for (const char* name : {"snake", "worm-line", "gingerbread", "pip", "sprout", "small", "arm", "pell", "pell-face"})
    for (const char* encoding : {"", ".compact"}) {
      const std::string rig = std::string(name) + encoding;
      CAPTURE(rig);
      CHECK(Refusal(TestRigBytes(rig), LoadLimits::Untrusted()) == "");
    }
}

TEST_CASE("load limits: each bound refuses the rig beyond it, naming the bound") {
  const std::vector<unsigned char> pip = TestRigBytes("pip");  // 625 vertices, 5 poses, 5,730 nonzeros
  Rig rig;
  REQUIRE(LoadRig(pip.data(), pip.size(), &rig, nullptr));
  std::size_t memory = 0;
  REQUIRE(RigMemorySize(pip.data(), pip.size(), &memory, nullptr));
  LoadLimits at;  // exactly the rig's own counts: it loads
  at.max_bytes = pip.size(), at.max_memory = memory, at.max_vertices = rig.vertex_count();
  const std::uint64_t nonzeros = rig.factor().row.size;
  at.max_poses = rig.pose_count(), at.max_factor_nonzeros = nonzeros;
  CHECK(Refusal(pip, at) == "");
  LoadLimits l = at;
  l.max_bytes = pip.size() - 1;
  CHECK(Refusal(pip, l) == "the file is " + std::to_string(pip.size()) + " bytes, above the limit of " +
                               std::to_string(pip.size() - 1) + " (LoadLimits::max_bytes)");
  l = at, l.max_memory = memory - 1;
  CHECK(Refusal(pip, l) == "the rig needs " + std::to_string(memory) + " bytes in memory, above the limit of " +
                               std::to_string(memory - 1) + " (LoadLimits::max_memory)");
  l = at, l.max_vertices = 624;
  CHECK(Refusal(pip, l) == "625 vertices, above the limit of 624 (LoadLimits::max_vertices)");
  l = at, l.max_poses = 4;
  CHECK(Refusal(pip, l) == "5 poses, above the limit of 4 (LoadLimits::max_poses)");
  l = at, l.max_factor_nonzeros = nonzeros - 1;
  CHECK(Refusal(pip, l) == "a factor of " + std::to_string(nonzeros) + " nonzeros, above the limit of " +
                               std::to_string(nonzeros - 1) + " (LoadLimits::max_factor_nonzeros)");
}

TEST_CASE("load limits: a character's attachments count alone and with the body") {
  const std::vector<unsigned char> face = TestRigBytes("pell-face");
  Rig rig;
  REQUIRE(LoadRig(face.data(), face.size(), &rig, nullptr));
  REQUIRE(rig.attachment_count() == 3);
  LoadLimits l;
  l.max_attachments = 2;
  CHECK(Refusal(face, l) == "3 attachments, above the limit of 2 (LoadLimits::max_attachments)");
  l.max_attachments = 3;
  CHECK(Refusal(face, l) == "");
  // The body alone fits, the body with its attachments does not.
  const std::uint64_t total = std::uint64_t(rig.vertex_count()) + rig.attached_vertex_count();
  l = LoadLimits{};
  l.max_vertices = rig.vertex_count();
  CHECK(Refusal(face, l) == std::to_string(total) + " vertices with the attachments', above the limit of " +
                                std::to_string(rig.vertex_count()) + " (LoadLimits::max_vertices)");
  l.max_vertices = std::uint32_t(total);
  CHECK(Refusal(face, l) == "");
  // The factors likewise: the body's fits, with the attachments' it does not.
  RigSection sections[format::kMaxSections];
  std::uint32_t count = 0;
  REQUIRE(ReadRigSections(face.data(), face.size(), sections, format::kMaxSections, &count, nullptr));
  std::uint64_t body_nonzeros = 0;
  for (std::uint32_t k = 0; k < count; ++k)
    if (sections[k].tag == format::kMeta)
      body_nonzeros = format::DecodeRecord<format::Meta>(face.data() + sections[k].offset).factor_nonzeros;
  REQUIRE(body_nonzeros > 0);
  l = LoadLimits{};
  l.max_factor_nonzeros = body_nonzeros;
  const std::string e = Refusal(face, l);
  CHECK(e.find("factors of ") == 0);
  CHECK(e.find(" nonzeros with the attachments', above the limit of " + std::to_string(body_nonzeros) +
               " (LoadLimits::max_factor_nonzeros)") != std::string::npos);
}

TEST_CASE("load limits: a factor filled beyond what the bake's orders give is refused before its arrays are read") {
  // Issue 38, F2: a rig with a poor fill-reducing order loaded in 1.8 s and
  // evaluated 35x slower than an honest bake of the same mesh. max_fill
  // bounds nnz by max_fill x V x ceil(log2 V) per pose space (the bake's
  // orders: at most 0.92 for the samples, 2.7 for a 90,000-vertex grid).
  std::vector<unsigned char> snake = TestRigBytes("snake");  // 205 vertices: 8 x 205 x 8 = 13,120 nonzeros at most
  RigSection sections[format::kMaxSections];
  std::uint32_t count = 0;
  REQUIRE(ReadRigSections(snake.data(), snake.size(), sections, format::kMaxSections, &count, nullptr));
  std::size_t meta = 0;
  for (std::uint32_t k = 0; k < count; ++k)
    if (sections[k].tag == format::kMeta) meta = std::size_t(sections[k].offset);
  REQUIRE(meta != 0);
  format::Meta m = format::DecodeRecord<format::Meta>(snake.data() + meta);
  CHECK(m.factor_nonzeros <= 205 * 8);  // the honest snake: under a fill of 1
  // META claiming 13,121 nonzeros: refused by the counts alone, before the
  // sections' sizes (which then no longer match) are looked at.
  m.factor_nonzeros = 8 * 205 * 8 + 1;
  format::EncodeRecord(m, snake.data() + meta);
  const std::uint32_t crc = format::Crc32(snake.data() + format::kHeaderSize, snake.size() - format::kHeaderSize);
  std::memcpy(snake.data() + format::kOffChecksum, &crc, 4);
  CHECK(Refusal(snake, LoadLimits::Untrusted()) ==
        "a factor of 13121 nonzeros for 205 vertices, above 8 x V x log2 V (LoadLimits::max_fill): a fill-reducing "
        "order the bake does not write");
  LoadLimits fill_only;
  fill_only.max_fill = 8;
  CHECK(Refusal(snake, fill_only).find("LoadLimits::max_fill") != std::string::npos);
  // At the bound itself the counts pass, and the sizes that no longer match refuse it instead.
  m.factor_nonzeros = 8 * 205 * 8;
  format::EncodeRecord(m, snake.data() + meta);
  const std::uint32_t crc2 = format::Crc32(snake.data() + format::kHeaderSize, snake.size() - format::kHeaderSize);
  std::memcpy(snake.data() + format::kOffChecksum, &crc2, 4);
  LoadOptions options;
  options.limits = fill_only;
  Rig rig;
  Error err;
  CHECK_FALSE(LoadRig(snake.data(), snake.size(), &rig, &err, options));
  CHECK(std::string(err.message).find("max_fill") == std::string::npos);
}
