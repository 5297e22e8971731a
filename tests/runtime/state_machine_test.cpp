// SPDX-License-Identifier: MIT
// The state machine (posemorph/state_machine.h) on Pell with a face, whose
// description declares one (assets/pell/make_pell.py): the golden sequence
// of states for a scripted input timeline, with its events and without a
// jump; blend and pad states follow their inputs; typed inputs; any bytes
// in an instance; a hostile MACH section refused at load, naming the
// problem.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "animator_support.h"
#include "posemorph/path.h"
#include "posemorph/state_machine.h"
#include "runtime_support.h"

using namespace posemorph;
using namespace posemorph::test;

namespace {

std::string StateName(const Rig& rig, std::uint32_t s) {
  const StringView n = rig.machine_states()[s].name;
  return {n.data, n.size};
}

std::uint32_t Input(const Rig& rig, const char* name) {
  const int i = rig.FindMachineInput(name);
  REQUIRE(i >= 0);
  return std::uint32_t(i);
}

// One character driven by the machine: inputs set before the step, then
// the step, then the animator's update by 1/60 s.
struct Driven {
  const Rig& rig;
  Character ch;
  MachineInstance m;
  std::vector<MachineChange> changes = std::vector<MachineChange>(8);
  explicit Driven(const Rig& r) : rig(r), ch(r) { REQUIRE(MachineReset(r, &m)); }
  std::vector<MachineChange> Step() {
    MachineStepJob job;
    job.rig = &rig;
    job.machines = {&m, 1};
    job.tracks = ch.Tracks();
    job.changes = MakeSpan(changes);
    std::size_t n = 0;
    std::uint64_t missed = 0;
    job.change_count = &n, job.changes_missed = &missed;
    REQUIRE(job.Run());
    REQUIRE(missed == 0);
    return {changes.begin(), changes.begin() + std::ptrdiff_t(n)};
  }
};

struct Seen {
  int frame;
  std::uint32_t layer;
  std::string from, to;
  bool operator==(const Seen& o) const { return frame == o.frame && layer == o.layer && from == o.from && to == o.to; }
};

}  // namespace

TEST_CASE("the sample's state machine gives its golden sequence, with its events and without a jump") {
  const Rig rig = LoadTestRig("pell-face");
  REQUIRE(rig.machine_layers().size == 2);
  Driven d(rig);
  const std::uint32_t wave = Input(rig, "wave"), sway = Input(rig, "sway"), talking = Input(rig, "talking"),
                      looking = Input(rig, "looking"), gaze = Input(rig, "gaze");
  std::vector<Seen> seen;
  std::vector<std::string> events;
  std::vector<double> before;
  double largest_move = 0;
  for (int k = 0; k <= 720; ++k) {
    if (k == 30 || k == 540) REQUIRE(MachineFire(rig, &d.m, wave));
    if (k == 60) REQUIRE(MachineSetBool(rig, &d.m, talking, true));
    if (k == 120) {
      REQUIRE(MachineSetBool(rig, &d.m, looking, true));
      REQUIRE(MachineSetPoint(rig, &d.m, gaze, 0.5, 0.5));
    }
    if (k == 180) REQUIRE(MachineSetBool(rig, &d.m, looking, false));
    if (k == 360) REQUIRE(MachineSetNumber(rig, &d.m, sway, 0.5));
    if (k == 480) REQUIRE(MachineSetNumber(rig, &d.m, sway, 0));
    if (k == 570) REQUIRE(MachineSetNumber(rig, &d.m, sway, 0.3));
    if (k == 660) REQUIRE(MachineSetBool(rig, &d.m, talking, false));
    for (const MachineChange& c : d.Step()) seen.push_back({k, c.layer, StateName(rig, c.from), StateName(rig, c.to)});
    for (const AnimatorEvent& e : d.ch.Update(1.0 / 60)) {
      const StringView n = rig.channel_rig(e.channel)->event(e.event).name;
      events.push_back(std::string(n.data, n.size) + (e.outgoing ? " (outgoing)" : ""));
    }
    const std::vector<double> x = Morph(rig, d.ch.raw, d.ch.limited);
    for (std::size_t i = 0; k > 0 && i + 1 < x.size(); i += 2)
      largest_move = std::max(largest_move, std::hypot(x[i] - before[i], x[i + 1] - before[i + 1]));
    before = x;
  }
  // The greet played once from frame 30's update reaches its last key 288
  // updates later (at 318: 288 x 1/60 rounds just below 4.8 at 317); the
  // next step takes the exit-time transition.
  const std::vector<Seen> golden = {
      {0, 0, "idle", "idle"},
      {0, 1, "calm", "calm"},
      {30, 0, "idle", "waving"},
      {60, 1, "calm", "chatting"},
      {120, 1, "chatting", "looking-at"},
      {180, 1, "looking-at", "calm"},
      {181, 1, "calm", "chatting"},
      {319, 0, "waving", "idle"},
      {360, 0, "idle", "swaying"},
      {480, 0, "swaying", "idle"},
      {540, 0, "idle", "waving"},
      {570, 0, "waving", "swaying"},
      {660, 1, "chatting", "calm"},
  };
  for (const Seen& s : seen) MESSAGE("frame " << s.frame << " layer " << s.layer << ": " << s.from << " -> " << s.to);
  CHECK(seen == golden);
  // "waving" plays the greet once: its wave at 0.8 s; the second wave is cut
  // short by swaying at 0.5 s, and its wave at 0.8 s comes from the
  // outgoing side of the 0.4 s mix.
  int waves = 0, outgoing_waves = 0;
  for (const std::string& e : events) waves += e == "wave-peak", outgoing_waves += e == "wave-peak (outgoing)";
  CHECK(waves == 1);
  CHECK(outgoing_waves == 1);
  MESSAGE("largest per-frame vertex move over the run: " << largest_move << " rig units");
  CHECK(largest_move < 10);  // the same hand-over cut moves 130 (animator_test.cpp)
}

