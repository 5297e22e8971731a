// SPDX-License-Identifier: MIT
// The Animator (animator.h): events crossed exactly once, in time order,
// against a reference computed from the playhead alone, under random dt
// sequences, loop wraps, speed changes, queues and mixes; mixes without a
// jump; hostile tracks and dt giving finite weights; the same bits for a
// batch as for characters one by one.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "posemorph/animator.h"
#include "posemorph/path.h"
#include "posemorph/rig_format.h"
#include "animator_support.h"
#include "runtime_support.h"

using namespace posemorph;
using namespace posemorph::test;

namespace {

struct Crossing {
  std::uint32_t channel, event;
  bool outgoing;
  double time;  // global seconds
};

// A path's crossings over a playhead that runs from `p0` (unwrapped, path
// clock) at `speed` from global time `g0` to `g1`: every event occurrence
// e + k x period in [p0, p0 + speed (g1 - g0)), by brute force over cycles.
void PathCrossings(const Rig& crig, std::uint32_t channel, std::uint32_t path, double p0, double speed, double g0,
                   double g1, bool outgoing, std::vector<Crossing>* out) {
  const PathView p = crig.path(path);
  const double period = p.end_time() - p.start_time();
  const double p1 = p0 + speed * (g1 - g0);
  const std::uint32_t base = std::uint32_t(p.events.data - crig.events().data);
  for (long cycle = -1; p.start_time() + cycle * period <= p1; ++cycle)
    for (std::size_t j = 0; j < p.events.size; ++j) {
      const double u = p.events[j].time + cycle * period;
      if (u >= p0 && u < p1) out->push_back({channel, base + std::uint32_t(j), outgoing, g0 + (u - p0) / speed});
    }
}

void SortCrossings(std::vector<Crossing>* c) {
  std::stable_sort(c->begin(), c->end(), [](const Crossing& a, const Crossing& b) {
    if (a.time != b.time) return a.time < b.time;
    if (a.channel != b.channel) return a.channel < b.channel;
    return a.outgoing && !b.outgoing;
  });
}

// Runs `dts`, issuing `command(update index, global time)` before each
// update; returns every event with its global time.
template <typename Command>
std::vector<Crossing> Run(Character& ch, const std::vector<double>& dts, Command command) {
  std::vector<Crossing> got;
  double now = 0;
  for (std::size_t k = 0; k < dts.size(); ++k) {
    command(k, now);
    for (const AnimatorEvent& e : ch.Update(dts[k])) {
      CHECK(e.time >= 0);
      CHECK(e.time <= dts[k]);
      got.push_back({e.channel, e.event, e.outgoing, now + e.time});
    }
    now += dts[k];
  }
  return got;
}

// The same crossings in the same order; crossings within `tolerance` of
// each other (two channels' events that coincide, such as 3 x 4.8 s and 4 x
// 3.6 s) may come in either order, as rounding puts them.
void CheckSame(const std::vector<Crossing>& got, const std::vector<Crossing>& expected, double tolerance) {
  REQUIRE(got.size() == expected.size());
  std::vector<bool> used(expected.size(), false);
  for (std::size_t i = 0; i < got.size(); ++i) {
    CAPTURE(i);
    bool found = false;
    for (std::size_t j = i >= 3 ? i - 3 : 0; j < std::min(expected.size(), i + 4) && !found; ++j) {
      const Crossing& e = expected[j];
      if (used[j] || got[i].channel != e.channel || got[i].event != e.event || got[i].outgoing != e.outgoing ||
          !(std::fabs(got[i].time - e.time) <= tolerance))
        continue;
      // Anything expected before it that is still unmatched must tie with it.
      for (std::size_t k = 0; k < j; ++k)
        if (!used[k]) CHECK(std::fabs(expected[k].time - e.time) <= tolerance);
      used[j] = found = true;
    }
    CHECK_MESSAGE(found, "crossing " << i << ": channel " << got[i].channel << " event " << got[i].event << " at "
                                     << got[i].time << "; expected " << expected[i].channel << " " << expected[i].event
                                     << " at " << expected[i].time);
  }
}

std::vector<double> RandomSteps(std::mt19937_64& rng, double total) {
  std::uniform_real_distribution<double> small(0, 0.25), large(0, 7);
  std::vector<double> dts;
  double sum = 0;
  while (sum < total) {
    const int kind = int(rng() % 10);
    const double dt = kind == 0 ? 0.0 : kind == 1 ? large(rng) : small(rng);
    dts.push_back(dt);
    sum += dt;
  }
  return dts;
}

double Sum(const std::vector<double>& v, std::size_t n) {
  double s = 0;
  for (std::size_t i = 0; i < n; ++i) s += v[i];
  return s;
}

}  // namespace

