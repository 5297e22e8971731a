// SPDX-License-Identifier: MIT
// Blink, breath, look-at and the spring of a channel (animator_behaviours.h).
// Plain double arithmetic in a fixed order, sin from the kernels' own
// series (no libm), so every target gives the same bits.
#include "animator_behaviours.h"

#include <cmath>

#if defined(_MSC_VER) && !defined(__clang__)
#define POSEMORPH_KERNEL_INLINE __forceinline
#else
#define POSEMORPH_KERNEL_INLINE inline __attribute__((always_inline))
#endif

namespace posemorph::detail {
namespace breath_math {
#include "kernels/sincos.h"
}  // namespace breath_math

namespace {

constexpr double kTwoPi = 6.283185307179586476925;
constexpr double kH = kBehaviourStep;

double Clamp(double v, double lo, double hi) { return v >= lo ? (v <= hi ? v : hi) : lo; }
bool Usable(double v, double bound) { return std::fabs(v) <= bound; }

// splitmix64 (Steele, Lea, Flood: "Fast splittable pseudorandom number
// generators"), the step and the finaliser.
std::uint64_t Next(std::uint64_t* state) {
  std::uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// The seconds to the next blink: interval x (1 + jitter u), u in [-1, 1),
// never shorter than a blink.
double Interval(const BlinkBehaviour& b, std::uint64_t* rng) {
  const double u = double(Next(rng) >> 11) * (1.0 / 9007199254740992.0) * 2.0 - 1.0;
  const double v = b.interval * (1.0 + b.jitter * u);
  return v > b.duration ? v : b.duration;
}

}  // namespace

Behaviours SanitisedBehaviours(const Behaviours& in, std::uint32_t pose_count) {
  Behaviours b = in;
  BlinkBehaviour& k = b.blink;
  k.enabled = k.enabled && k.pose < pose_count;
  k.interval = Clamp(k.interval, 0.02, 1e6);
  k.jitter = Clamp(k.jitter, 0, 0.95);
  k.duration = Clamp(k.duration, 0.001, 60);
  k.strength = Clamp(k.strength, 0, 1);
  BreathBehaviour& r = b.breath;
  r.period = Clamp(r.period, 0.05, 1e6);
  r.x = Clamp(r.x, -1e3, 1e3);
  r.y = Clamp(r.y, -1e3, 1e3);
  LookAtBehaviour& l = b.look_at;
  l.smoothing = Clamp(l.smoothing, 0, 1e3);
  l.strength = Clamp(l.strength, 0, 1);
  if (std::isfinite(l.x) && std::isfinite(l.y)) {
    l.x = Clamp(l.x, -kMaxBehaviourPoint, kMaxBehaviourPoint);
    l.y = Clamp(l.y, -kMaxBehaviourPoint, kMaxBehaviourPoint);
  }
  SpringBehaviour& p = b.spring;
  p.frequency = Clamp(p.frequency, 0.01, 20);
  p.damping = Clamp(p.damping, 0, 100);
  p.strength = Clamp(p.strength, 0, 4);
  return b;
}

void SanitiseBehaviourState(BehaviourState* s) {
  const double bound = 10 * kMaxBehaviourPoint;
  bool usable = s->clock >= 0 && s->clock <= 1e15 && s->since_step >= -kBehaviourStepSnap && s->since_step < kH &&
                Usable(s->breath_origin, 1e15) && Usable(s->blink_next, 1e15) && (s->primed & ~15u) == 0;
  for (int i = 0; i < 4; ++i)
    usable = usable && Usable(s->look[i], bound) && Usable(s->spring[i], bound) && Usable(s->lag[i], bound);
  if (usable) return;
  const double clock = s->clock >= 0 && s->clock <= 1e15 ? s->clock : 0.0;
  *s = BehaviourState{};
  s->clock = clock;
}

void PointAdjustment::Apply(double* x, double* y) const {
  if (look_strength > 0) {
    *x += look_strength * (look_x - *x);
    *y += look_strength * (look_y - *y);
  }
  // Nothing added when there is nothing to add: the point keeps its bits
  // (a -0 stays -0), so a channel without behaviours shows exactly what
  // WeightsJob gives at its motion's point.
  if (dx != 0 || dy != 0) {
    *x += dx;
    *y += dy;
  }
}

PointAdjustment Adjustment(const Behaviours& b, const BehaviourState& s, bool full) {
  PointAdjustment a;
  const double alpha = s.since_step / kH;
  if (b.look_at.enabled && (s.primed & kLookBit)) {
    a.look_strength = b.look_at.strength;
    a.look_x = s.look[0] + alpha * (s.look[2] - s.look[0]);
    a.look_y = s.look[1] + alpha * (s.look[3] - s.look[1]);
  }
  if (!full) return a;
  if (b.breath.enabled && (s.primed & kBreathBit)) {
    const double u = std::fmod(s.clock - s.breath_origin, b.breath.period) / b.breath.period;
    double sn = 0, cs = 1;
    breath_math::SinCos(kTwoPi * u, &sn, &cs);
    a.dx += b.breath.x * sn;
    a.dy += b.breath.y * sn;
  }
  if (b.spring.enabled && (s.primed & kSpringBit)) {
    const double k = b.spring.strength;
    a.dx += k * (s.lag[0] + alpha * (s.lag[2] - s.lag[0]));
    a.dy += k * (s.lag[1] + alpha * (s.lag[3] - s.lag[1]));
  }
  return a;
}

void StartTimed(const Behaviours& b, BehaviourState* s) {
  if (!b.blink.enabled) {
    s->primed &= ~std::uint32_t(kBlinkBit);
  } else if (!(s->primed & kBlinkBit)) {
    s->blink_rng = b.blink.seed;
    s->blink_next = s->clock + Interval(b.blink, &s->blink_rng);
    s->primed |= kBlinkBit;
  }
  if (!b.breath.enabled) {
    s->primed &= ~std::uint32_t(kBreathBit);
  } else if (!(s->primed & kBreathBit)) {
    s->breath_origin = s->clock;
    s->primed |= kBreathBit;
  }
  if (!b.look_at.enabled) s->primed &= ~std::uint32_t(kLookBit);
  if (!b.spring.enabled) s->primed &= ~std::uint32_t(kSpringBit);
}

void StartLook(BehaviourState* s, double x, double y) {
  if (!std::isfinite(x) || !std::isfinite(y)) x = y = 0;
  x = Clamp(x, -kMaxBehaviourPoint, kMaxBehaviourPoint);
  y = Clamp(y, -kMaxBehaviourPoint, kMaxBehaviourPoint);
  s->look[0] = s->look[2] = x;
  s->look[1] = s->look[3] = y;
  s->primed |= kLookBit;
}

void StartSpring(BehaviourState* s, double x, double y) {
  if (!std::isfinite(x) || !std::isfinite(y)) x = y = 0;
  s->spring[0] = Clamp(x, -kMaxBehaviourPoint, kMaxBehaviourPoint);
  s->spring[1] = Clamp(y, -kMaxBehaviourPoint, kMaxBehaviourPoint);
  s->spring[2] = s->spring[3] = 0;
  for (double& v : s->lag) v = 0;
  s->primed |= kSpringBit;
}

void LookStep(const Behaviours& b, BehaviourState* s) {
  s->look[0] = s->look[2];
  s->look[1] = s->look[3];
  const LookAtBehaviour& l = b.look_at;
  if (!std::isfinite(l.x) || !std::isfinite(l.y)) return;
  const double k = l.smoothing > kH ? kH / l.smoothing : 1.0;
  s->look[2] += k * (l.x - s->look[2]);
  s->look[3] += k * (l.y - s->look[3]);
}

// The trapezoidal rule (implicit midpoint) on e'' = -K e - C e', with e
// the spring point's lag behind the target (held over the step): stable for
// every step and parameter, no numerical damping of the swing, and it
// settles at the target.
void SpringStep(const Behaviours& b, BehaviourState* s, double target_x, double target_y) {
  s->lag[0] = s->lag[2];
  s->lag[1] = s->lag[3];
  if (!std::isfinite(target_x) || !std::isfinite(target_y)) return;
  const double target[2] = {Clamp(target_x, -kMaxBehaviourPoint, kMaxBehaviourPoint),
                            Clamp(target_y, -kMaxBehaviourPoint, kMaxBehaviourPoint)};
  const double w = kTwoPi * b.spring.frequency;
  const double k = 0.25 * kH * kH * w * w, c = kH * b.spring.damping * w;  // h^2 K / 4, h C / 2
  for (int i = 0; i < 2; ++i) {
    const double e0 = s->spring[i] - target[i], v0 = s->spring[2 + i];
    const double v1 = (v0 * (1 - k - c) - kH * w * w * e0) / (1 + k + c);
    const double e1 = e0 + 0.5 * kH * (v0 + v1);
    s->spring[i] = target[i] + e1;
    s->spring[2 + i] = v1;
    s->lag[2 + i] = e1;
  }
}

void SettleLook(const Behaviours& b, BehaviourState* s) {
  const LookAtBehaviour& l = b.look_at;
  if (std::isfinite(l.x) && std::isfinite(l.y)) {
    s->look[0] = s->look[2] = l.x;
    s->look[1] = s->look[3] = l.y;
  }
}

double StepClock(double since_step, double seconds) {
  double v = since_step + seconds;
  if (!(v >= -kBehaviourStepSnap)) return 0;
  // A few steps are subtracted (the usual frame spans one to four); more wrap with fmod.
  for (int k = 0; k < 8 && v >= kH - kBehaviourStepSnap; ++k) v -= kH;
  if (v >= kH - kBehaviourStepSnap) v = std::fmod(v + kBehaviourStepSnap, kH) - kBehaviourStepSnap;
  return v;
}

double BlinkWeight(const BlinkBehaviour& b, BehaviourState* s) {
  if (!b.enabled || !(s->primed & kBlinkBit)) return 0;
  int advanced = 0;
  while (s->clock >= s->blink_next + b.duration && advanced < 64) {
    s->blink_next += Interval(b, &s->blink_rng);
    ++advanced;
  }
  // More than 64 blinks in one update: the schedule starts again from now.
  if (s->clock >= s->blink_next + b.duration) s->blink_next = s->clock + Interval(b, &s->blink_rng);
  const double u = (s->clock - s->blink_next) / b.duration;
  if (!(u >= 0 && u < 1)) return 0;
  // 16 u^2 (1 - u)^2: 0 at both ends with zero slope, 1 halfway.
  const double v = 4 * u * (1 - u);
  return b.strength * v * v;
}

}  // namespace posemorph::detail
