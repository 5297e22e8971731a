// SPDX-License-Identifier: MIT
// Choosing the kernel path: names, availability, forced paths, and the
// clear error for a path this build or CPU lacks (never an illegal
// instruction).
#include <cstring>
#include <string>

#include "posemorph/posemorph.h"
#include "runtime_support.h"

using namespace posemorph;
using namespace posemorph::test;

TEST_CASE("path names round-trip and unknown names are refused") {
  for (Isa isa : {Isa::kAuto, Isa::kScalar, Isa::kSse2, Isa::kAvx2, Isa::kAvx512, Isa::kNeon, Isa::kWasmSimd}) {
    Isa back = Isa::kAuto;
    REQUIRE(ParseIsa(IsaName(isa), &back));
    CHECK(back == isa);
  }
  Isa out = Isa::kScalar;
  CHECK_FALSE(ParseIsa("avx1024", &out));
  CHECK_FALSE(ParseIsa(nullptr, &out));
  CHECK(out == Isa::kScalar);
}

TEST_CASE("the scalar path is always there and the best path is available") {
  CHECK(IsaAvailable(Isa::kScalar));
  CHECK(IsaAvailable(BestIsa()));
  CHECK_FALSE(IsaAvailable(Isa::kAuto));
#if defined(__x86_64__) || defined(_M_X64)
  CHECK(IsaAvailable(Isa::kSse2));
  CHECK_FALSE(IsaAvailable(Isa::kNeon));
#elif defined(__aarch64__)
  CHECK(IsaAvailable(Isa::kNeon));
  CHECK(BestIsa() == Isa::kNeon);
  CHECK_FALSE(IsaAvailable(Isa::kAvx2));
#endif
}

TEST_CASE("a rig reports the path it was loaded with") {
  const std::vector<unsigned char> bytes = TestRigBytes("small");
  for (Isa isa : {Isa::kScalar, Isa::kSse2, Isa::kAvx2, Isa::kAvx512, Isa::kNeon, Isa::kWasmSimd}) {
    const std::string path = IsaName(isa);
    CAPTURE(path);
    Rig rig;
    Error err;
    LoadOptions options;
    options.isa = isa;
    const bool ok = LoadRig(bytes.data(), bytes.size(), &rig, &err, options);
    CHECK(ok == IsaAvailable(isa));
    if (ok) {
      CHECK(rig.isa() == isa);
    } else {
      // A forced path the build or CPU lacks: an error at load, naming it.
      CHECK(err.code == ErrorCode::kUnsupportedIsa);
      CHECK(std::string(err.message).find(IsaName(isa)) != std::string::npos);
      CHECK_FALSE(rig.loaded());
    }
  }
  Rig rig = LoadTestRig("small");
  CHECK(rig.isa() != Isa::kAuto);
}

#if !defined(_WIN32) && !defined(__EMSCRIPTEN__)
TEST_CASE("POSEMORPH_ISA chooses the path, and an unknown value fails the load") {
  const std::vector<unsigned char> bytes = TestRigBytes("small");
  const char* saved = std::getenv("POSEMORPH_ISA");
  const std::string restore = saved ? saved : "";
  setenv("POSEMORPH_ISA", "scalar", 1);
  {
    Rig rig;
    REQUIRE(LoadRig(bytes.data(), bytes.size(), &rig, nullptr));
    CHECK(rig.isa() == Isa::kScalar);
    // An explicit option wins over the variable.
    LoadOptions options;
    options.isa = BestIsa();
    REQUIRE(LoadRig(bytes.data(), bytes.size(), &rig, nullptr, options));
    CHECK(rig.isa() == BestIsa());
  }
  setenv("POSEMORPH_ISA", "mmx", 1);
  {
    Rig rig;
    Error err;
    CHECK_FALSE(LoadRig(bytes.data(), bytes.size(), &rig, &err));
    CHECK(err.code == ErrorCode::kUnsupportedIsa);
    CHECK(std::string(err.message).find("POSEMORPH_ISA=mmx") != std::string::npos);
    pm_rig* c_rig = nullptr;
    pm_error c_err;
    CHECK(pm_rig_load(bytes.data(), bytes.size(), &c_rig, &c_err) == PM_ERROR_UNSUPPORTED_ISA);
    CHECK(c_rig == nullptr);
  }
  if (saved)
    setenv("POSEMORPH_ISA", restore.c_str(), 1);
  else
    unsetenv("POSEMORPH_ISA");
}
#endif