TEST_CASE("the rig stores its paths' events, sorted by time, each run on its path") {
  const Rig rig = LoadTestRig("pell-face");
  REQUIRE(rig.channel_count() == 2);
  const Rig& face = *rig.channel_rig(1);
  REQUIRE(rig.event_count() == 4);
  REQUIRE(face.event_count() == 5);
  const PathView greet = rig.path(0), chatter = face.path(0);
  REQUIRE(greet.events.size == 4);
  CHECK(std::string(greet.events[0].name.data, greet.events[0].name.size) == "wave-peak");
  CHECK(greet.events[3].time == 4.8);
  REQUIRE(chatter.events.size == 5);
  // Two events at 1.8 keep the description's order.
  CHECK(std::string(chatter.events[2].name.data, chatter.events[2].name.size) == "gasp");
  CHECK(std::string(chatter.events[3].name.data, chatter.events[3].name.size) == "blink");
  for (std::size_t i = 1; i < chatter.events.size; ++i) CHECK(chatter.events[i].time >= chatter.events[i - 1].time);
  const Rig compact = LoadTestRig("pell-face.compact");
  CHECK(compact.channel_rig(1)->event_count() == 5);
  CHECK(compact.path(0).events.size == 4);
}

TEST_CASE("looping paths on two channels report every crossing once, in time order, for random dt") {
  const Rig rig = LoadTestRig("pell-face");
  const Rig& face = *rig.channel_rig(1);
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 40; ++trial) {
    CAPTURE(trial);
    Character ch(rig);
    const std::vector<double> dts = RandomSteps(rng, 40);
    // Speeds change at two updates; the reference follows the playhead.
    const std::size_t change_a = dts.size() / 3, change_b = 2 * dts.size() / 3;
    const double speeds[3] = {1.0, 2.5, 0.4};
    const auto got = Run(ch, dts, [&](std::size_t k, double) {
      PlayOptions o;
      o.mix = 0;
      if (k == 0) {
        REQUIRE(AnimatorPlay(rig, ch.Tracks(), 0, 0, o));
        REQUIRE(AnimatorPlay(rig, ch.Tracks(), 1, 0, o));
      }
      if (k == change_a) AnimatorSetSpeed(rig, ch.Tracks(), 1, speeds[1]);
      if (k == change_b) AnimatorSetSpeed(rig, ch.Tracks(), 1, speeds[2]);
    });
    std::vector<Crossing> expected;
    const double total = Sum(dts, dts.size()), ga = Sum(dts, change_a), gb = Sum(dts, change_b);
    PathCrossings(rig, 0, 0, 0, 1, 0, total, false, &expected);
    PathCrossings(face, 1, 0, 0, speeds[0], 0, ga, false, &expected);
    PathCrossings(face, 1, 0, ga * speeds[0], speeds[1], ga, gb, false, &expected);
    PathCrossings(face, 1, 0, ga * speeds[0] + (gb - ga) * speeds[1], speeds[2], gb, total, false, &expected);
    SortCrossings(&expected);
    CHECK(expected.size() > 60);
    CheckSame(got, expected, 1e-9);
  }
}

TEST_CASE("a path played once reports its events up to and including its last key, then a queued one takes over") {
  const Rig rig = LoadTestRig("pell-face");
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 40; ++trial) {
    CAPTURE(trial);
    Character ch(rig);
    const std::vector<double> dts = RandomSteps(rng, 14);
    const auto got = Run(ch, dts, [&](std::size_t k, double) {
      if (k != 0) return;
      PlayOptions once;
      once.loop = 0;
      once.mix = 0;
      REQUIRE(AnimatorPlay(rig, ch.Tracks(), 0, 0, once));
      REQUIRE(AnimatorQueue(rig, ch.Tracks(), 0, 0, once));
    });
    // Two plays of "greet" (4.8 s), back to back; each reports its four
    // events once, "cycle" (at the last key) included.
    std::vector<Crossing> expected;
    for (int play = 0; play < 2; ++play)
      for (std::uint32_t j = 0; j < 4; ++j) expected.push_back({0, j, false, 4.8 * play + rig.event(j).time});
    CheckSame(got, expected, 1e-9);
    CHECK(ch.tracks[0].current.ended);
  }
}

