// SPDX-License-Identifier: MIT
// Colour set by states (format 1.10; MachineColourJob) on Pell with a face,
// whose body layer has a "ghost" state (a blue tint, the body and arms at
// 0.3 under a whole head) and a "vanished" one (opacity 0): the states'
// colours as views, fades that follow each transition's mix linearly and
// never jump (also when a change interrupts one), the same colour at 30, 60
// and 144 updates per second, any bytes giving colours in [0, 1], the C
// API's bits, and each refusal of the job.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "animator_support.h"
#include "posemorph/posemorph.h"
#include "posemorph/rig_format.h"
#include "posemorph/state_machine.h"
#include "runtime_support.h"

using namespace posemorph;
using namespace posemorph::test;

namespace {

std::uint32_t Input(const Rig& rig, const char* name) {
  const int i = rig.FindMachineInput(name);
  REQUIRE(i >= 0);
  return std::uint32_t(i);
}

std::uint32_t Part(const Rig& rig, const char* name) {
  for (std::uint32_t p = 0; p < rig.part_count(); ++p)
    if (std::string(rig.part(p).name.data, rig.part(p).name.size) == name) return p;
  FAIL("no part " << name);
  return 0;
}

// One character: each frame its machine steps, its animator advances by dt
// and its colour follows.
struct Coloured {
  const Rig& rig;
  Character ch;
  MachineInstance m;
  Colour colour;
  std::vector<float> parts;
  explicit Coloured(const Rig& r) : rig(r), ch(r), parts(r.part_count()) { REQUIRE(MachineReset(r, &m)); }
  void Frame(double dt) {
    MachineStepJob step;
    step.rig = &rig, step.machines = {&m, 1}, step.tracks = ch.Tracks();
    REQUIRE(step.Run());
    ch.Update(dt);
    MachineColourJob job;
    job.rig = &rig, job.dt = dt, job.machines = {&m, 1};
    job.colours = {&colour, 1}, job.part_opacities = MakeSpan(parts);
    REQUIRE(job.Validate());
    REQUIRE(job.Run());
  }
};

}  // namespace

TEST_CASE("states carry the colours the description gives them") {
  const Rig rig = LoadTestRig("pell-face");
  const MachineStateView& ghost = rig.machine_states()[std::size_t(rig.FindMachineState("ghost"))];
  const MachineStateView& vanished = rig.machine_states()[std::size_t(rig.FindMachineState("vanished"))];
  const MachineStateView& idle = rig.machine_states()[std::size_t(rig.FindMachineState("idle"))];
  CHECK(ghost.colour[0] == 0.7f);
  CHECK(ghost.colour[1] == 0.85f);
  CHECK(ghost.colour[2] == 1.0f);
  CHECK(ghost.colour[3] == 1.0f);
  REQUIRE(ghost.part_opacities.size == 3);
  CHECK(ghost.part_opacities[0].part == Part(rig, "body"));
  CHECK(ghost.part_opacities[1].part == Part(rig, "arm-left"));
  CHECK(ghost.part_opacities[2].part == Part(rig, "arm-right"));
  for (const MachinePartOpacityView& o : ghost.part_opacities) CHECK(o.opacity == 0.3f);
  CHECK(vanished.colour[3] == 0.0f);
  CHECK(vanished.part_opacities.size == 0);
  for (float c : idle.colour) CHECK(c == 1.0f);
  CHECK(rig.format_minor() == format::kVersionMinor);
}

