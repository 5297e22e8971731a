// SPDX-License-Identifier: MIT
// The Animator (animator.h; docs/animation.md): commands, and an update that
// runs each track's command, behaviours, time and weights. The playhead
// (motions, mixes, queues, segments) is animator_playhead.cpp, the event
// streams and their merge animator_events.cpp, the behaviours' pieces
// animator_behaviours.cpp. Look-at and the spring step at fixed times within
// an update, their target read from a copy of the playhead advanced to each
// (it reports nothing and freezes no weights).
#include "posemorph/animator.h"

#include <cmath>
#include <cstring>

#include "posemorph/jobs.h"
#include "animator_behaviours.h"
#include "animator_events.h"
#include "animator_playhead.h"

namespace posemorph {
namespace {

using detail::ChannelWeights;
using detail::EventStreams;
using detail::Freeze;
using detail::NonNegative;
using detail::Playhead;
using detail::PointAdjustment;
using detail::WeightSettings;

const Rig* ChannelRig(const Rig& rig, std::uint32_t channel) {
  return rig.loaded() && channel < rig.channel_count() ? rig.channel_rig(channel) : nullptr;
}

// Look-at and the spring through one update: a fixed step each time the
// step clock passes a multiple of kBehaviourStep, with the spring's target
// read from a copy of the playhead advanced to that instant.
void StepBehaviours(const Rig& crig, std::uint32_t channel, const Playhead& p, const Behaviours& b, BehaviourState* st,
                    double dt, const WeightSettings& s, Freeze f) {
  Playhead probe = p;
  f.snapshot = nullptr;
  double done = 0, x = 0, y = 0;
  if ((st->since_step + dt) / kBehaviourStep > kMaxBehaviourSteps) {
    done = dt - kMaxBehaviourSteps * kBehaviourStep;
    detail::RunTime(crig, channel, &probe, done, s, f, nullptr);
    st->since_step = 0;
    if (b.look_at.enabled) detail::SettleLook(b, st);
    detail::PlayheadPoint(crig, probe, detail::Adjustment(b, *st, false), &x, &y);
    if (b.spring.enabled) detail::StartSpring(st, x, y);
  }
  for (int k = 0; k <= kMaxBehaviourSteps && st->since_step + (dt - done) >= kBehaviourStep - kBehaviourStepSnap; ++k) {
    const double to = kBehaviourStep - st->since_step;
    if (b.spring.enabled) detail::RunTime(crig, channel, &probe, to, s, f, nullptr);  // only the spring reads it
    done += to;
    st->since_step = 0;
    if (b.look_at.enabled) detail::LookStep(b, st);
    if (!b.spring.enabled) continue;
    // The target at this step sees the look point just reached.
    PointAdjustment look = detail::Adjustment(b, *st, false);
    look.look_x = st->look[2];
    look.look_y = st->look[3];
    detail::PlayheadPoint(crig, probe, look, &x, &y);
    detail::SpringStep(b, st, x, y);
  }
  st->since_step = detail::StepClock(st->since_step, dt - done);
}

// One track through one update: its command, its behaviours, its time,
// its weights.
void UpdateTrack(const Rig& crig, std::uint32_t channel, AnimatorTrack* t, double dt, const WeightSettings& s,
                 EventStreams* streams, ChannelWeights* out) {
  detail::SanitiseTrack(crig, t);
  BehaviourState& st = t->behaviour_state;
  const Behaviours& b = t->behaviours;
  const BehaviourState start = st;  // what a hand-over that interrupts a mix freezes with
  const Freeze f{&b, &start, t->snapshot};
  Playhead p = detail::LoadPlayhead(*t);
  if (t->has_pending) {
    t->has_pending = false;
    detail::HandOver(crig, &p, t->pending, t->pending_mix, s, f);
  }
  detail::StartTimed(b, &st);
  double x = 0, y = 0;
  if (b.look_at.enabled && !(st.primed & detail::kLookBit)) {
    detail::PlayheadPoint(crig, p, PointAdjustment{}, &x, &y);
    detail::StartLook(&st, x, y);
  }
  if (b.spring.enabled && !(st.primed & detail::kSpringBit)) {
    detail::PlayheadPoint(crig, p, detail::Adjustment(b, st, false), &x, &y);
    detail::StartSpring(&st, x, y);
  }
  if (b.look_at.enabled || b.spring.enabled)
    StepBehaviours(crig, channel, p, b, &st, dt, s, f);
  else
    st.since_step = detail::StepClock(st.since_step, dt);
  detail::RunTime(crig, channel, &p, dt, s, f, streams);
  detail::StorePlayhead(p, t);
  st.clock += dt;
  detail::PlayheadWeights(crig, p, t->snapshot, s, detail::Adjustment(b, st, true), out);
  const double blink = detail::BlinkWeight(b.blink, &st);
  if (!(blink > 0)) return;
  const std::size_t n = crig.pose_count();
  for (std::size_t i = 0; i < n; ++i) {
    const double e = i == b.blink.pose ? blink : 0.0;
    out->raw[i] = (1 - blink) * out->raw[i] + e;
    out->limited[i] = (1 - blink) * out->limited[i] + e;
    if (s.texture) out->texture[i] = (1 - blink) * out->texture[i] + e;
  }
}

bool Valid(const Rig& rig, Span<AnimatorTrack> tracks, std::uint32_t channel) {
  return rig.loaded() && tracks.data && tracks.size >= rig.channel_count() && channel < rig.channel_count();
}

Motion PathMotion(const Rig& crig, std::uint32_t path, const PlayOptions& o) {
  Motion m;
  m.kind = MotionKind::kPath;
  m.path = path;
  const PathView p = crig.path(path);
  m.loop = o.loop < 0 ? p.loop : o.loop > 0;
  m.speed = NonNegative(o.speed, kMaxAnimatorSpeed);
  m.time = p.start_time() + NonNegative(o.start, kMaxAnimatorSpeed);
  return detail::SanitisedMotion(crig, m, false);
}

}  // namespace

bool AnimatorReset(const Rig& rig, Span<AnimatorTrack> tracks) {
  if (!Valid(rig, tracks, 0)) return false;
  for (std::uint32_t c = 0; c < rig.channel_count(); ++c) tracks[c] = AnimatorTrack{};
  return true;
}

namespace {

// A path to play now (`queue` false: clears the queue) or when the current
// one ends (`queue` true), into the track's pending or queued slot.
bool SetPath(const Rig& rig, Span<AnimatorTrack> tracks, std::uint32_t channel, std::uint32_t path,
             const PlayOptions& options, bool queue) {
  if (!Valid(rig, tracks, channel)) return false;
  const Rig& crig = *ChannelRig(rig, channel);
  if (path >= crig.path_count()) return false;
  AnimatorTrack& t = tracks[channel];
  (queue ? t.queued : t.pending) = PathMotion(crig, path, options);
  (queue ? t.queued_mix : t.pending_mix) = NonNegative(options.mix, kMaxAnimatorMix);
  if (queue) {
    t.has_queued = true;
  } else {
    t.has_pending = true;
    t.has_queued = false;
  }
  return true;
}

}  // namespace

bool AnimatorPlay(const Rig& rig, Span<AnimatorTrack> tracks, std::uint32_t channel, std::uint32_t path,
                  const PlayOptions& options) {
  return SetPath(rig, tracks, channel, path, options, false);
}

bool AnimatorQueue(const Rig& rig, Span<AnimatorTrack> tracks, std::uint32_t channel, std::uint32_t path,
                   const PlayOptions& options) {
  return SetPath(rig, tracks, channel, path, options, true);
}

bool AnimatorSetPoint(const Rig& rig, Span<AnimatorTrack> tracks, std::uint32_t channel, double x, double y,
                      double mix) {
  if (!Valid(rig, tracks, channel)) return false;
  AnimatorTrack& t = tracks[channel];
  Motion m;
  m.kind = MotionKind::kPoint;
  m.x = x;
  m.y = y;
  if (t.has_pending && t.pending.kind == MotionKind::kPoint) {
    t.pending.x = x, t.pending.y = y;
  } else if (!t.has_pending && t.current.kind == MotionKind::kPoint) {
    t.current.x = x, t.current.y = y;
  } else {
    t.pending = m;
    t.pending_mix = NonNegative(mix, kMaxAnimatorMix);
    t.has_pending = true;
  }
  return true;
}

bool AnimatorStop(const Rig& rig, Span<AnimatorTrack> tracks, std::uint32_t channel, double mix) {
  if (!Valid(rig, tracks, channel)) return false;
  AnimatorTrack& t = tracks[channel];
  t.pending = Motion{};
  t.pending_mix = NonNegative(mix, kMaxAnimatorMix);
  t.has_pending = true;
  t.has_queued = false;
  return true;
}

bool AnimatorSetSpeed(const Rig& rig, Span<AnimatorTrack> tracks, std::uint32_t channel, double speed) {
  if (!Valid(rig, tracks, channel)) return false;
  AnimatorTrack& t = tracks[channel];
  const double v = NonNegative(speed, kMaxAnimatorSpeed);
  if (t.current.kind == MotionKind::kPath) t.current.speed = v;
  if (t.has_pending && t.pending.kind == MotionKind::kPath) t.pending.speed = v;
  return true;
}

bool AnimatorSetBehaviours(const Rig& rig, Span<AnimatorTrack> tracks, std::uint32_t channel,
                           const Behaviours& behaviours) {
  if (!Valid(rig, tracks, channel)) return false;
  tracks[channel].behaviours = behaviours;
  return true;
}

bool AnimatorLookAt(const Rig& rig, Span<AnimatorTrack> tracks, std::uint32_t channel, double x, double y) {
  if (!Valid(rig, tracks, channel)) return false;
  tracks[channel].behaviours.look_at.x = x;
  tracks[channel].behaviours.look_at.y = y;
  return true;
}

bool AnimatorUpdateJob::Validate() const {
  if (!rig || !rig->loaded() || count > kMaxAnimatorBatch) return false;
  const std::size_t C = rig->channel_count(), N = rig->pose_count(), A = rig->attached_weight_count();
  if (!tracks.data || tracks.size < count * C) return false;
  if (!weights.data || weights.size < count * N || !limited_weights.data || limited_weights.size < count * N)
    return false;
  if (!texture_weights.empty() && texture_weights.size < count * N) return false;
  if (A && (!attached_weights.data || attached_weights.size < count * A || !attached_limited_weights.data ||
            attached_limited_weights.size < count * A))
    return false;
  if (A && !attached_texture_weights.empty() && attached_texture_weights.size < count * A) return false;
  if (!events.empty() && (!events.data || !event_count || !events_missed)) return false;
  return true;
}

bool AnimatorUpdateJob::Run() const {
  if (!Validate()) return false;
  const std::uint32_t C = rig->channel_count();
  const double step = dt > 0 ? (dt < kMaxAnimatorStep ? dt : kMaxAnimatorStep) : 0.0;
  std::size_t written = 0;
  double missed = 0;
  EventStreams streams;
  ChannelWeights w;
  for (std::size_t i = 0; i < count; ++i) {
    streams.count = 0;
    for (std::uint32_t c = 0; c < C; ++c) {
      const Rig& crig = *rig->channel_rig(c);
      const std::size_t n = crig.pose_count();
      const bool wanted = c == 0 ? !texture_weights.empty() : !attached_texture_weights.empty();
      const WeightSettings s{sigma >= 0 ? detail::ClampTo(sigma, 0, 1) : crig.default_sigma(), limit_weights, wanted};
      UpdateTrack(crig, c, &tracks[i * C + c], step, s, events.empty() ? nullptr : &streams, &w);
      double *raw, *limited, *texture;
      if (c == 0) {
        raw = weights.data + i * n;
        limited = limited_weights.data + i * n;
        texture = texture_weights.empty() ? nullptr : texture_weights.data + i * n;
      } else {
        const std::size_t at = count * rig->channel_weight_offset(c) + i * n;
        raw = attached_weights.data + at;
        limited = attached_limited_weights.data + at;
        texture = attached_texture_weights.empty() ? nullptr : attached_texture_weights.data + at;
      }
      std::memcpy(raw, w.raw, n * sizeof(double));
      std::memcpy(limited, limit_weights ? w.limited : w.raw, n * sizeof(double));
      if (texture) std::memcpy(texture, w.texture, n * sizeof(double));
    }
    if (!events.empty()) detail::EmitEvents(&streams, std::uint32_t(i), step, events, &written, &missed);
  }
  if (event_count) *event_count = written;
  if (events_missed) *events_missed = missed >= 1.8e19 ? ~std::uint64_t(0) : std::uint64_t(missed);
  return true;
}

}  // namespace posemorph
