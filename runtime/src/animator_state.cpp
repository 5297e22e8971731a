// SPDX-License-Identifier: MIT
// An animator's state as bytes for late joiners (animator.h: AnimatorSave,
// AnimatorLoad). Layout, little-endian (docs/animation.md):
//   "PMA" 1 (version), u8 channel count, then per channel:
//   u8 flags: 1 mixing, 2 a pending command, 4 a queued path, 8 a running
//     clock, 16 behaviours; the rest 0
//   motion current; mixing: motion from, f64 mix_elapsed, f64 mix_duration
//     (and from a snapshot: 3 N f64); pending: motion, f64 mix; queued:
//     motion, f64 mix
//   clock: f64 clock, f64 since_step
//   behaviours: u8 enabled (1 blink, 2 breath, 4 look-at, 8 spring), u8
//     primed (of those enabled), the enabled ones' parameters, then the
//     primed ones' state
//   motion: u8 kind | 4 loop | 8 ended | 16 speed 1; a path: u32 path, f64
//     time (and f64 speed without the speed-1 bit); a point or a snapshot:
//     f64 x, f64 y.
#include <cmath>
#include <cstring>

#include "posemorph/animator.h"
#include "animator_behaviours.h"
#include "animator_playhead.h"

namespace posemorph {
namespace {

constexpr unsigned char kMagic[3] = {'P', 'M', 'A'};
constexpr unsigned char kVersion = 1;
enum ChannelFlag : unsigned { kMixing = 1, kPending = 2, kQueued = 4, kClock = 8, kBehaviours = 16 };
enum MotionFlag : unsigned { kLoop = 4, kEnded = 8, kSpeedOne = 16 };

// Writes, or (with no output) only counts.
struct Writer {
  unsigned char* out = nullptr;
  std::size_t n = 0;
  void U8(unsigned v) {
    if (out) out[n] = static_cast<unsigned char>(v);
    ++n;
  }
  void U32(std::uint32_t v) {
    for (int i = 0; i < 4; ++i) U8((v >> (8 * i)) & 0xFFu);
  }
  void U64(std::uint64_t v) {
    for (int i = 0; i < 8; ++i) U8(unsigned(v >> (8 * i)) & 0xFFu);
  }
  void F64(double v) {
    std::uint64_t u = 0;
    std::memcpy(&u, &v, 8);
    U64(u);
  }
};

// Reads within bounds; `ok` turns false at the first read past the end.
struct Reader {
  const unsigned char* p;
  std::size_t size, n = 0;
  bool ok = true;
  unsigned U8() {
    if (n >= size) return ok = false, 0u;
    return p[n++];
  }
  std::uint32_t U32() {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= std::uint32_t(U8()) << (8 * i);
    return v;
  }
  std::uint64_t U64() {
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= std::uint64_t(U8()) << (8 * i);
    return v;
  }
  double F64() {
    const std::uint64_t u = U64();
    double v = 0;
    std::memcpy(&v, &u, 8);
    return v;
  }
};

void PutMotion(Writer* w, const Motion& m) {
  const bool path = m.kind == MotionKind::kPath, one = path && m.speed == 1;
  // loop and ended mean something only on a path.
  w->U8(unsigned(m.kind) | (path && m.loop ? kLoop : 0u) | (path && m.ended ? kEnded : 0u) | (one ? kSpeedOne : 0u));
  if (path) {
    w->U32(m.path);
    w->F64(m.time);
    if (!one) w->F64(m.speed);
  } else if (m.kind == MotionKind::kPoint || m.kind == MotionKind::kSnapshot) {
    w->F64(m.x);
    w->F64(m.y);
  }
}

bool GetMotion(Reader* r, const Rig& crig, bool allow_snapshot, Motion* m) {
  const unsigned b = r->U8();
  const unsigned kind = b & 3u;
  if ((b & ~31u) || (kind == unsigned(MotionKind::kSnapshot) && !allow_snapshot)) return false;
  *m = Motion{};
  m->kind = MotionKind(kind);
  m->loop = (b & kLoop) != 0;
  m->ended = (b & kEnded) != 0;
  if (m->kind == MotionKind::kPath) {
    m->path = r->U32();
    m->time = r->F64();
    m->speed = (b & kSpeedOne) ? 1.0 : r->F64();
    if (r->ok && m->path >= crig.path_count()) return false;
  } else {
    if (b & (kLoop | kEnded | kSpeedOne)) return false;
    if (m->kind != MotionKind::kRest) m->x = r->F64(), m->y = r->F64();
  }
  return r->ok;
}

unsigned Enabled(const Behaviours& b) {
  return (b.blink.enabled ? 1u : 0u) | (b.breath.enabled ? 2u : 0u) | (b.look_at.enabled ? 4u : 0u) |
         (b.spring.enabled ? 8u : 0u);
}

// One channel's track (sanitised, as an update would read it).
void PutTrack(Writer* w, const Rig& crig, const AnimatorTrack& t) {
  const BehaviourState& st = t.behaviour_state;
  const unsigned enabled = Enabled(t.behaviours), primed = st.primed & enabled;
  const bool clock = st.clock != 0 || st.since_step != 0 || std::signbit(st.clock) || std::signbit(st.since_step);
  w->U8((t.mixing ? kMixing : 0u) | (t.has_pending ? kPending : 0u) | (t.has_queued ? kQueued : 0u) |
        (clock ? kClock : 0u) | (enabled ? kBehaviours : 0u));
  PutMotion(w, t.current);
  if (t.mixing) {
    PutMotion(w, t.from);
    w->F64(t.mix_elapsed);
    w->F64(t.mix_duration);
    if (t.from.kind == MotionKind::kSnapshot)
      for (std::size_t i = 0; i < 3 * std::size_t(crig.pose_count()); ++i) w->F64(t.snapshot[i]);
  }
  if (t.has_pending) PutMotion(w, t.pending), w->F64(t.pending_mix);
  if (t.has_queued) PutMotion(w, t.queued), w->F64(t.queued_mix);
  if (clock) w->F64(st.clock), w->F64(st.since_step);
  if (!enabled) return;
  w->U8(enabled);
  w->U8(primed);
  const Behaviours& b = t.behaviours;
  if (enabled & 1u) {
    w->U32(b.blink.pose);
    w->F64(b.blink.interval), w->F64(b.blink.jitter), w->F64(b.blink.duration), w->F64(b.blink.strength);
    w->U64(b.blink.seed);
  }
  if (enabled & 2u) w->F64(b.breath.period), w->F64(b.breath.x), w->F64(b.breath.y);
  if (enabled & 4u) {
    w->F64(b.look_at.x), w->F64(b.look_at.y), w->F64(b.look_at.smoothing), w->F64(b.look_at.strength);
  }
  if (enabled & 8u) w->F64(b.spring.frequency), w->F64(b.spring.damping), w->F64(b.spring.strength);
  if (primed & 1u) w->F64(st.blink_next), w->U64(st.blink_rng);
  if (primed & 2u) w->F64(st.breath_origin);
  if (primed & 4u)
    for (double v : st.look) w->F64(v);
  if (primed & 8u) {
    for (double v : st.spring) w->F64(v);
    for (double v : st.lag) w->F64(v);
  }
}

bool GetTrack(Reader* r, const Rig& crig, AnimatorTrack* t) {
  *t = AnimatorTrack{};
  const unsigned flags = r->U8();
  if (flags & ~31u) return false;
  t->mixing = (flags & kMixing) != 0;
  t->has_pending = (flags & kPending) != 0;
  t->has_queued = (flags & kQueued) != 0;
  if (!GetMotion(r, crig, false, &t->current)) return false;
  if (t->mixing) {
    if (!GetMotion(r, crig, true, &t->from)) return false;
    t->mix_elapsed = r->F64();
    t->mix_duration = r->F64();
    if (t->from.kind == MotionKind::kSnapshot)
      for (std::size_t i = 0; i < 3 * std::size_t(crig.pose_count()); ++i) t->snapshot[i] = r->F64();
  }
  if (t->has_pending && !GetMotion(r, crig, false, &t->pending)) return false;
  if (t->has_pending) t->pending_mix = r->F64();
  if (t->has_queued && !GetMotion(r, crig, false, &t->queued)) return false;
  if (t->has_queued) t->queued_mix = r->F64();
  BehaviourState& st = t->behaviour_state;
  if (flags & kClock) st.clock = r->F64(), st.since_step = r->F64();
  if (!(flags & kBehaviours)) return r->ok;
  const unsigned enabled = r->U8(), primed = r->U8();
  if (!enabled || (enabled & ~15u) || (primed & ~enabled)) return false;
  Behaviours& b = t->behaviours;
  b.blink.enabled = (enabled & 1u) != 0;
  b.breath.enabled = (enabled & 2u) != 0;
  b.look_at.enabled = (enabled & 4u) != 0;
  b.spring.enabled = (enabled & 8u) != 0;
  if (enabled & 1u) {
    b.blink.pose = r->U32();
    b.blink.interval = r->F64(), b.blink.jitter = r->F64(), b.blink.duration = r->F64();
    b.blink.strength = r->F64();
    b.blink.seed = r->U64();
  }
  if (enabled & 2u) b.breath.period = r->F64(), b.breath.x = r->F64(), b.breath.y = r->F64();
  if (enabled & 4u) {
    b.look_at.x = r->F64(), b.look_at.y = r->F64(), b.look_at.smoothing = r->F64();
    b.look_at.strength = r->F64();
  }
  if (enabled & 8u) b.spring.frequency = r->F64(), b.spring.damping = r->F64(), b.spring.strength = r->F64();
  st.primed = primed;
  if (primed & 1u) st.blink_next = r->F64(), st.blink_rng = r->U64();
  if (primed & 2u) st.breath_origin = r->F64();
  if (primed & 4u)
    for (double& v : st.look) v = r->F64();
  if (primed & 8u) {
    for (double& v : st.spring) v = r->F64();
    for (double& v : st.lag) v = r->F64();
  }
  return r->ok;
}

bool Usable(const Rig& rig, std::size_t tracks) { return rig.loaded() && tracks >= rig.channel_count(); }

// The tracks as an update would read them, written (or counted).
void PutState(Writer* w, const Rig& rig, Span<const AnimatorTrack> tracks) {
  for (unsigned char c : kMagic) w->U8(c);
  w->U8(kVersion);
  w->U8(rig.channel_count());
  for (std::uint32_t c = 0; c < rig.channel_count(); ++c) {
    const Rig& crig = *rig.channel_rig(c);
    AnimatorTrack t = tracks[c];
    detail::SanitiseTrack(crig, &t);
    PutTrack(w, crig, t);
  }
}

}  // namespace

std::size_t AnimatorStateSize(const Rig& rig, Span<const AnimatorTrack> tracks) {
  if (!Usable(rig, tracks.size) || !tracks.data) return 0;
  Writer w;
  PutState(&w, rig, tracks);
  return w.n;
}

bool AnimatorSave(const Rig& rig, Span<const AnimatorTrack> tracks, Span<unsigned char> out, std::size_t* written) {
  const std::size_t size = AnimatorStateSize(rig, tracks);
  if (!size || !out.data || out.size < size || !written) return false;
  Writer w;
  w.out = out.data;
  PutState(&w, rig, tracks);
  *written = w.n;
  return true;
}

bool AnimatorLoad(const Rig& rig, Span<const unsigned char> bytes, Span<AnimatorTrack> tracks) {
  if (!Usable(rig, tracks.size) || !tracks.data || !bytes.data) return false;
  // First read it all into scratch tracks, one channel at a time, to check
  // it; then again into the caller's.
  for (int pass = 0; pass < 2; ++pass) {
    Reader r{bytes.data, bytes.size};
    for (unsigned char c : kMagic)
      if (r.U8() != c) return false;
    if (r.U8() != kVersion || r.U8() != rig.channel_count() || !r.ok) return false;
    for (std::uint32_t c = 0; c < rig.channel_count(); ++c) {
      AnimatorTrack scratch;
      AnimatorTrack* t = pass == 0 ? &scratch : &tracks[c];
      if (!GetTrack(&r, *rig.channel_rig(c), t)) return false;
    }
    if (r.n != bytes.size) return false;
  }
  return true;
}

}  // namespace posemorph