TEST_CASE("blend and pad states follow their inputs") {
  const Rig rig = LoadTestRig("pell-face");
  Driven d(rig);
  const std::uint32_t sway = Input(rig, "sway"), looking = Input(rig, "looking"), gaze = Input(rig, "gaze");
  d.Step(), d.ch.Update(0);
  // Without the layers' declared behaviours (breath, spring, blink, look-at), which move the points.
  for (std::uint32_t c = 0; c < 2; ++c) REQUIRE(AnimatorSetBehaviours(rig, d.ch.Tracks(), c, Behaviours{}));
  REQUIRE(MachineSetNumber(rig, &d.m, sway, 0.25));
  REQUIRE(MachineSetBool(rig, &d.m, looking, true));
  REQUIRE(MachineSetPoint(rig, &d.m, gaze, 0.3, 0.7));
  for (int k = 0; k < 60; ++k) d.Step(), d.ch.Update(1.0 / 60);  // past both mixes
  double x = 0, y = 0;
  REQUIRE(SamplePath(rig, 0, 0.25 * 4.8, &x, &y));
  CHECK(d.ch.raw == WeightsAt(rig, x, y).raw);
  CHECK(d.ch.ChannelWeights(1) == WeightsAt(*rig.channel_rig(1), 0.3, 0.7).raw);
  REQUIRE(MachineSetNumber(rig, &d.m, sway, 0.75));  // a blend moves at once along its path
  REQUIRE(MachineSetPoint(rig, &d.m, gaze, -0.4, 0.1));
  d.Step(), d.ch.Update(1.0 / 60);
  REQUIRE(SamplePath(rig, 0, 0.75 * 4.8, &x, &y));
  CHECK(d.ch.raw == WeightsAt(rig, x, y).raw);
  CHECK(d.ch.ChannelWeights(1) == WeightsAt(*rig.channel_rig(1), -0.4, 0.1).raw);
}

