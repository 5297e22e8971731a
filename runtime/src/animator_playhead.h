// SPDX-License-Identifier: MIT
// Internal to the Animator: the part of a track that time moves (its
// motions, its mix, its queue), what a track shows from it (a point, the
// weights), hand-overs, and a run of time through an update's segments.
// animator.cpp runs it for the track itself and, for the behaviours' fixed
// steps, for a copy that reports nothing and freezes no weights.
#pragma once
#include <cstddef>
#include <cstdint>

#include "posemorph/animator.h"
#include "animator_behaviours.h"
#include "animator_events.h"

namespace posemorph::detail {

struct Playhead {
  Motion current, from;
  bool mixing = false;
  double mix_elapsed = 0, mix_duration = 0;
  bool has_queued = false;
  Motion queued;
  double queued_mix = 0;
};
Playhead LoadPlayhead(const AnimatorTrack& t);
void StorePlayhead(const Playhead& p, AnimatorTrack* t);

struct ChannelWeights {
  double raw[format::kMaxPoses], limited[format::kMaxPoses], texture[format::kMaxPoses];
};
struct WeightSettings {
  double sigma;
  bool limit;
  bool texture = true;  // the texture weights are wanted (the update's caller reads them)
};

// What a hand-over that interrupts a mix freezes: the blend's weights into
// `snapshot` (3 x N, the texture weights too, whatever the update's
// caller reads; null: none, for a copy that only needs the point) and the
// point the spring followed, each with the behaviours' adjustments of the
// update's start (`start`: a copy of their state then), computed only when
// a hand-over interrupts a mix.
struct Freeze {
  const Behaviours* behaviours = nullptr;
  const BehaviourState* start = nullptr;
  double* snapshot = nullptr;
  PointAdjustment Full() const { return Adjustment(*behaviours, *start, true); }
  PointAdjustment Look() const { return Adjustment(*behaviours, *start, false); }
};

// Clamps to [lo, hi]; NaN to lo.
double ClampTo(double v, double lo, double hi);
// NaN -> 0; then clamped to [0, hi].
double NonNegative(double v, double hi);

// A motion read from caller memory made valid (a stopped one when it names
// nothing the channel has).
Motion SanitisedMotion(const Rig& crig, const Motion& in, bool allow_snapshot);
// A track read from caller memory made valid: its behaviours clamped, a
// hostile behaviour state started afresh, its motions sanitised, a mix that
// cannot be shown ended.
void SanitiseTrack(const Rig& crig, AnimatorTrack* t);
// The point a motion shows (a snapshot has none: pose 0's).
void MotionPoint(const Rig& crig, const Motion& m, double* x, double* y);
// The point a playhead follows (the spring's target): its motion's, or
// during a mix the blend of its two motions' points (a snapshot keeps the
// one it had); `adj` moves each motion's point.
void PlayheadPoint(const Rig& crig, const Playhead& p, const PointAdjustment& adj, double* x, double* y);
// The weights it shows (before a blink); `snapshot` as in Freeze.
void PlayheadWeights(const Rig& crig, const Playhead& p, const double* snapshot, const WeightSettings& s,
                     const PointAdjustment& adj, ChannelWeights* out);
// Hands over to `m` over `mix` seconds (what every command does once
// applied). Interrupting a mix freezes its blend as the outgoing side.
void HandOver(const Rig& crig, Playhead* p, const Motion& m, double mix, const WeightSettings& s, const Freeze& f);
// Time through one update (of `dt` seconds), split into segments where a
// mix ends or a queued path takes over; events into `streams` when given.
void RunTime(const Rig& crig, std::uint32_t channel, Playhead* p, double dt, const WeightSettings& s, const Freeze& f,
             EventStreams* streams);

}  // namespace posemorph::detail
