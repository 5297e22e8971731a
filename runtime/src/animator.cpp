// SPDX-License-Identifier: MIT
// Tracks, mixes, queues and path events (animator.h; docs/animation.md);
// the event streams and their merge are in animator_events.cpp.
// An update runs each track through at most a few segments of time, split
// where a mix ends or a queued path takes over; each segment of a path with
// events becomes a stream of crossings, and a character's streams are
// merged in time order into the caller's buffer.
#include "posemorph/animator.h"

#include <cmath>
#include <cstring>

#include "posemorph/jobs.h"
#include "posemorph/path.h"
#include "animator_events.h"

namespace posemorph {
namespace {

constexpr std::uint32_t kN = format::kMaxPoses;
constexpr int kMaxSegments = detail::kMaxAnimatorSegments;
constexpr int kMaxStreams = detail::kMaxEventStreams;
using detail::EventStream;
using detail::EventStreams;

double Clamp(double v, double lo, double hi) { return v < lo ? lo : (v > hi ? hi : v); }
// NaN -> 0; then clamped to [0, hi].
double NonNegative(double v, double hi) { return v > 0 ? (v < hi ? v : hi) : 0.0; }

const Rig* ChannelRig(const Rig& rig, std::uint32_t channel) {
  return rig.loaded() && channel < rig.channel_count() ? rig.channel_rig(channel) : nullptr;
}

bool Loops(const PathView& p, const Motion& m) { return m.loop && p.end_time() > p.start_time(); }

// A motion read from a track: any bytes become a valid motion (a stopped
// one when they name nothing the channel has).
Motion Sanitised(const Rig& crig, const Motion& in, bool allow_snapshot) {
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
    m.time = Clamp(m.time, start, end);
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

struct Weights {
  double raw[kN], limited[kN], texture[kN];
};

struct Settings {
  double sigma;
  bool limit;
};

void MotionWeights(const Rig& crig, const Motion& m, const Settings& s, Weights* w) {
  const std::size_t n = crig.pose_count();
  WeightsJob job;
  job.rig = &crig;
  MotionPoint(crig, m, &job.x, &job.y);
  job.sigma = s.sigma;
  job.limit_weights = s.limit;
  job.raw = {w->raw, n};
  job.limited = {w->limited, n};
  job.texture = {w->texture, n};
  job.Run();
}

bool SnapshotUsable(const AnimatorTrack& t, std::size_t n) {
  for (std::size_t i = 0; i < 3 * n; ++i)
    if (!(std::fabs(t.snapshot[i]) <= kMaxJobWeight)) return false;
  return true;
}

// The weights a (sanitised) track shows now.
void TrackWeights(const Rig& crig, const AnimatorTrack& t, const Settings& s, Weights* out) {
  const std::size_t n = crig.pose_count();
  MotionWeights(crig, t.current, s, out);
  if (!t.mixing) return;
  Weights from;
  if (t.from.kind == MotionKind::kSnapshot) {
    std::memcpy(from.raw, t.snapshot, n * sizeof(double));
    std::memcpy(from.limited, t.snapshot + n, n * sizeof(double));
    std::memcpy(from.texture, t.snapshot + 2 * n, n * sizeof(double));
  } else {
    MotionWeights(crig, t.from, s, &from);
  }
  const double a = Clamp(t.mix_elapsed / t.mix_duration, 0, 1), b = 1 - a;
  for (std::size_t i = 0; i < n; ++i) {
    out->raw[i] = b * from.raw[i] + a * out->raw[i];
    out->limited[i] = b * from.limited[i] + a * out->limited[i];
    out->texture[i] = b * from.texture[i] + a * out->texture[i];
  }
}

// A track read from caller memory, made valid.
void Sanitise(const Rig& crig, AnimatorTrack* t) {
  const std::size_t n = crig.pose_count();
  t->current = Sanitised(crig, t->current, false);
  t->from = Sanitised(crig, t->from, true);
  if (t->mixing && (!(t->mix_duration > 0) || !(t->mix_duration <= kMaxAnimatorMix) || !std::isfinite(t->mix_elapsed) ||
                    (t->from.kind == MotionKind::kSnapshot && !SnapshotUsable(*t, n))))
    t->mixing = false;
  if (t->mixing) t->mix_elapsed = Clamp(t->mix_elapsed, 0, t->mix_duration);
  if (t->has_pending) {
    t->pending = Sanitised(crig, t->pending, false);
    t->pending_mix = NonNegative(t->pending_mix, kMaxAnimatorMix);
  }
  if (t->has_queued) {
    t->queued = Sanitised(crig, t->queued, false);
    t->queued_mix = NonNegative(t->queued_mix, kMaxAnimatorMix);
  }
}

// Hands the track over to `m` over `mix` seconds (what every command does
// once applied). Interrupting a mix freezes its blend as the outgoing side.
void HandOver(const Rig& crig, AnimatorTrack* t, const Motion& m, double mix, const Settings& s) {
  if (!(mix > 0)) {
    t->current = m;
    t->mixing = false;
    t->from = Motion{};
    return;
  }
  if (t->mixing) {
    const std::size_t n = crig.pose_count();
    Weights now;
    TrackWeights(crig, *t, s, &now);
    std::memcpy(t->snapshot, now.raw, n * sizeof(double));
    std::memcpy(t->snapshot + n, now.limited, n * sizeof(double));
    std::memcpy(t->snapshot + 2 * n, now.texture, n * sizeof(double));
    t->from = Motion{};
    t->from.kind = MotionKind::kSnapshot;
  } else {
    t->from = t->current;
  }
  t->current = m;
  t->mixing = true;
  t->mix_elapsed = 0;
  t->mix_duration = mix;
}

// Advances a path motion by `seconds` (to its end, or its cycle's end,
// when `to_end`), adding the stream of what it crossed.
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
  if (p.events.empty() || !(t1 > t0 || closed) || !(m->speed > 0) || streams->count >= kMaxStreams) return;
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

// One track through one update: its command, its segments, its weights.
void UpdateTrack(const Rig& crig, std::uint32_t channel, AnimatorTrack* t, double dt, const Settings& s,
                 EventStreams* streams, Weights* out) {
  Sanitise(crig, t);
  if (t->has_pending) {
    t->has_pending = false;
    HandOver(crig, t, t->pending, t->pending_mix, s);
  }
  double left = dt, clock = 0;
  for (int segment = 0; segment < kMaxSegments; ++segment) {
    if (t->has_queued && t->current.kind != MotionKind::kPath) {
      t->has_queued = false;
      HandOver(crig, t, t->queued, t->queued_mix, s);
    }
    double seconds = left;
    bool mix_ends = false, hand_over = false;
    if (t->mixing && t->mix_duration - t->mix_elapsed <= seconds) {
      seconds = t->mix_duration - t->mix_elapsed;
      mix_ends = true;
    }
    if (t->has_queued) {
      const double r = TimeToHandOver(crig, t->current);
      if (r <= seconds) {
        mix_ends = mix_ends && r == seconds;
        seconds = r;
        hand_over = true;
      }
    }
    if (seconds < 0) seconds = 0;
    if (t->mixing) Advance(crig, channel, true, &t->from, seconds, false, clock, streams);
    Advance(crig, channel, false, &t->current, seconds, hand_over, clock, streams);
    if (t->mixing) {
      t->mix_elapsed += seconds;
      if (mix_ends || !(t->mix_elapsed < t->mix_duration)) {
        t->mixing = false;
        t->from = Motion{};
      }
    }
    clock += seconds;
    left -= seconds;
    if (hand_over) {
      t->has_queued = false;
      HandOver(crig, t, t->queued, t->queued_mix, s);
    }
    if (!(left > 0) && !hand_over && !mix_ends) break;
    if (!(left > 0) && !t->has_queued && !t->mixing) break;
  }
  TrackWeights(crig, *t, s, out);
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
  return Sanitised(crig, m, false);
}

}  // namespace

bool AnimatorReset(const Rig& rig, Span<AnimatorTrack> tracks) {
  if (!Valid(rig, tracks, 0)) return false;
  for (std::uint32_t c = 0; c < rig.channel_count(); ++c) tracks[c] = AnimatorTrack{};
  return true;
}

bool AnimatorPlay(const Rig& rig, Span<AnimatorTrack> tracks, std::uint32_t channel, std::uint32_t path,
                  const PlayOptions& options) {
  if (!Valid(rig, tracks, channel)) return false;
  const Rig& crig = *ChannelRig(rig, channel);
  if (path >= crig.path_count()) return false;
  AnimatorTrack& t = tracks[channel];
  t.pending = PathMotion(crig, path, options);
  t.pending_mix = NonNegative(options.mix, kMaxAnimatorMix);
  t.has_pending = true;
  t.has_queued = false;
  return true;
}

bool AnimatorQueue(const Rig& rig, Span<AnimatorTrack> tracks, std::uint32_t channel, std::uint32_t path,
                   const PlayOptions& options) {
  if (!Valid(rig, tracks, channel)) return false;
  const Rig& crig = *ChannelRig(rig, channel);
  if (path >= crig.path_count()) return false;
  AnimatorTrack& t = tracks[channel];
  t.queued = PathMotion(crig, path, options);
  t.queued_mix = NonNegative(options.mix, kMaxAnimatorMix);
  t.has_queued = true;
  return true;
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
  Weights w;
  for (std::size_t i = 0; i < count; ++i) {
    streams.count = 0;
    for (std::uint32_t c = 0; c < C; ++c) {
      const Rig& crig = *rig->channel_rig(c);
      const std::size_t n = crig.pose_count();
      const Settings s{sigma >= 0 ? Clamp(sigma, 0, 1) : crig.default_sigma(), limit_weights};
      UpdateTrack(crig, c, &tracks[i * C + c], step, s, &streams, &w);
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