TEST_CASE("during a mix both gestures report their events, the outgoing one until at the mix's end") {
  const Rig rig = LoadTestRig("pell-face");
  const Rig& face = *rig.channel_rig(1);
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 40; ++trial) {
    CAPTURE(trial);
    Character ch(rig);
    const std::vector<double> dts = RandomSteps(rng, 30);
    const std::size_t at = dts.size() / 2;
    const double mix = 1.7;
    const auto got = Run(ch, dts, [&](std::size_t k, double) {
      PlayOptions o;
      o.mix = 0;
      if (k == 0) REQUIRE(AnimatorPlay(rig, ch.Tracks(), 1, 0, o));
      if (k == at) {
        o.mix = mix;
        o.speed = 2;
        o.start = 0.3;
        REQUIRE(AnimatorPlay(rig, ch.Tracks(), 1, 0, o));
      }
    });
    const double g = Sum(dts, at), total = Sum(dts, dts.size());
    std::vector<Crossing> expected;
    PathCrossings(face, 1, 0, 0, 1, 0, g, false, &expected);
    PathCrossings(face, 1, 0, g, 1, g, std::min(total, g + mix), true, &expected);
    PathCrossings(face, 1, 0, 0.3, 2, g, total, false, &expected);
    SortCrossings(&expected);
    CheckSame(got, expected, 1e-9);
  }
}

TEST_CASE("a full event buffer keeps the first crossings in order and counts the rest") {
  const Rig rig = LoadTestRig("pell-face");
  Character ch(rig, 7);
  PlayOptions o;
  o.mix = 0;
  REQUIRE(AnimatorPlay(rig, ch.Tracks(), 1, 0, o));
  std::uint64_t missed = 0;
  // 35 s of a 3.6 s loop with 5 events (the tenth cycle's last, at 35.4 s, is not reached): 49 crossings.
  const auto got = ch.Update(35.0, &missed);
  REQUIRE(got.size() == 7);
  CHECK(missed == 42);
  for (std::size_t i = 1; i < got.size(); ++i) CHECK(got[i].time >= got[i - 1].time);
  CHECK(got[0].event == 0);
  CHECK(got[5].event == 0);  // the second cycle's first
  // A dt of 1e9 s is bounded: seven written, the rest counted.
  ch.Update(1e9, &missed);
  CHECK(missed > 1000000000ull);
}

TEST_CASE("a mix hands over without a jump: no per-frame move beyond the larger of the two gestures'") {
  const Rig rig = LoadTestRig("pell-face");
  const double frame = 1.0 / 60;
  const std::size_t V2 = 2 * std::size_t(rig.vertex_count());
  // The body's positions at the animator's weights.
  auto positions = [&](Character& ch) { return Morph(rig, ch.raw, ch.limited); };
  auto max_move = [&](const std::vector<double>& a, const std::vector<double>& b) {
    double m = 0;
    for (std::size_t i = 0; i + 1 < V2; i += 2) m = std::max(m, std::hypot(a[i] - b[i], a[i + 1] - b[i + 1]));
    return m;
  };
  // Each gesture alone: "greet" at speed 1 from 0 and at speed 1.3 from 2.0.
  auto gesture_max = [&](double speed, double start) {
    Character ch(rig);
    PlayOptions o;
    o.mix = 0, o.speed = speed, o.start = start;
    AnimatorPlay(rig, ch.Tracks(), 0, 0, o);
    ch.Update(0);
    std::vector<double> before = positions(ch);
    double m = 0;
    for (int f = 0; f < int(4.8 / speed / frame) + 2; ++f) {
      ch.Update(frame);
      const std::vector<double> now = positions(ch);
      m = std::max(m, max_move(before, now));
      before = now;
    }
    return m;
  };
  const double own = std::max(gesture_max(1, 0), gesture_max(1.3, 2.0));
  auto handover_max = [&](double mix) {
    Character ch(rig);
    PlayOptions o;
    o.mix = 0;
    AnimatorPlay(rig, ch.Tracks(), 0, 0, o);
    for (int f = 0; f < 30; ++f) ch.Update(frame);  // at 0.5 s: moving toward "wave"
    std::vector<double> before = positions(ch);
    o.mix = mix, o.speed = 1.3, o.start = 2.0;
    AnimatorPlay(rig, ch.Tracks(), 0, 0, o);
    double m = 0;
    for (int f = 0; f < int(mix / frame) + 2; ++f) {
      ch.Update(frame);
      const std::vector<double> now = positions(ch);
      m = std::max(m, max_move(before, now));
      before = now;
    }
    return m;
  };
  const double mixed = handover_max(0.8), cut = handover_max(0);
  MESSAGE("largest per-frame move: gestures alone " << own << ", during a 0.8 s mix " << mixed << ", cut " << cut);
  CHECK(mixed <= own);
  CHECK(cut > 3 * own);  // the measure sees a jump: cutting moves far more in one frame
}

