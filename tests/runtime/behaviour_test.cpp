// SPDX-License-Identifier: MIT
// The Animator's behaviours (animator.h: blink, breath, look-at, spring):
// the pose at a time does not depend on the update rate; the spring
// overshoots and settles as a damped spring does; breath is the offset it
// declares; blinks come at their jittered intervals, the same for the same
// seed; look-at closes its gap over its smoothing time; hostile parameters,
// states and steps give finite weights.
#include <algorithm>
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

constexpr double kPi = 3.14159265358979323846;

double MaxDifference(const std::vector<double>& a, const std::vector<double>& b) {
  REQUIRE(a.size() == b.size());
  double m = 0;
  for (std::size_t i = 0; i < a.size(); ++i) m = std::max(m, std::fabs(a[i] - b[i]));
  return m;
}

double Sum(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s;
}

// The sample's behaviours: a springy, breathing body; a face that blinks
// toward "sleepy" and looks at a target.
void DeclareBehaviours(const Rig& rig, Span<AnimatorTrack> tracks, std::uint64_t seed) {
  Behaviours body;
  body.spring.enabled = true;
  body.spring.frequency = 2.5, body.spring.damping = 0.3;
  body.breath.enabled = true;
  body.breath.period = 3, body.breath.y = 0.05;
  REQUIRE(AnimatorSetBehaviours(rig, tracks, 0, body));
  Behaviours face;
  face.blink.enabled = true;
  face.blink.pose = 3;
  face.blink.interval = 0.9, face.blink.jitter = 0.5, face.blink.duration = 0.15, face.blink.seed = seed;
  face.look_at.enabled = true;
  face.look_at.x = 1, face.look_at.y = 0, face.look_at.smoothing = 0.2, face.look_at.strength = 0.8;
  face.spring.enabled = true;
  face.spring.frequency = 4, face.spring.damping = 0.5;
  REQUIRE(AnimatorSetBehaviours(rig, tracks, 1, face));
}

// Commands at times in sixths of a second (shared by 30, 60 and 144 Hz):
// gestures, a pad cut (a fast move for the spring), mixes, a queue, an
// interrupted mix, look-at targets.
void Timeline(const Rig& rig, Span<AnimatorTrack> t, int sixth, bool behaviours) {
  // Plays of path 0: at (sixth), on (channel), over (mix) at (speed) from (start).
  struct Play {
    int sixth;
    std::uint32_t channel;
    double mix, speed, start;
  };
  const Play plays[] = {{0, 0, 0, 1, 0},
                        {9, 1, 0.5, 1, 0},
                        {15, 0, 0.4, 1.3, 2.0},
                        {21, 0, 0.5, 1, 0},
                        {22, 0, 0.3, 1, 1.0}};  // 22 interrupts the mix begun at 21
  for (const Play& p : plays) {
    if (p.sixth != sixth) continue;
    PlayOptions o;
    o.mix = p.mix, o.speed = p.speed, o.start = p.start;
    AnimatorPlay(rig, t, p.channel, 0, o);
  }
  if (sixth == 0 && behaviours) DeclareBehaviours(rig, t, 7);
  if (sixth == 6) AnimatorLookAt(rig, t, 1, 0, 1);
  if (sixth == 12) AnimatorSetPoint(rig, t, 0, -1, 0, 0);
  if (sixth == 15) AnimatorLookAt(rig, t, 1, -1, 0);
  if (sixth == 18) AnimatorQueue(rig, t, 0, 0, PlayOptions());
  if (sixth == 22) AnimatorSetPoint(rig, t, 1, 0.5, 0.5, 0.2);
}

struct Sample {
  std::vector<double> weights;    // every channel's raw, limited and texture weights
  std::vector<double> positions;  // the body's vertices
};

