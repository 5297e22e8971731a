// SPDX-License-Identifier: MIT
// Loading into caller-owned memory: the size query, the same frames as an
// allocating load, and every misuse refused (null, misaligned, short).
#include <cstdint>
#include <cstring>
#include <string>

#include "posemorph/posemorph.h"
#include "runtime_support.h"

using namespace posemorph;
using namespace posemorph::test;

namespace {

// Memory aligned to kRigMemoryAlignment (plus `offset` bytes), from a vector of doubles.
struct Aligned {
  std::vector<double> storage;
  unsigned char* at(std::size_t offset) {
    auto p = reinterpret_cast<std::uintptr_t>(storage.data());
    p = (p + kRigMemoryAlignment - 1) / kRigMemoryAlignment * kRigMemoryAlignment;
    return reinterpret_cast<unsigned char*>(p) + offset;
  }
  explicit Aligned(std::size_t bytes) : storage(bytes / sizeof(double) + 8) {}
};

}  // namespace

TEST_CASE("a rig loaded in caller-owned memory gives the same bits as an allocating load") {
  for (const char* name : {"snake", "pip", "small"}) {
    const std::string rig_name = name;
    CAPTURE(rig_name);
    std::vector<unsigned char> bytes = TestRigBytes(name);
    const Rig owned = LoadTestRig(name);
    std::size_t needed = 0;
    Error err;
    REQUIRE_MESSAGE(RigMemorySize(bytes.data(), bytes.size(), &needed, &err), err.message);
    CHECK(needed == owned.arena_bytes());
    Aligned memory(needed);
    Rig rig;
    REQUIRE_MESSAGE(LoadRigInPlace(bytes.data(), bytes.size(), memory.at(0), needed, &rig, &err), err.message);
    std::fill(bytes.begin(), bytes.end(), 0);  // the bytes are not needed after loading
    CHECK(rig.loaded());
    CHECK(rig.arena_bytes() == needed);
    CHECK(reinterpret_cast<const unsigned char*>(rig.triangles().data) >= memory.at(0));
    CHECK(reinterpret_cast<const unsigned char*>(rig.triangles().data) < memory.at(needed));
    const PoseSpaceGrid& g = rig.grid();
    for (double fx : {-0.2, 0.3, 0.77, 1.3}) {
      const double px = g.origin_x + fx * g.cell * g.cells_x, py = g.origin_y + (1 - fx) * g.cell * g.cells_y;
      const Weights a = WeightsAt(rig, px, py), b = WeightsAt(owned, px, py);
      const std::vector<double> xa = Morph(rig, a.raw, a.limited), xb = Morph(owned, b.raw, b.limited);
      CHECK(std::memcmp(xa.data(), xb.data(), xa.size() * sizeof(double)) == 0);
    }
  }
}

// LoadRig's own arena starts on a kRigMemoryAlignment boundary on every
// target, as LoadRigInPlace asks of a caller's memory: WebAssembly's new[]
// aligns to 8 bytes only, and an attachment's rig is loaded in place inside
// its parent's arena (the cross build runs this under node).
TEST_CASE("an allocating load aligns its arrays, and each attachment's, to kRigMemoryAlignment") {
  const auto aligned = [](const void* p) { return reinterpret_cast<std::uintptr_t>(p) % kRigMemoryAlignment == 0; };
  for (const char* name : {"snake", "pip.compact", "pell-face", "pell-face.compact"}) {
    const std::string rig_name = name;
    CAPTURE(rig_name);
    std::vector<Rig> rigs;  // all alive at once: each arena at another heap address
    for (int copy = 0; copy < 8; ++copy) rigs.push_back(LoadTestRig(name));
    for (const Rig& rig : rigs) {
      CHECK(aligned(rig.triangles().data));
      CHECK(aligned(rig.pose_positions(0).data));
      for (std::uint32_t a = 0; a < rig.attachment_count(); ++a) {
        CAPTURE(a);
        CHECK(aligned(rig.attachment(a).rig->triangles().data));
        CHECK(aligned(rig.attachment(a).rig->pose_positions(0).data));
      }
    }
  }
}

TEST_CASE("in-place loading refuses null, misaligned and short memory, naming the size") {
  const std::vector<unsigned char> bytes = TestRigBytes("small");
  std::size_t needed = 0;
  REQUIRE(RigMemorySize(bytes.data(), bytes.size(), &needed, nullptr));
  Aligned memory(needed + 64);
  Rig rig;
  Error err;
  CHECK_FALSE(LoadRigInPlace(bytes.data(), bytes.size(), nullptr, needed, &rig, &err));
  CHECK(err.code == ErrorCode::kInvalidArgument);
  CHECK_FALSE(LoadRigInPlace(bytes.data(), bytes.size(), memory.at(8), needed, &rig, &err));
  CHECK(std::string(err.message).find("aligned") != std::string::npos);
  CHECK_FALSE(LoadRigInPlace(bytes.data(), bytes.size(), memory.at(0), needed - 1, &rig, &err));
  CHECK(std::string(err.message).find(std::to_string(needed)) != std::string::npos);
  CHECK_FALSE(rig.loaded());
  // The size query validates what sizes the memory, and refuses a bad rig.
  std::vector<unsigned char> bad = bytes;
  bad[0] = 'X';
  CHECK_FALSE(RigMemorySize(bad.data(), bad.size(), &needed, &err));
  CHECK(err.code == ErrorCode::kBadMagic);
  CHECK(needed == 0);
  CHECK_FALSE(RigMemorySize(bytes.data(), bytes.size(), nullptr, &err));
}

TEST_CASE("the C API loads in place too: handle and arrays in the caller's memory") {
  const std::vector<unsigned char> bytes = TestRigBytes("snake");
  std::size_t needed = 0;
  pm_error err;
  REQUIRE(pm_rig_memory_size(bytes.data(), bytes.size(), &needed, &err) == PM_OK);
  Aligned memory(needed);
  pm_rig* rig = nullptr;
  CHECK(pm_rig_load_in_place(bytes.data(), bytes.size(), memory.at(0), needed - 1, &rig, &err) != PM_OK);
  CHECK(rig == nullptr);
  CHECK(pm_rig_load_in_place(bytes.data(), bytes.size(), memory.at(4), needed, &rig, &err) ==
        PM_ERROR_INVALID_ARGUMENT);
  REQUIRE(pm_rig_load_in_place(bytes.data(), bytes.size(), memory.at(0), needed, &rig, &err) == PM_OK);
  CHECK(reinterpret_cast<unsigned char*>(rig) == memory.at(0));
  pm_rig_info info;
  pm_rig_get_info(rig, &info);
  std::vector<double> w(info.pose_count), ws(info.pose_count), work(pm_morph_workspace_size(rig)),
      x(2 * info.vertex_count);
  CHECK(pm_weights(rig, 0.3, -0.2, 0, 1, w.data(), ws.data(), nullptr, w.size()) == PM_OK);
  CHECK(pm_morph(rig, w.data(), ws.data(), 0, work.data(), work.size(), x.data(), nullptr, x.size()) == PM_OK);
  const Rig owned = LoadTestRig("snake");
  const Weights ow = WeightsAt(owned, 0.3, -0.2);
  const std::vector<double> ox = Morph(owned, ow.raw, ow.limited);
  CHECK(std::memcmp(x.data(), ox.data(), x.size() * sizeof(double)) == 0);
  pm_rig_free(rig);  // ends the rig; the memory stays ours
}