TEST_CASE("interrupting a mix freezes its blend and mixes from it, without a jump") {
  const Rig rig = LoadTestRig("pell-face");
  Character ch(rig);
  PlayOptions o;
  o.mix = 0;
  AnimatorPlay(rig, ch.Tracks(), 0, 0, o);
  ch.Update(0.5);
  o.mix = 1.0, o.start = 2.4;
  AnimatorPlay(rig, ch.Tracks(), 0, 0, o);
  ch.Update(0.4);
  const std::vector<double> before = ch.raw;
  // A pad interrupts the mix: the next update starts from the frozen blend.
  REQUIRE(AnimatorSetPoint(rig, ch.Tracks(), 0, -1, 0, 0.5));
  ch.Update(0);
  CHECK(ch.tracks[0].from.kind == MotionKind::kSnapshot);
  for (std::size_t i = 0; i < before.size(); ++i) CHECK(ch.raw[i] == doctest::Approx(before[i]).epsilon(1e-12));
  ch.Update(0.25);
  ch.Update(0.25);
  CHECK_FALSE(ch.tracks[0].mixing);
  const Weights pad = WeightsAt(rig, -1, 0);
  for (std::size_t i = 0; i < pad.raw.size(); ++i) CHECK(ch.raw[i] == pad.raw[i]);
  // The pad moves at once (no mix) while it is followed.
  REQUIRE(AnimatorSetPoint(rig, ch.Tracks(), 0, 1, 0, 0.5));
  ch.Update(0.01);
  const Weights wave = WeightsAt(rig, 1, 0);
  for (std::size_t i = 0; i < wave.raw.size(); ++i) CHECK(ch.raw[i] == wave.raw[i]);
}

TEST_CASE("weights during a mix are a partition of unity on both channels") {
  const Rig rig = LoadTestRig("pell-face");
  Character ch(rig);
  PlayOptions o;
  AnimatorPlay(rig, ch.Tracks(), 0, 0, o);
  AnimatorPlay(rig, ch.Tracks(), 1, 0, o);
  for (int f = 0; f < 200; ++f) {
    if (f % 37 == 0) AnimatorSetPoint(rig, ch.Tracks(), f % 2, 0.3 * f, -0.5, 0.6);
    if (f % 53 == 0) AnimatorPlay(rig, ch.Tracks(), 1, 0, o);
    if (f % 71 == 0) AnimatorStop(rig, ch.Tracks(), 0, 0.4);
    ch.Update(1.0 / 30);
    double sum = 0, tex = 0, face = 0;
    for (double w : ch.raw) sum += w;
    for (double w : ch.texture) {
      tex += w;
      CHECK(w >= 0);
    }
    for (double w : ch.attached_raw) face += w;
    CHECK(sum == doctest::Approx(1).epsilon(1e-12));
    CHECK(tex == doctest::Approx(1).epsilon(1e-12));
    CHECK(face == doctest::Approx(1).epsilon(1e-12));
  }
}