// The timeline at `rate` updates per second for 5 s, sampled every sixth of a second.
std::vector<Sample> RunAt(const Rig& rig, int rate, bool behaviours) {
  Character ch(rig);
  std::vector<Sample> out;
  for (int k = 0; k <= 5 * rate; ++k) {
    ch.Update(k == 0 ? 0.0 : 1.0 / rate);  // to k / rate seconds
    if ((6 * k) % rate != 0) continue;
    // Commands at this instant take effect from here, in the next update.
    Timeline(rig, ch.Tracks(), 6 * k / rate, behaviours);
    Sample s;
    for (const auto* v :
         {&ch.raw, &ch.limited, &ch.texture, &ch.attached_raw, &ch.attached_limited, &ch.attached_texture})
      s.weights.insert(s.weights.end(), v->begin(), v->end());
    s.positions = Morph(rig, ch.raw, ch.limited);
    out.push_back(std::move(s));
  }
  return out;
}

double RigSize(const Rig& rig) {
  const std::vector<double> x = MorphAt(rig, rig.pose_points()[0], rig.pose_points()[1]);
  double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
  for (std::size_t i = 0; i < x.size(); ++i)
    lo[i % 2] = std::min(lo[i % 2], x[i]), hi[i % 2] = std::max(hi[i % 2], x[i]);
  return std::hypot(hi[0] - lo[0], hi[1] - lo[1]);
}

}  // namespace

TEST_CASE("behaviours give the same pose at shared times at 30, 60 and 144 updates per second") {
  const Rig rig = LoadTestRig("pell-face");
  const double size = RigSize(rig);
  const std::vector<Sample> fine = RunAt(rig, 144, true);
  REQUIRE(fine.size() == 31);
  double worst_weight = 0, worst_position = 0;
  for (int rate : {30, 60}) {
    const std::vector<Sample> coarse = RunAt(rig, rate, true);
    REQUIRE(coarse.size() == fine.size());
    for (std::size_t i = 0; i < fine.size(); ++i) {
      worst_weight = std::max(worst_weight, MaxDifference(coarse[i].weights, fine[i].weights));
      worst_position = std::max(worst_position, MaxDifference(coarse[i].positions, fine[i].positions) / size);
    }
  }
  // The behaviours did something: without them the same timeline differs.
  const std::vector<Sample> plain = RunAt(rig, 60, false);
  double effect = 0;
  for (std::size_t i = 0; i < fine.size(); ++i)
    effect = std::max(effect, MaxDifference(plain[i].weights, fine[i].weights));
  MESSAGE("30/60 vs 144 Hz: weights within " << worst_weight << ", positions within " << worst_position
                                             << " of the rig size; behaviours change weights by up to " << effect);
  CHECK(worst_weight <= 1e-9);
  CHECK(worst_position <= 1e-9);
  CHECK(effect > 0.05);
}

TEST_CASE("the spring overshoots a cut and settles on it, as a damped spring does") {
  const Rig rig = LoadTestRig("pell-face");
  const Rig& body = *rig.channel_rig(0);
  Character ch(rig);
  Behaviours b;
  b.spring.enabled = true;
  b.spring.frequency = 2.5, b.spring.damping = 0.3;
  REQUIRE(AnimatorSetBehaviours(rig, ch.Tracks(), 0, b));
  ch.Update(0);
  // Starting the spring changes nothing: the channel shows its motion's bits.
  CHECK(ch.raw == WeightsAt(body, 0, 0).raw);
  REQUIRE(AnimatorSetPoint(rig, ch.Tracks(), 0, 1, 0, 0));  // a cut to "wave"
  double peak = 0;
  for (int f = 0; f < 6 * 60; ++f) {
    ch.Update(1.0 / 60);
    peak = std::max(peak, ch.tracks[0].behaviour_state.spring[0]);
  }
  // Underdamped at 0.3: the overshoot of a step is exp(-pi z / sqrt(1 - z^2)) =
  // 0.372 (the trapezoidal rule keeps the swing; the 120 Hz steps sample its peak).
  MESSAGE("spring peak " << peak);
  CHECK(std::fabs(peak - 1.3723) <= 0.005);
  const Weights settled = WeightsAt(body, 1, 0);
  CHECK(MaxDifference(ch.raw, settled.raw) <= 1e-9);
  CHECK(MaxDifference(ch.limited, settled.limited) <= 1e-9);
}