TEST_CASE("a change of state fades the colour over its mix, linearly, and never jumps") {
  const Rig rig = LoadTestRig("pell-face");
  Coloured c(rig);
  const double dt = 1.0 / 60;
  c.Frame(dt);  // starts: the initial states' colour at once
  CHECK(c.colour.a == 1.0f);
  for (float p : c.parts) CHECK(p == 1.0f);
  // Vanish: idle -> vanished over 1 s (its mix), opacity 1 -> 0.
  REQUIRE(MachineSetBool(rig, &c.m, Input(rig, "vanish"), true));
  float last = 1;
  for (int f = 1; f <= 30; ++f) {
    c.Frame(dt);
    CHECK(std::fabs(c.colour.a - float(1 - f * dt)) < 1e-5f);
    CHECK(last - c.colour.a <= float(dt) + 1e-5f);  // no faster than the mix
    last = c.colour.a;
  }
  // Half-way the game changes its mind: back to idle over 0.5 s from where the fade was.
  REQUIRE(MachineSetBool(rig, &c.m, Input(rig, "vanish"), false));
  c.Frame(dt);
  CHECK(std::fabs(c.colour.a - (0.5f + 0.5f * float(dt / 0.5))) < 1e-5f);
  for (int f = 0; f < 40; ++f) {
    const float before = c.colour.a;
    c.Frame(dt);
    CHECK(c.colour.a >= before);
    CHECK(c.colour.a - before <= 0.5f * float(dt / 0.5) + 1e-5f);
  }
  CHECK(c.colour.a == 1.0f);
  // The ghost: tint and the body's parts fade to theirs over 0.6 s; the head stays.
  REQUIRE(MachineSetBool(rig, &c.m, Input(rig, "ghost"), true));
  for (int f = 0; f < 36; ++f) c.Frame(dt);
  CHECK(std::fabs(c.colour.r - 0.7f) < 1e-5f);
  CHECK(std::fabs(c.colour.g - 0.85f) < 1e-5f);
  CHECK(c.colour.b == 1.0f);
  CHECK(c.colour.a == 1.0f);
  CHECK(std::fabs(c.parts[Part(rig, "body")] - 0.3f) < 1e-5f);
  CHECK(std::fabs(c.parts[Part(rig, "arm-right")] - 0.3f) < 1e-5f);
  CHECK(c.parts[Part(rig, "head")] == 1.0f);
  // Vanishing from the ghost: the tint stays, opacity goes to 0, the parts back to 1.
  REQUIRE(MachineSetBool(rig, &c.m, Input(rig, "vanish"), true));
  for (int f = 0; f < 60; ++f) c.Frame(dt);
  CHECK(c.colour.a == 0.0f);
  CHECK(c.colour.r == 1.0f);
  CHECK(c.parts[Part(rig, "body")] == 1.0f);
}

TEST_CASE("the colour at a time does not depend on the update rate") {
  const Rig rig = LoadTestRig("pell-face");
  // The same input timeline at 30, 60 and 144 updates/s, compared every sixth of a second.
  std::vector<std::vector<float>> seen(3);
  const int rates[] = {30, 60, 144};
  for (int r = 0; r < 3; ++r) {
    Coloured c(rig);
    const int rate = rates[r], per_sixth = rate / 6;
    for (int f = 0; f <= 4 * rate; ++f) {
      c.Frame(f == 0 ? 0 : 1.0 / rate);  // to f / rate
      if (f % per_sixth == 0) {
        seen[r].insert(seen[r].end(), {c.colour.r, c.colour.g, c.colour.b, c.colour.a});
        seen[r].insert(seen[r].end(), c.parts.begin(), c.parts.end());
      }
      // Inputs at shared times: they take effect from the next update, which starts then.
      if (f == rate / 2) REQUIRE(MachineSetBool(rig, &c.m, Input(rig, "ghost"), true));
      if (f == rate * 3 / 2) REQUIRE(MachineSetBool(rig, &c.m, Input(rig, "vanish"), true));
      if (f == rate * 2) REQUIRE(MachineSetBool(rig, &c.m, Input(rig, "vanish"), false));
    }
  }
  REQUIRE(seen[0].size() == seen[1].size());
  REQUIRE(seen[0].size() == seen[2].size());
  for (std::size_t k = 0; k < seen[0].size(); ++k) {
    CAPTURE(k);
    CHECK(std::fabs(seen[0][k] - seen[1][k]) < 1e-5f);
    CHECK(std::fabs(seen[0][k] - seen[2][k]) < 1e-5f);
  }
}

