// SPDX-License-Identifier: MIT
// An animator's state for late joiners (animator.h: AnimatorSave,
// AnimatorLoad): a peer that loads what another saved, at any moment (mid
// mix, a frozen blend, a command not yet applied, a queue, every
// behaviour running), continues with the same bits and the same events;
// the sizes are as documented; hostile bytes are refused without a change,
// or give finite weights.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "animator_support.h"
#include "posemorph/animator.h"
#include "runtime_support.h"

using namespace posemorph;
using namespace posemorph::test;

namespace {

void DeclareEverything(const Rig& rig, Span<AnimatorTrack> t) {
  Behaviours b;
  b.blink.enabled = b.breath.enabled = b.look_at.enabled = b.spring.enabled = true;
  b.blink.pose = 3, b.blink.interval = 0.6, b.breath.y = 0.04, b.look_at.strength = 0.6;
  for (std::uint32_t c = 0; c < rig.channel_count(); ++c) REQUIRE(AnimatorSetBehaviours(rig, t, c, b));
}

// The commands of update k (the same for every peer that runs them).
void Commands(const Rig& rig, Span<AnimatorTrack> t, int k) {
  PlayOptions o;
  o.mix = 0.1 + 0.05 * (k % 7), o.speed = 0.6 + 0.1 * (k % 5), o.start = 0.3 * (k % 11);
  if (k % 23 == 0) AnimatorPlay(rig, t, 0, 0, o);
  if (k % 23 == 4) AnimatorPlay(rig, t, 0, 0, o);  // interrupts: a frozen blend
  if (k % 31 == 9) AnimatorQueue(rig, t, 0, 0, o);
  if (k % 19 == 3) AnimatorPlay(rig, t, 1, 0, o);
  if (k % 29 == 12) AnimatorSetPoint(rig, t, 1, 0.2 * (k % 5), 0.5, 0.2);
  if (k % 37 == 20) AnimatorStop(rig, t, 0, 0.3);
  if (k % 13 == 6) AnimatorLookAt(rig, t, 1, std::cos(0.3 * k), std::sin(0.3 * k));
  if (k % 41 == 17) AnimatorSetSpeed(rig, t, 0, 1.7);
}

double Step(int k) { return k % 97 == 50 ? 3.0 : k % 11 == 5 ? 0.0 : 1.0 / (30 + (k * 7) % 115); }

std::vector<unsigned char> Save(const Rig& rig, Character& ch) {
  std::vector<unsigned char> bytes(AnimatorStateSize(rig, ch.Tracks()));
  std::size_t written = 0;
  REQUIRE(AnimatorSave(rig, ch.Tracks(), MakeSpan(bytes), &written));
  REQUIRE(written == bytes.size());
  return bytes;
}

bool Same(const Character& a, const Character& b) {
  auto same = [](const std::vector<double>& x, const std::vector<double>& y) {
    return std::memcmp(x.data(), y.data(), x.size() * sizeof(double)) == 0;
  };
  return same(a.raw, b.raw) && same(a.limited, b.limited) && same(a.texture, b.texture) &&
         same(a.attached_raw, b.attached_raw) && same(a.attached_limited, b.attached_limited) &&
         same(a.attached_texture, b.attached_texture);
}

}  // namespace

TEST_CASE("a late joiner that loads a saved state continues with the same bits and events") {
  const Rig rig = LoadTestRig("pell-face");
  Character a(rig);
  DeclareEverything(rig, a.Tracks());
  std::size_t largest = 0;
  int checked = 0;
  for (int k = 0; k < 400; ++k) {
    Commands(rig, a.Tracks(), k);
    // Save before the update: this frame's commands are still pending.
    if (k % 37 == 4 || k % 23 == 4) {
      const std::vector<unsigned char> bytes = Save(rig, a);
      largest = std::max(largest, bytes.size());
      Character b(rig);
      REQUIRE(AnimatorLoad(rig, MakeSpan(bytes), b.Tracks()));
      Character a2(rig);  // the saver's own continuation, on a copy
      a2.tracks = a.tracks;
      bool same = true, same_events = true;
      for (int j = k; j < k + 60; ++j) {
        if (j > k) Commands(rig, a2.Tracks(), j), Commands(rig, b.Tracks(), j);
        const std::vector<AnimatorEvent> ea = a2.Update(Step(j)), eb = b.Update(Step(j));
        same = same && Same(a2, b);
        same_events = same_events && ea.size() == eb.size();
        for (std::size_t e = 0; same_events && e < ea.size(); ++e)
          same_events = ea[e].channel == eb[e].channel && ea[e].event == eb[e].event &&
                        ea[e].outgoing == eb[e].outgoing && ea[e].time == eb[e].time;
      }
      CAPTURE(k);
      CHECK(same);
      CHECK(same_events);
      ++checked;
    }
    a.Update(Step(k));
  }
  MESSAGE(checked << " joins checked; largest state " << largest << " bytes");
  CHECK(checked >= 20);
  CHECK(largest <= 5 + rig.channel_count() * kMaxAnimatorStateBytesPerChannel);
}