TEST_CASE("breath offsets the channel's point by its declared sine") {
  const Rig rig = LoadTestRig("pell-face");
  const Rig& body = *rig.channel_rig(0);
  Character ch(rig);
  Behaviours b;
  b.breath.enabled = true;
  b.breath.period = 2, b.breath.x = 0.02, b.breath.y = 0.1;
  REQUIRE(AnimatorSetBehaviours(rig, ch.Tracks(), 0, b));
  double worst = 0;
  for (int f = 0; f <= 100; ++f) {
    ch.Update(f == 0 ? 0.0 : 0.05);
    const double s = std::sin(2 * kPi * (0.05 * f) / 2);
    const Weights w = WeightsAt(body, body.pose_points()[0] + 0.02 * s, body.pose_points()[1] + 0.1 * s);
    worst = std::max(worst, MaxDifference(ch.raw, w.raw));
  }
  CHECK(worst <= 1e-9);
}

TEST_CASE("blinks come at jittered intervals, full and short, the same for the same seed") {
  const Rig rig = LoadTestRig("pell-face");
  auto run = [&](std::uint64_t seed, std::vector<int>* starts, double* peak, double* worst_sum) {
    Character ch(rig);
    Behaviours b;
    b.blink.enabled = true;
    b.blink.pose = 3;
    b.blink.interval = 2, b.blink.jitter = 0.5, b.blink.duration = 0.15, b.blink.seed = seed;
    REQUIRE(AnimatorSetBehaviours(rig, ch.Tracks(), 1, b));
    std::vector<double> trace;
    bool closed = false;
    int run_length = 0;
    for (int f = 0; f < 60 * 60; ++f) {
      ch.Update(1.0 / 60);
      for (int which = 0; which < 3; ++which)
        *worst_sum = std::max(*worst_sum, std::fabs(Sum(ch.ChannelWeights(1, which)) - 1));
      const double w = ch.ChannelWeights(1)[3];
      *peak = std::max(*peak, w);
      trace.insert(trace.end(), ch.attached_raw.begin(), ch.attached_raw.end());
      if (w > 0.5 && !closed) starts->push_back(f), run_length = 0;
      if (w > 0.5) ++run_length;
      if (closed && !(w > 0.5)) {
        CHECK(run_length >= 4);  // 16 u^2 (1 - u)^2 > 0.5 for 54% of 0.15 s: 4.9 frames
        CHECK(run_length <= 6);
      }
      closed = w > 0.5;
    }
    return trace;
  };
  std::vector<int> a, b, c;
  double peak = 0, worst_sum = 0;
  const std::vector<double> ta = run(42, &a, &peak, &worst_sum);
  const std::vector<double> tb = run(42, &b, &peak, &worst_sum);
  const std::vector<double> tc = run(43, &c, &peak, &worst_sum);
  CHECK(std::memcmp(ta.data(), tb.data(), ta.size() * sizeof(double)) == 0);
  CHECK(a == b);
  CHECK(a != c);
  MESSAGE("blinks in 60 s: " << a.size() << " (seed 42), " << c.size() << " (seed 43); peak weight " << peak);
  CHECK(peak >= 0.99);
  CHECK(worst_sum <= 1e-12);
  for (const std::vector<int>* s : {&a, &c}) {
    CHECK(s->size() >= 20);  // intervals lie in [1, 3) s
    CHECK(s->size() <= 60);
    for (std::size_t i = 1; i < s->size(); ++i) {
      const double gap = ((*s)[i] - (*s)[i - 1]) / 60.0;
      CHECK(gap >= 1 - 2.0 / 60);
      CHECK(gap <= 3 + 2.0 / 60);
    }
  }
}