TEST_CASE("any bytes in an instance give colours in [0, 1], and the C API gives the same bits") {
  const Rig rig = LoadTestRig("pell-face");
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 300; ++trial) {
    MachineInstance m;
    unsigned char* bytes = reinterpret_cast<unsigned char*>(&m);
    for (std::size_t i = 0; i < sizeof(MachineInstance); ++i) bytes[i] = static_cast<unsigned char>(rng());
    Colour colour;
    std::vector<float> parts(rig.part_count());
    MachineColourJob job;
    job.rig = &rig, job.dt = trial % 3 == 0 ? std::nan("") : 0.01 * trial;
    job.machines = {&m, 1}, job.colours = {&colour, 1}, job.part_opacities = MakeSpan(parts);
    REQUIRE(job.Run());
    for (float v : {colour.r, colour.g, colour.b, colour.a}) CHECK((v >= 0 && v <= 1));
    for (float v : parts) CHECK((v >= 0 && v <= 1));
  }
  // The C API on the same machine, after the same step.
  Coloured c(rig);
  REQUIRE(MachineSetBool(rig, &c.m, Input(rig, "ghost"), true));
  c.Frame(0.1);
  MachineInstance copy = c.m;
  c.Frame(0.1);
  Character other(rig);
  std::vector<unsigned char> rig_bytes = TestRigBytes("pell-face");
  pm_rig* crig = nullptr;
  REQUIRE(pm_rig_load(rig_bytes.data(), rig_bytes.size(), &crig, nullptr) == PM_OK);
  MachineStepJob step;
  step.rig = &rig, step.machines = {&copy, 1}, step.tracks = other.Tracks();
  REQUIRE(step.Run());
  pm_colour colour;
  std::vector<float> parts(rig.part_count());
  REQUIRE(pm_machine_colours(crig, &copy, sizeof copy, 1, 0.1, &colour, parts.data(), parts.size()) == PM_OK);
  CHECK(std::memcmp(&colour, &c.colour, sizeof colour) == 0);
  CHECK(parts == c.parts);
  CHECK(pm_machine_colours(crig, &copy, sizeof copy, 1, 0.1, nullptr, parts.data(), parts.size() - 1) ==
        PM_ERROR_BUFFER_TOO_SMALL);
  CHECK(pm_machine_colours(crig, &copy, sizeof copy - 1, 1, 0.1, &colour, nullptr, 0) == PM_ERROR_BUFFER_TOO_SMALL);
  pm_rig_free(crig);
}

TEST_CASE("MachineColourJob refuses each listed failure case") {
  const Rig rig = LoadTestRig("pell-face"), plain = LoadTestRig("pip");
  MachineInstance m[2];
  REQUIRE(MachineReset(rig, &m[0]));
  REQUIRE(MachineReset(rig, &m[1]));
  Colour colours[2];
  std::vector<float> parts(2 * rig.part_count());
  auto job = [&] {
    MachineColourJob j;
    j.rig = &rig, j.count = 2, j.machines = {m, 2}, j.colours = {colours, 2}, j.part_opacities = MakeSpan(parts);
    return j;
  };
  CHECK(job().Validate());
  MachineColourJob j = job();
  j.rig = nullptr;
  CHECK_FALSE(j.Validate());
  j = job(), j.rig = &plain;  // no machine
  CHECK_FALSE(j.Validate());
  j = job(), j.count = kMaxAnimatorBatch + 1;
  CHECK_FALSE(j.Validate());
  j = job(), j.machines.size = 1;
  CHECK_FALSE(j.Validate());
  j = job(), j.colours.size = 1;
  CHECK_FALSE(j.Validate());
  j = job(), j.part_opacities.size -= 1;
  CHECK_FALSE(j.Validate());
  j = job(), j.colours = {}, j.part_opacities = {};  // nothing asked: still a valid job (it advances the fades)
  CHECK(j.Validate());
  CHECK_FALSE(MachineColourJob{}.Run());
}