TEST_CASE("state sizes are as documented") {
  const Rig rig = LoadTestRig("pell-face");
  Character ch(rig);
  CHECK(Save(rig, ch).size() == 5 + 2 + 2);  // two stopped channels
  PlayOptions o;
  o.mix = 0;
  REQUIRE(AnimatorPlay(rig, ch.Tracks(), 0, 0, o));
  ch.Update(0.1);
  CHECK(Save(rig, ch).size() == 5 + 30 + 18);  // a path at speed 1; a stopped channel whose clock runs
  o.mix = 0.5;
  REQUIRE(AnimatorPlay(rig, ch.Tracks(), 0, 0, o));
  ch.Update(0.1);
  CHECK(Save(rig, ch).size() == 5 + (30 + 13 + 16) + 18);  // + the motion it mixes from and the mix
  REQUIRE(AnimatorPlay(rig, ch.Tracks(), 0, 0, o));
  ch.Update(0.1);
  const std::size_t N = rig.pose_count();
  CHECK(Save(rig, ch).size() == 5 + (30 + 17 + 16 + 24 * N) + 18);  // a frozen blend: 24 bytes a pose
  Character fresh(rig);
  Behaviours b;
  b.spring.enabled = b.breath.enabled = true;
  REQUIRE(AnimatorSetBehaviours(rig, fresh.Tracks(), 0, b));
  fresh.Update(0.1);
  // flags, rest, clock; masks, 2 x 3 parameters, breath origin, spring and lag.
  CHECK(Save(rig, fresh).size() == 5 + (2 + 16 + 2 + 48 + 8 + 64) + 18);
}

TEST_CASE("a hostile state is refused without a change, or gives finite weights") {
  const Rig rig = LoadTestRig("pell-face");
  Character a(rig);
  DeclareEverything(rig, a.Tracks());
  for (int k = 0; k < 28; ++k) Commands(rig, a.Tracks(), k), a.Update(Step(k));
  Commands(rig, a.Tracks(), 23 * 4 + 4);  // a command pending
  const std::vector<unsigned char> good = Save(rig, a);
  Character b(rig);
  const std::vector<AnimatorTrack> before = b.tracks;
  auto unchanged = [&] {
    return std::memcmp(b.tracks.data(), before.data(), before.size() * sizeof(AnimatorTrack)) == 0;
  };
  for (std::size_t n = 0; n < good.size(); ++n) {
    CAPTURE(n);
    REQUIRE_FALSE(AnimatorLoad(rig, Span<const unsigned char>{good.data(), n}, b.Tracks()));
  }
  CHECK(unchanged());
  std::vector<unsigned char> longer = good;
  longer.push_back(0);
  CHECK_FALSE(AnimatorLoad(rig, MakeSpan(longer), b.Tracks()));
  std::vector<unsigned char> bad = good;
  bad[3] = 2;  // version
  CHECK_FALSE(AnimatorLoad(rig, MakeSpan(bad), b.Tracks()));
  bad = good, bad[4] = 3;  // channels
  CHECK_FALSE(AnimatorLoad(rig, MakeSpan(bad), b.Tracks()));
  bad = good, bad[5] |= 0x80;  // a reserved flag
  CHECK_FALSE(AnimatorLoad(rig, MakeSpan(bad), b.Tracks()));
  CHECK_FALSE(AnimatorLoad(rig, MakeSpan(good), Span<AnimatorTrack>{b.tracks.data(), 1}));  // too few tracks
  CHECK(unchanged());
  std::mt19937_64 rng(9);
  int loaded = 0, refused = 0;
  for (int round = 0; round < 2000; ++round) {
    bad = good;
    for (int flips = 1 + int(rng() % 4); flips > 0; --flips) bad[rng() % bad.size()] ^= std::uint8_t(1u << (rng() % 8));
    Character c(rig);
    const std::vector<AnimatorTrack> c_before = c.tracks;
    if (!AnimatorLoad(rig, MakeSpan(bad), c.Tracks())) {
      ++refused;
      REQUIRE(std::memcmp(c.tracks.data(), c_before.data(), c_before.size() * sizeof(AnimatorTrack)) == 0);
      continue;
    }
    ++loaded;
    bool finite = true;
    for (double dt : {1.0 / 60, 0.5, 1e9}) {
      c.Update(dt);
      for (const auto* v : {&c.raw, &c.limited, &c.texture, &c.attached_raw, &c.attached_limited})
        for (double x : *v) finite = finite && std::isfinite(x);
    }
    REQUIRE(finite);
  }
  MESSAGE("2000 mutated states: " << loaded << " loaded (finite weights), " << refused << " refused");
  CHECK(loaded > 0);
  CHECK(refused > 0);
}