TEST_CASE("look-at closes its gap over its smoothing time and shows the target at its strength") {
  const Rig rig = LoadTestRig("pell-face");
  const Rig& face = *rig.channel_rig(1);
  for (double strength : {1.0, 0.5}) {
    CAPTURE(strength);
    Character ch(rig);
    Behaviours b;
    b.look_at.enabled = true;
    b.look_at.smoothing = 0.1, b.look_at.strength = strength;
    REQUIRE(AnimatorSetBehaviours(rig, ch.Tracks(), 1, b));
    ch.Update(0);
    CHECK(ch.ChannelWeights(1) == WeightsAt(face, 0, 0).raw);  // starts where the face is
    REQUIRE(AnimatorLookAt(rig, ch.Tracks(), 1, 1, 0));
    for (int f = 0; f < 24; ++f) ch.Update(1.0 / 240);
    // One time constant: exp(-1) = 0.368 of the gap left (explicit steps of
    // h / smoothing: (1 - 1/12)^12 = 0.352).
    const double gap = 1 - ch.tracks[1].behaviour_state.look[2];
    CHECK(gap > 0.34);
    CHECK(gap < 0.37);
    for (int f = 0; f < 120; ++f) ch.Update(1.0 / 60);
    CHECK(MaxDifference(ch.ChannelWeights(1), WeightsAt(face, strength, 0).raw) <= 1e-9);
  }
}

TEST_CASE("hostile behaviours, states and steps give finite weights, and a huge step settles") {
  const Rig rig = LoadTestRig("pell-face");
  const double nan = std::nan(""), inf = HUGE_VAL;
  std::mt19937_64 rng(5);
  for (int round = 0; round < 200; ++round) {
    Character ch(rig);
    DeclareBehaviours(rig, ch.Tracks(), rng());
    PlayOptions o;
    AnimatorPlay(rig, ch.Tracks(), 0, 0, o);
    ch.Update(0.3);
    const double values[] = {nan, inf, -inf, 1e300, -1e300, 0, -1, 1e-300, 5};
    auto pick = [&] { return values[rng() % 9]; };
    for (std::uint32_t c = 0; c < 2; ++c) {
      Behaviours& b = ch.tracks[c].behaviours;
      b.blink.interval = pick(), b.blink.duration = pick(), b.blink.jitter = pick(), b.blink.strength = pick();
      b.blink.pose = std::uint32_t(rng());
      b.breath.period = pick(), b.breath.x = pick(), b.breath.y = pick();
      b.look_at.x = pick(), b.look_at.y = pick(), b.look_at.smoothing = pick(), b.look_at.strength = pick();
      b.spring.frequency = pick(), b.spring.damping = pick(), b.spring.strength = pick();
      if (round % 2) {  // the state as random bytes
        auto* bytes = reinterpret_cast<unsigned char*>(&ch.tracks[c].behaviour_state);
        for (std::size_t i = 0; i < sizeof(BehaviourState); ++i) bytes[i] = static_cast<unsigned char>(rng());
      }
    }
    for (double dt : {1.0 / 60, pick(), 1e9, 1.0 / 60, 0.5}) {
      ch.Update(dt);
      bool finite = true;
      for (const auto* v : {&ch.raw, &ch.limited, &ch.texture, &ch.attached_raw, &ch.attached_limited})
        for (double x : *v) finite = finite && std::isfinite(x);
      REQUIRE(finite);
    }
  }
  // A step beyond kMaxBehaviourSteps runs the last 10 s: the look point and
  // the spring reach their targets.
  Character ch(rig);
  DeclareBehaviours(rig, ch.Tracks(), 3);
  ch.Update(0);
  REQUIRE(AnimatorSetPoint(rig, ch.Tracks(), 1, 0, 1, 0));
  ch.Update(1e9);
  const BehaviourState& s = ch.tracks[1].behaviour_state;
  CHECK(std::fabs(s.look[2] - 1) <= 1e-9);
  CHECK(std::fabs(s.lag[2]) + std::fabs(s.lag[3]) <= 1e-9);
}