TEST_CASE("the layers' declared behaviours run from the first step, seeded per character") {
  const Rig rig = LoadTestRig("pell-face");
  const MachineBehavioursView& body = rig.machine_layers()[0].behaviours;
  const MachineBehavioursView& face = rig.machine_layers()[1].behaviours;
  CHECK(body.breath);
  CHECK(body.spring);
  CHECK_FALSE(body.blink);
  CHECK(face.blink);
  CHECK(face.blink_pose == 3);  // "sleepy"
  CHECK(face.look_input == int(Input(rig, "gaze")));
  const std::size_t count = 3;
  Crowd crowd(rig, count, 64);
  std::vector<MachineInstance> machines(count);
  for (MachineInstance& m : machines) REQUIRE(MachineReset(rig, &m));
  REQUIRE(MachineSetPoint(rig, &machines[1], Input(rig, "gaze"), 0.6, -0.2));
  MachineStepJob step;
  step.rig = &rig, step.count = count, step.machines = MakeSpan(machines), step.tracks = MakeSpan(crowd.tracks);
  REQUIRE(step.Run());
  for (std::size_t i = 0; i < count; ++i) {
    const Span<AnimatorTrack> t = crowd.Tracks(i);
    CHECK(t[0].behaviours.breath.enabled);
    CHECK(t[0].behaviours.breath.y == 0.04);
    CHECK(t[0].behaviours.spring.damping == 0.35);
    CHECK(t[1].behaviours.blink.enabled);
    CHECK(t[1].behaviours.blink.seed == face.blink_seed + i);
  }
  CHECK(crowd.Tracks(1)[1].behaviours.look_at.x == 0.6);  // the gaze input, each step
  CHECK(crowd.Tracks(1)[1].behaviours.look_at.y == -0.2);
  // Idle for 12 s: each face blinks (toward "sleepy"), at its own times.
  std::vector<int> first_blink(count, -1);
  for (int f = 0; f < 720; ++f) {
    REQUIRE(step.Run());
    REQUIRE(crowd.Job(1.0 / 60).Run());
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t n = rig.channel_rig(1)->pose_count();
      if (first_blink[i] < 0 && crowd.attached_raw[count * rig.channel_weight_offset(1) + i * n + 3] > 0.9)
        first_blink[i] = f;
    }
  }
  for (std::size_t i = 0; i < count; ++i) CHECK(first_blink[i] >= 0);
  CHECK((first_blink[0] != first_blink[1] || first_blink[1] != first_blink[2]));
}

TEST_CASE("inputs are typed, and any bytes in an instance step to finite weights") {
  const Rig rig = LoadTestRig("pell-face");
  MachineInstance m;
  REQUIRE(MachineReset(rig, &m));
  const std::uint32_t sway = Input(rig, "sway"), talking = Input(rig, "talking"), wave = Input(rig, "wave");
  CHECK_FALSE(MachineSetBool(rig, &m, sway, true));
  CHECK_FALSE(MachineSetNumber(rig, &m, talking, 1));
  CHECK_FALSE(MachineFire(rig, &m, talking));
  CHECK_FALSE(MachineSetPoint(rig, &m, wave, 0, 0));
  CHECK_FALSE(MachineSetBool(rig, &m, 99, true));
  REQUIRE(MachineSetNumber(rig, &m, sway, std::nan("")));
  CHECK(m.values[2 * sway] == 0);
  const Rig plain = LoadTestRig("pell");
  CHECK_FALSE(MachineReset(plain, &m));  // no machine
  std::mt19937_64 rng(3);
  for (int round = 0; round < 300; ++round) {
    Driven d(rig);
    auto* bytes = reinterpret_cast<unsigned char*>(&d.m);
    for (std::size_t i = 0; i < sizeof(MachineInstance); ++i) bytes[i] = static_cast<unsigned char>(rng());
    bool finite = true;
    for (int k = 0; k < 5; ++k) {
      d.Step();
      d.ch.Update(k == 2 ? 1e9 : 0.1);
      for (const auto* v : {&d.ch.raw, &d.ch.limited, &d.ch.attached_raw, &d.ch.attached_limited})
        for (double w : *v) finite = finite && std::isfinite(w);
      for (std::uint32_t l = 0; l < rig.machine_layers().size; ++l) {
        const MachineLayerView& layer = rig.machine_layers()[l];
        CHECK(d.m.state[l] >= layer.first_state);
        CHECK(d.m.state[l] < layer.first_state + layer.state_count);
      }
    }
    REQUIRE(finite);
  }
}