TEST_CASE("hostile dt, speeds, points and track bytes give finite weights") {
  const Rig rig = LoadTestRig("pell-face");
  const double inf = HUGE_VAL, nan = std::nan("");
  Character ch(rig);
  PlayOptions o;
  o.speed = nan, o.mix = -3, o.start = inf;
  REQUIRE(AnimatorPlay(rig, ch.Tracks(), 0, 0, o));
  o.speed = inf, o.mix = nan;
  REQUIRE(AnimatorPlay(rig, ch.Tracks(), 1, 0, o));
  CHECK_FALSE(AnimatorPlay(rig, ch.Tracks(), 2, 0, o));  // no channel 2
  CHECK_FALSE(AnimatorPlay(rig, ch.Tracks(), 0, 1, o));  // no path 1
  CHECK_FALSE(AnimatorPlay(rig, ch.Tracks().subspan(0, 1), 0, 0, o));
  auto finite = [&] {
    for (const auto* v : {&ch.raw, &ch.limited, &ch.texture, &ch.attached_raw, &ch.attached_limited})
      for (double w : *v) REQUIRE(std::isfinite(w));
  };
  for (double dt : {nan, -1.0, 0.0, 1e9, inf, -inf, 1e-300, 3.0}) {
    CAPTURE(dt);
    ch.Update(dt);
    finite();
  }
  // A NaN dt counts as 0: nothing moves.
  const std::vector<double> before = ch.attached_raw;
  ch.Update(nan);
  CHECK(ch.attached_raw == before);
  AnimatorSetPoint(rig, ch.Tracks(), 0, nan, inf, nan);
  ch.Update(0.1);
  finite();
  // Random values in every field of the tracks (as a track from a peer
  // could hold): numbers as random bit patterns, kinds and indices out of range.
  std::mt19937_64 rng(3);
  auto number = [&] {
    const std::uint64_t bits = rng();
    double v;
    std::memcpy(&v, &bits, sizeof v);
    const int pick = int(rng() % 6);
    return pick == 0 ? v : pick == 1 ? nan : pick == 2 ? inf : pick == 3 ? -1e300 : double(rng() % 100) / 7 - 3;
  };
  auto motion = [&](Motion* m) {
    m->kind = MotionKind(rng() % 6);
    m->loop = rng() % 2, m->ended = rng() % 2;
    m->path = std::uint32_t(rng() % 3);
    m->time = number(), m->speed = number(), m->x = number(), m->y = number();
  };
  for (int trial = 0; trial < 300; ++trial) {
    for (AnimatorTrack& t : ch.tracks) {
      motion(&t.current), motion(&t.from), motion(&t.pending), motion(&t.queued);
      t.mixing = rng() % 2, t.has_pending = rng() % 2, t.has_queued = rng() % 2;
      t.mix_elapsed = number(), t.mix_duration = number(), t.pending_mix = number(), t.queued_mix = number();
      for (double& v : t.snapshot) v = rng() % 3 ? number() : 0.25;
    }
    ch.Update(trial % 2 ? 0.05 : 1e3);
    finite();
  }
}

