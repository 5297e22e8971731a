// SPDX-License-Identifier: MIT
// A track's playhead (animator_playhead.h): motions, mixes, queues, the
// point and weights they show, hand-overs and segments of time.
#include "animator_playhead.h"

#include <cmath>
#include <cstring>

#include "posemorph/jobs.h"
#include "posemorph/path.h"

namespace posemorph::detail {
namespace {

bool Loops(const PathView& p, const Motion& m) { return m.loop && p.end_time() > p.start_time(); }

void MotionWeights(const Rig& crig, const Motion& m, const WeightSettings& s, const PointAdjustment& adj,
                   ChannelWeights* w) {
  const std::size_t n = crig.pose_count();
  WeightsJob job;
  job.rig = &crig;
  MotionPoint(crig, m, &job.x, &job.y);
  adj.Apply(&job.x, &job.y);
  job.sigma = s.sigma;
  job.limit_weights = s.limit;
  job.raw = {w->raw, n};
  job.limited = {w->limited, n};
  if (s.texture) job.texture = {w->texture, n};  // else not computed: nobody reads them
  job.Run();
}

// Advances a path motion by `seconds` (to its end, or its cycle's end,
// when `to_end`), adding the stream of what it crossed when `streams` is
// given.
void Advance(const Rig& crig, std::uint32_t channel, bool outgoing, Motion* m, double seconds, bool to_end,
             double offset, EventStreams* streams) {
  if (m->kind != MotionKind::kPath) return;
  const PathView p = crig.path(m->path);
  const double start = p.start_time(), end = p.end_time();
  const bool loop = Loops(p, *m);
  if (!loop && m->ended) return;
  const double t0 = m->time;
  double t1 = to_end ? end : t0 + m->speed * seconds;
  bool closed = false;
  if (loop) {
    double r = std::fmod(t1 - start, end - start);
    if (r < 0) r += end - start;
    double wrapped = start + r;
    if (!(wrapped < end)) wrapped = start;
    m->time = wrapped;
  } else if (t1 >= end && (seconds > 0 || to_end)) {
    t1 = end;
    closed = true;
    m->ended = true;
    m->time = end;
  } else {
    m->time = t1;
  }
  if (!streams || p.events.empty() || !(t1 > t0 || closed) || !(m->speed > 0) || streams->count >= kMaxEventStreams)
    return;
  EventStream& s = streams->s[streams->count++];
  s = EventStream{};
  s.events = p.events.data;
  s.n = std::uint32_t(p.events.size);
  s.base = std::uint32_t(p.events.data - crig.events().data);
  s.channel = channel;
  s.outgoing = outgoing;
  s.loop = loop;
  s.closed = closed;
  s.t0 = t0;
  s.t1 = t1;
  s.start = start;
  s.period = end - start;
  s.speed = m->speed;
  s.offset = offset;
  s.Begin();
}

// Seconds until the current path hands over to the queued one (infinite
// when it never does at speed 0).
double TimeToHandOver(const Rig& crig, const Motion& m) {
  if (m.kind != MotionKind::kPath) return 0;
  const PathView p = crig.path(m.path);
  if (!Loops(p, m) && m.ended) return 0;
  if (!(m.speed > 0)) return HUGE_VAL;
  return (p.end_time() - m.time) / m.speed;
}

bool SnapshotUsable(const AnimatorTrack& t, std::size_t n) {
  for (std::size_t i = 0; i < 3 * n; ++i)
    if (!(std::fabs(t.snapshot[i]) <= kMaxJobWeight)) return false;
  return true;
}

}  // namespace

Playhead LoadPlayhead(const AnimatorTrack& t) {
  Playhead p;
  p.current = t.current, p.from = t.from;
  p.mixing = t.mixing, p.mix_elapsed = t.mix_elapsed, p.mix_duration = t.mix_duration;
  p.has_queued = t.has_queued, p.queued = t.queued, p.queued_mix = t.queued_mix;
  return p;
}

void StorePlayhead(const Playhead& p, AnimatorTrack* t) {
  t->current = p.current, t->from = p.from;
  t->mixing = p.mixing, t->mix_elapsed = p.mix_elapsed, t->mix_duration = p.mix_duration;
  t->has_queued = p.has_queued, t->queued = p.queued, t->queued_mix = p.queued_mix;
}

double ClampTo(double v, double lo, double hi) { return v >= lo ? (v <= hi ? v : hi) : lo; }
double NonNegative(double v, double hi) { return v > 0 ? (v < hi ? v : hi) : 0.0; }

Motion SanitisedMotion(const Rig& crig, const Motion& in, bool allow_snapshot) {
  Motion m = in;
  const bool known = m.kind == MotionKind::kRest || m.kind == MotionKind::kPath || m.kind == MotionKind::kPoint ||
                     (allow_snapshot && m.kind == MotionKind::kSnapshot);
  if (!known || (m.kind == MotionKind::kPath && m.path >= crig.path_count())) return Motion{};
  if (m.kind != MotionKind::kPath) return m;
  const PathView p = crig.path(m.path);
  const double start = p.start_time(), end = p.end_time();
  m.speed = NonNegative(m.speed, kMaxAnimatorSpeed);
  if (!std::isfinite(m.time)) m.time = start;
  if (Loops(p, m)) {
    m.ended = false;
    if (!(m.time >= start && m.time < end)) {
      double r = std::fmod(m.time - start, end - start);
      if (r < 0) r += end - start;
      m.time = start + r;
      if (!(m.time < end)) m.time = start;
    }
  } else {
    m.loop = false;
    m.time = ClampTo(m.time, start, end);
    if (m.ended) m.time = end;
  }
  return m;
}

void MotionPoint(const Rig& crig, const Motion& m, double* x, double* y) {
  if (m.kind == MotionKind::kPath && SamplePath(crig, m.path, m.time, x, y)) return;
  if (m.kind == MotionKind::kPoint) {
    *x = m.x;
    *y = m.y;
    return;
  }
  *x = crig.pose_points()[0];
  *y = crig.pose_points()[1];
}

void PlayheadPoint(const Rig& crig, const Playhead& p, const PointAdjustment& adj, double* x, double* y) {
  MotionPoint(crig, p.current, x, y);
  adj.Apply(x, y);
  if (!p.mixing) return;
  double fx = p.from.x, fy = p.from.y;
  if (p.from.kind != MotionKind::kSnapshot) {
    MotionPoint(crig, p.from, &fx, &fy);
    adj.Apply(&fx, &fy);
  }
  const double a = ClampTo(p.mix_elapsed / p.mix_duration, 0, 1), b = 1 - a;
  *x = b * fx + a * *x;
  *y = b * fy + a * *y;
}

void PlayheadWeights(const Rig& crig, const Playhead& p, const double* snapshot, const WeightSettings& s,
                     const PointAdjustment& adj, ChannelWeights* out) {
  const std::size_t n = crig.pose_count();
  MotionWeights(crig, p.current, s, adj, out);
  if (!p.mixing) return;
  ChannelWeights from;
  if (p.from.kind == MotionKind::kSnapshot) {
    if (!snapshot) return;  // a copy's frozen blend: only its point is known
    std::memcpy(from.raw, snapshot, n * sizeof(double));
    std::memcpy(from.limited, snapshot + n, n * sizeof(double));
    std::memcpy(from.texture, snapshot + 2 * n, n * sizeof(double));
  } else {
    MotionWeights(crig, p.from, s, adj, &from);
  }
  const double a = ClampTo(p.mix_elapsed / p.mix_duration, 0, 1), b = 1 - a;
  for (std::size_t i = 0; i < n; ++i) {
    out->raw[i] = b * from.raw[i] + a * out->raw[i];
    out->limited[i] = b * from.limited[i] + a * out->limited[i];
  }
  if (!s.texture) return;
  for (std::size_t i = 0; i < n; ++i) out->texture[i] = b * from.texture[i] + a * out->texture[i];
}

void HandOver(const Rig& crig, Playhead* p, const Motion& m, double mix, const WeightSettings& s, const Freeze& f) {
  if (!(mix > 0)) {
    p->current = m;
    p->mixing = false;
    p->from = Motion{};
    return;
  }
  if (p->mixing) {
    Motion frozen;
    frozen.kind = MotionKind::kSnapshot;
    PlayheadPoint(crig, *p, f.Look(), &frozen.x, &frozen.y);
    if (f.snapshot) {
      const std::size_t n = crig.pose_count();
      ChannelWeights now;
      WeightSettings all = s;  // a later update may read the frozen texture weights
      all.texture = true;
      PlayheadWeights(crig, *p, f.snapshot, all, f.Full(), &now);
      std::memcpy(f.snapshot, now.raw, n * sizeof(double));
      std::memcpy(f.snapshot + n, now.limited, n * sizeof(double));
      std::memcpy(f.snapshot + 2 * n, now.texture, n * sizeof(double));
    }
    p->from = frozen;
  } else {
    p->from = p->current;
  }
  p->current = m;
  p->mixing = true;
  p->mix_elapsed = 0;
  p->mix_duration = mix;
}

void RunTime(const Rig& crig, std::uint32_t channel, Playhead* p, double dt, const WeightSettings& s, const Freeze& f,
             EventStreams* streams) {
  double left = dt, clock = 0;
  for (int segment = 0; segment < kMaxAnimatorSegments; ++segment) {
    if (p->has_queued && p->current.kind != MotionKind::kPath) {
      p->has_queued = false;
      HandOver(crig, p, p->queued, p->queued_mix, s, f);
    }
    double seconds = left;
    bool mix_ends = false, hand_over = false;
    if (p->mixing && p->mix_duration - p->mix_elapsed <= seconds) {
      seconds = p->mix_duration - p->mix_elapsed;
      mix_ends = true;
    }
    if (p->has_queued) {
      const double r = TimeToHandOver(crig, p->current);
      if (r <= seconds) {
        mix_ends = mix_ends && r == seconds;
        seconds = r;
        hand_over = true;
      }
    }
    if (seconds < 0) seconds = 0;
    if (p->mixing) Advance(crig, channel, true, &p->from, seconds, false, clock, streams);
    Advance(crig, channel, false, &p->current, seconds, hand_over, clock, streams);
    if (p->mixing) {
      p->mix_elapsed += seconds;
      if (mix_ends || !(p->mix_elapsed < p->mix_duration)) {
        p->mixing = false;
        p->from = Motion{};
      }
    }
    clock += seconds;
    left -= seconds;
    if (hand_over) {
      p->has_queued = false;
      HandOver(crig, p, p->queued, p->queued_mix, s, f);
    }
    if (!(left > 0) && !hand_over && !mix_ends) break;
    if (!(left > 0) && !p->has_queued && !p->mixing) break;
  }
}

void SanitiseTrack(const Rig& crig, AnimatorTrack* t) {
  const std::size_t n = crig.pose_count();
  t->behaviours = SanitisedBehaviours(t->behaviours, crig.pose_count());
  SanitiseBehaviourState(&t->behaviour_state);
  t->current = SanitisedMotion(crig, t->current, false);
  t->from = SanitisedMotion(crig, t->from, true);
  if (t->mixing && (!(t->mix_duration > 0) || !(t->mix_duration <= kMaxAnimatorMix) || !std::isfinite(t->mix_elapsed) ||
                    (t->from.kind == MotionKind::kSnapshot && !SnapshotUsable(*t, n))))
    t->mixing = false;
  if (t->mixing) t->mix_elapsed = ClampTo(t->mix_elapsed, 0, t->mix_duration);
  if (t->has_pending) {
    t->pending = SanitisedMotion(crig, t->pending, false);
    t->pending_mix = NonNegative(t->pending_mix, kMaxAnimatorMix);
  }
  if (t->has_queued) {
    t->queued = SanitisedMotion(crig, t->queued, false);
    t->queued_mix = NonNegative(t->queued_mix, kMaxAnimatorMix);
  }
}

}  // namespace posemorph::detail