TEST_CASE("a rig whose state machine is hostile is refused at load, naming the problem") {
  const std::vector<unsigned char> bytes = TestRigBytes("pell-face");
  const std::uint64_t mach = SectionOffset(bytes, format::kMachine);
  REQUIRE(mach != 0);
  // Where the entries start, from the header's counts (Pell with a face: 7
  // inputs, 2 layers, 8 states, 12 transitions, 12 conditions, 5 colours).
  const auto h = format::DecodeRecord<format::MachineHeader>(bytes.data() + mach);
  REQUIRE(h.input_count == 7);
  REQUIRE(h.colour_count == 5);
  const std::uint64_t inputs = mach + 24, layers = inputs + h.input_count * 24, states = layers + 2 * 16,
                      transitions = states + h.state_count * 32, conditions = transitions + h.transition_count * 32,
                      behaviours = conditions + h.condition_count * 16, colours = behaviours + 2 * 120,
                      names = colours + h.colour_count * 40;
  auto expect = [&](const std::function<void(unsigned char*)>& mutate, const std::string& problem) {
    ExpectRefused(bytes, mutate, problem);
  };
  expect([&](unsigned char* b) { PutU32(b + mach, 65); }, "MACH counts outside their limits: 65 inputs");
  expect([&](unsigned char* b) { PutU32(b + mach + 4, 3); }, "MACH counts outside their limits");
  expect([&](unsigned char* b) { PutU32(b + mach + 20, 65 * h.state_count + 1); },
         "colours for 8 states, above one per state and part");
  // The colours (format 1.10): the ghost's three parts and its tint, then the fade out.
  expect([&](unsigned char* b) { PutU32(b + colours, 8); }, "MACH colour 0: state 8 of 8");
  expect([&](unsigned char* b) { PutU32(b + colours + 4, 64); }, "MACH colour 0: state 3 of 8, part 64");
  expect([&](unsigned char* b) { PutF64(b + colours + 32, 1.5); }, "MACH colour 0: a component (1.5) outside 0..1");
  expect([&](unsigned char* b) { PutF64(b + colours + 3 * 40 + 8, std::nan("")); },
         "MACH colour 3: a component (nan) outside 0..1");
  expect([&](unsigned char* b) { PutF64(b + colours + 8, 0.5); }, "MACH colour 0: a part's tint is not 1, 1, 1");
  expect([&](unsigned char* b) { PutU32(b + colours + 40 + 4, 0); }, "MACH colour 1: not after colour 0");
  expect([&](unsigned char* b) { PutU32(b + colours + 2 * 40 + 4, 9); },
         "MACH state 3: an opacity for part 9 of a rig with 4");
  expect([&](unsigned char* b) { PutU32(b + inputs, 7); }, "MACH input 0: type 7");
  expect([&](unsigned char* b) { PutF64(b + inputs + 24 + 8, std::nan("")); }, "MACH input 1: default (nan");
  expect([&](unsigned char* b) { PutU32(b + layers + 16, 0); }, "MACH layer 1: channel 0 is not one of 2");
  expect([&](unsigned char* b) { PutU32(b + layers + 8, 5); }, "MACH layer 0: 5 states (initial 5)");
  expect([&](unsigned char* b) { PutU32(b + states + 32, 9); }, "MACH state 1: kind 9");
  expect([&](unsigned char* b) { PutU32(b + states + 2 * 32 + 8, 2); }, "MACH state 2: input 2 is not a number input");
  expect([&](unsigned char* b) { PutF64(b + states + 32 + 16, -1); }, "MACH state 1: speed -1");
  expect([&](unsigned char* b) { PutU32(b + states + 32 + 4, 7); }, "MACH state 1: path 7 of channel 0, which has 1");
  expect([&](unsigned char* b) { PutU32(b + transitions, 5); },
         "MACH transition 0: target state 5 is not in its layer");
  expect([&](unsigned char* b) { PutF64(b + transitions + 16, std::nan("")); }, "MACH transition 0: mix nan");
  expect([&](unsigned char* b) { PutU32(b + transitions + 8, 1); },
         "MACH transition 0: an exit time on a state that plays no path");
  expect([&](unsigned char* b) { PutU32(b + conditions + 4, 0); },  // "is true" of a number
         "MACH condition 0: operator 0 does not apply to input 1's type 1");
  expect([&](unsigned char* b) { PutU32(b + conditions, 40); }, "MACH condition 0: input 40 of 7");
  expect([&](unsigned char* b) { PutU32(b + behaviours, 16); }, "MACH layer 0's behaviours: unknown bits");
  expect([&](unsigned char* b) { PutF64(b + behaviours + 8, std::nan("")); },
         "MACH layer 0's behaviours: a parameter (nan) beyond 1e6");
  expect([&](unsigned char* b) { PutU32(b + behaviours + 120 + 72, 1); },
         "MACH layer 1's behaviours: look-at input 1 is not a point input");
  expect([&](unsigned char* b) { PutU32(b + behaviours + 120 + 4, 9); },
         "MACH layer 1's behaviours: blink pose 9 of channel 1, which has 4");
  expect([&](unsigned char* b) { PutU32(b + names, 200); }, "MACH name 0 is 200 bytes");
  expect([&](unsigned char* b) { PutU32(b + names, 0); }, "MACH name 0 is 0 bytes");
}
