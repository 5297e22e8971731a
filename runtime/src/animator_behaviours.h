// SPDX-License-Identifier: MIT
// Internal to the Animator (animator.cpp): the procedural behaviours of a
// channel (animator.h, BlinkBehaviour ... SpringBehaviour) as functions of
// its BehaviourState. animator.cpp runs the fixed steps (it alone knows the
// point a track shows at a time); these are the pieces it runs.
#pragma once
#include <cstdint>

#include "posemorph/animator.h"

namespace posemorph::detail {

enum BehaviourBit : std::uint32_t { kBlinkBit = 1, kBreathBit = 2, kLookBit = 4, kSpringBit = 8 };

// The bound on points the spring and the look point take: targets beyond
// it are clamped, and a state beyond ten times it is started afresh.
constexpr double kMaxBehaviourPoint = 1e6;

// The parameters clamped to their documented ranges (a NaN becomes the
// range's lower end); a blink whose pose is not below `pose_count` is off.
Behaviours SanitisedBehaviours(const Behaviours& in, std::uint32_t pose_count);
// A state read from caller memory: a non-finite or out-of-bounds field
// starts the behaviours afresh (primed = 0, clock kept when it is usable).
void SanitiseBehaviourState(BehaviourState* s);

// How the behaviours move a motion's point at the state's instant:
// p -> p + look_strength (look - p) + (dx, dy).
struct PointAdjustment {
  double look_strength = 0, look_x = 0, look_y = 0;
  double dx = 0, dy = 0;
  void Apply(double* x, double* y) const;
};
// With `full` false only look-at (the part the spring's target includes).
PointAdjustment Adjustment(const Behaviours& b, const BehaviourState& s, bool full);

// Starting behaviours (bits not yet primed): blink and breath from the
// clock; look-at from `x, y`, the point the channel shows without it.
void StartTimed(const Behaviours& b, BehaviourState* s);
void StartLook(BehaviourState* s, double x, double y);
// The spring from its target: at rest there.
void StartSpring(BehaviourState* s, double x, double y);

// One fixed step: the look point toward the target; then (with the target
// the channel's point including the new look point) the spring.
void LookStep(const Behaviours& b, BehaviourState* s);
void SpringStep(const Behaviours& b, BehaviourState* s, double target_x, double target_y);
// Both at their targets now (an update longer than kMaxBehaviourSteps).
void SettleLook(const Behaviours& b, BehaviourState* s);

// The step clock `since_step` after `seconds` without steps being taken
// (or after the last one): within [-kBehaviourStepSnap, kBehaviourStep),
// wrapped as the stepping loop would wrap it.
double StepClock(double since_step, double seconds);

// The blink's weight at the state's clock, advancing its schedule.
double BlinkWeight(const BlinkBehaviour& b, BehaviourState* s);

}  // namespace posemorph::detail