TEST_CASE("a batch gives every character the bits it gets alone, and the same run gives the same bits") {
  const Rig rig = LoadTestRig("pell-face");
  const std::size_t count = 5, C = rig.channel_count(), N = rig.pose_count(), A = rig.attached_weight_count();
  std::vector<Character> alone;
  for (std::size_t i = 0; i < count; ++i) alone.emplace_back(rig);
  std::vector<AnimatorTrack> tracks(count * C);
  REQUIRE(AnimatorReset(rig, Span<AnimatorTrack>{tracks.data(), C}));
  for (std::size_t i = 1; i < count; ++i)
    for (std::size_t c = 0; c < C; ++c) tracks[i * C + c] = tracks[c];
  std::vector<double> raw(count * N), limited(count * N), ar(count * A), al(count * A);
  std::vector<AnimatorEvent> events(256);
  for (int f = 0; f < 120; ++f) {
    for (std::size_t i = 0; i < count; ++i) {
      if (f % (11 + int(i)) == 0) {
        PlayOptions o;
        o.speed = 0.5 + 0.25 * double(i), o.mix = 0.3, o.start = 0.1 * f;
        for (std::uint32_t c = 0; c < C; ++c) {
          AnimatorPlay(rig, alone[i].Tracks(), c, 0, o);
          AnimatorPlay(rig, Span<AnimatorTrack>{tracks.data() + i * C, C}, c, 0, o);
        }
      }
    }
    const double dt = 0.01 + 0.001 * (f % 7);
    std::vector<std::vector<AnimatorEvent>> single;
    for (Character& ch : alone) single.push_back(ch.Update(dt));
    AnimatorUpdateJob job;
    job.rig = &rig;
    job.count = count;
    job.dt = dt;
    job.tracks = MakeSpan(tracks);
    job.weights = MakeSpan(raw), job.limited_weights = MakeSpan(limited);
    job.attached_weights = MakeSpan(ar), job.attached_limited_weights = MakeSpan(al);
    job.events = MakeSpan(events);
    std::size_t n = 0;
    std::uint64_t missed = 0;
    job.event_count = &n, job.events_missed = &missed;
    REQUIRE(job.Run());
    std::size_t k = 0;
    for (std::size_t i = 0; i < count; ++i) {
      CHECK(std::memcmp(raw.data() + i * N, alone[i].raw.data(), N * sizeof(double)) == 0);
      CHECK(std::memcmp(limited.data() + i * N, alone[i].limited.data(), N * sizeof(double)) == 0);
      // AttachJob's layout: channel by channel, count x that channel's poses.
      for (std::uint32_t c = 1; c < C; ++c) {
        const std::size_t nc = rig.channel_rig(c)->pose_count(), off = rig.channel_weight_offset(c);
        CHECK(std::memcmp(ar.data() + count * off + i * nc, alone[i].attached_raw.data() + off, nc * sizeof(double)) ==
              0);
      }
      for (const AnimatorEvent& e : single[i]) {
        REQUIRE(k < n);
        CHECK(events[k].character == i);
        CHECK(events[k].event == e.event);
        CHECK(events[k].time == e.time);
        ++k;
      }
    }
    CHECK(k == n);
  }
}

TEST_CASE("an update job refuses spans that are too short and does nothing") {
  const Rig rig = LoadTestRig("pell-face");
  Character ch(rig);
  AnimatorUpdateJob job;
  job.rig = &rig;
  job.tracks = ch.Tracks();
  job.weights = MakeSpan(ch.raw), job.limited_weights = MakeSpan(ch.limited);
  job.attached_weights = MakeSpan(ch.attached_raw), job.attached_limited_weights = MakeSpan(ch.attached_limited);
  CHECK(job.Validate());
  AnimatorUpdateJob bad = job;
  bad.tracks = ch.Tracks().subspan(0, 1);
  CHECK_FALSE(bad.Run());
  bad = job;
  bad.attached_weights = {};
  CHECK_FALSE(bad.Validate());
  bad = job;
  bad.count = 2;
  CHECK_FALSE(bad.Validate());
  bad = job;
  bad.events = MakeSpan(ch.buffer);  // without event_count and events_missed
  CHECK_FALSE(bad.Validate());
  bad = job;
  bad.rig = nullptr;
  CHECK_FALSE(bad.Validate());
  Rig empty;
  bad.rig = &empty;
  CHECK_FALSE(bad.Validate());
}

TEST_CASE("a rig whose events are hostile is refused at load, naming the event and the problem") {
  const std::vector<unsigned char> bytes = TestRigBytes("pell-face");
  const std::uint64_t evnt = SectionOffset(bytes, format::kEvents), meta = SectionOffset(bytes, format::kMeta);
  REQUIRE(evnt != 0);
  auto expect = [&](const std::function<void(unsigned char*)>& mutate, const std::string& problem) {
    ExpectRefused(bytes, mutate, problem);
  };
  expect([&](unsigned char* b) { PutU32(b + evnt + 8, 5); }, "event 0 names path 5; the rig has 1");
  expect([&](unsigned char* b) { PutF64(b + evnt, std::nan("")); }, "event 0 at time nan, outside its path 0's keys");
  expect([&](unsigned char* b) { PutF64(b + evnt + 16, 9.0); },
         "event 1 at time 9, outside its path 0's keys [0, 4.8]");
  expect([&](unsigned char* b) { PutF64(b + evnt + 16, 0.1); }, "event 1 is out of order");
  expect([&](unsigned char* b) { PutU32(b + evnt + 12, 1); }, "event 0: reserved field is not zero");
  expect(
      [&](unsigned char* b) {
        std::uint32_t flags;
        std::memcpy(&flags, b + meta + 28, 4);
        PutU32(b + meta + 28, flags & ~format::kMetaFlagEvents);
      },
      "EVNT section present but META says the paths have no events");
}
