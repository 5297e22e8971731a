// SPDX-License-Identifier: MIT
// The animation layer over the jobs: per control channel, a track that
// plays a path (a gesture) once or looped at a speed, queues the next,
// follows a point set by code (a pad), stops, and hands over from one to the
// next over a mix duration without a jump; an update advances every
// character of a batch by dt, reports the path events it crossed, and
// writes each channel's weights in the layouts MorphBatchJob and AttachJob
// read; small procedural behaviours (blink, breath, look-at, a spring) run
// on top of what a track plays. docs/animation.md is the guide.
//
// What a mix blends: the two motions' weight vectors (raw, limited and
// texture, each as WeightsJob gives it at the motion's point), as
// (1 - a) x outgoing + a x incoming with a = elapsed / duration. Each is a
// partition of unity, so the blend is one too, and it passes through no pose
// that neither motion shows (blending the two pose-space points would cross
// the poses between them). The outgoing motion keeps playing during the mix
// (and reports its events); a command that interrupts a mix freezes the
// blend it had reached (a snapshot of its weights, which reports nothing)
// and mixes from that.
//
// Determinism: an update is plain IEEE-754 double arithmetic in a fixed
// order, so the same commands and dt sequence give the same bits on every
// compiler, target and kernel path. Nothing here allocates or throws.
#pragma once
#include "posemorph/export.h"
#include <cstddef>
#include <cstdint>

#include "posemorph/rig.h"
#include "posemorph/rig_format.h"
#include "posemorph/span.h"

namespace posemorph {

// The largest dt an update takes: beyond it (and for +inf) it counts as
// this; a NaN or negative dt counts as 0.
constexpr double kMaxAnimatorStep = 1e9;
// Speeds, mix durations and start offsets are clamped to [0, this]
// (a NaN speed or mix counts as 0).
constexpr double kMaxAnimatorSpeed = 1e6;
constexpr double kMaxAnimatorMix = 1e6;

enum class MotionKind : std::uint8_t {
  kRest = 0,      // the channel's pose 0 (its point): a stopped track
  kPath = 1,      // a path played from its clock
  kPoint = 2,     // a pose-space point set by code (a pad)
  kSnapshot = 3,  // a mix frozen by an interrupting command (only ever outgoing)
};

// What one layer of a track shows.
struct Motion {
  MotionKind kind = MotionKind::kRest;
  bool loop = false;
  bool ended = false;      // a path played once has reached its last key (and reported its events there)
  std::uint32_t path = 0;  // kPath: in the channel's rig
  double time = 0;         // kPath: on the path's clock; looping: within [first key, last key)
  double speed = 1;        // kPath: path seconds per second, >= 0
  double x = 0, y = 0;     // kPoint
};

// How to play a path.
struct PlayOptions {
  double speed = 1;
  // -1: as the path says (its "loop"); 0: once, holding the last key; 1: looped.
  int loop = -1;
  // Seconds over which the track hands over from what it shows now; 0 cuts.
  double mix = 0.2;
  // Where on the path's clock to start, in seconds after its first key.
  double start = 0;
};

// Procedural motion: small behaviours declared per channel on top of what
// the track plays (docs/animation.md, "Behaviours"). Each acts in pose
// space: look-at, breath and the spring move every motion's point before
// its weights are taken (p -> p + strength (look - p) + breath + spring);
// a blink pulses the channel's weights toward one pose afterwards. Look-at
// and the spring integrate on a fixed step (kBehaviourStep, shown
// interpolated between the last two steps), breath and blinks are functions
// of the channel's clock, so the pose at a given time does not depend on
// the update rate. Parameters are clamped to the ranges given; a behaviour
// that is not enabled costs nothing and contributes nothing.
struct BlinkBehaviour {
  bool enabled = false;
  std::uint32_t pose = 0;  // of the channel's rig; out of range: no blink
  double interval = 4;     // mean seconds from one blink to the next, [0.02, 1e6]
  double jitter = 0.5;     // each interval is interval x (1 + jitter u), u uniform in [-1, 1); [0, 0.95]
  double duration = 0.15;  // seconds of one blink, [0.001, 60]; intervals are never shorter
  double strength = 1;     // the pose's weight at the blink's height, [0, 1]
  std::uint64_t seed = 1;  // of the jitter's generator (splitmix64): give each character its own
};
struct BreathBehaviour {
  bool enabled = false;
  double period = 3.5;  // seconds, [0.05, 1e6]
  double x = 0, y = 0;  // amplitude: the offset at the breath's height, pose-space units, [-1e3, 1e3]
};
struct LookAtBehaviour {
  bool enabled = false;
  double x = 0, y = 0;     // the target (AnimatorLookAt sets it); non-finite: the look point stays
  double smoothing = 0.1;  // seconds: the look point closes 1/e of its gap to the target in this, [0, 1e3]
  double strength = 1;     // 1: the channel shows the look point; 0: its motion; [0, 1]
};
struct SpringBehaviour {
  bool enabled = false;
  double frequency = 2.5;  // Hz, [0.01, 20]
  double damping = 0.3;    // ratio to critical damping, [0, 100]
  double strength = 1;     // scale of the lag shown, [0, 4]
};
struct Behaviours {
  BlinkBehaviour blink;
  BreathBehaviour breath;
  LookAtBehaviour look_at;
  SpringBehaviour spring;  // secondary motion
};

// The fixed step of look-at and the spring, seconds. A step whose time an
// update reaches within kBehaviourStepSnap (rounding) is taken in that
// update, so a command at a step's time (at a frame time shared by 30, 60
// and 144 Hz, say) always takes effect from the next step.
constexpr double kBehaviourStep = 1.0 / 120.0;
constexpr double kBehaviourStepSnap = 1e-9 * kBehaviourStep;
// An update that spans more fixed steps than this (10 s) runs the last of
// them and settles the spring and the look point at their targets first.
constexpr int kMaxBehaviourSteps = 1200;

// What the behaviours remember between updates (part of the track).
struct BehaviourState {
  std::uint32_t primed = 0;  // bit per behaviour that has started: 1 blink, 2 breath, 4 look-at, 8 spring
  std::uint32_t reserved = 0;
  double clock = 0;          // seconds the channel has run
  double since_step = 0;     // seconds since the last fixed step, [-kBehaviourStepSnap, kBehaviourStep)
  double breath_origin = 0;  // clock at which breath started
  double blink_next = 0;     // clock at which the next (or current) blink starts
  std::uint64_t blink_rng = 0;
  double look[4] = {};    // look point at the last two steps: x0, y0, x1, y1
  double spring[4] = {};  // spring point and velocity: x, y, vx, vy
  double lag[4] = {};     // spring point minus its target at the last two steps
};

// One channel of one character. A plain value: copy it, store it, compare
// it; Animator functions change it. Its size is fixed (sizeof, about 2
// KB, most of it the snapshot a rare interrupted mix needs), so a
// character's animator is rig.channel_count() tracks in caller memory.
struct AnimatorTrack {
  Motion current;  // what it plays
  Motion from;     // during a mix: what it hands over from
  bool mixing = false;
  double mix_elapsed = 0, mix_duration = 0;
  // A command since the last update: applied at the start of the next.
  bool has_pending = false;
  Motion pending;
  double pending_mix = 0;
  // What starts when the current path ends (once: at its last key; looped:
  // at the end of the cycle in progress; a point or a stopped track: at once).
  bool has_queued = false;
  Motion queued;
  double queued_mix = 0;
  Behaviours behaviours;
  BehaviourState behaviour_state;
  // from.kind == kSnapshot: raw, limited, texture weights, N each (and
  // from.x, from.y the point the spring followed then).
  double snapshot[3 * format::kMaxPoses] = {};
};

// Commands on one character's tracks (rig.channel_count() of them, indexed
// by channel). Each takes effect at the start of the next update, so
// commands between two updates happen at the same instant; the last of
// several on one channel wins (a queue entry is kept apart). They return
// false, changing nothing, when the rig is not loaded, `tracks` is shorter
// than the channel count, the channel or path is out of range.
//
// Initialise: every track stopped (at the channel's pose 0).
PM_API bool AnimatorReset(const Rig& rig, Span<AnimatorTrack> tracks);
// Play path `path` of the channel's rig (Rig::channel_rig) now, handing over
// over options.mix seconds; clears the channel's queue.
PM_API bool AnimatorPlay(const Rig& rig, Span<AnimatorTrack> tracks, std::uint32_t channel, std::uint32_t path,
                         const PlayOptions& options = PlayOptions());
// Play `path` when the current one ends (see AnimatorTrack::queued),
// replacing what was queued; options.mix is the hand-over then.
PM_API bool AnimatorQueue(const Rig& rig, Span<AnimatorTrack> tracks, std::uint32_t channel, std::uint32_t path,
                          const PlayOptions& options = PlayOptions());
// Follow a pose-space point set by code. A track already following a point
// moves to the new one at once (no mix: the code sets it every frame);
// otherwise it hands over over `mix` seconds. Non-finite coordinates are
// taken as WeightsJob takes them (finite weights for any input).
PM_API bool AnimatorSetPoint(const Rig& rig, Span<AnimatorTrack> tracks, std::uint32_t channel, double x, double y,
                             double mix = 0.2);
// Hand over to the channel's pose 0 over `mix` seconds; clears the queue.
PM_API bool AnimatorStop(const Rig& rig, Span<AnimatorTrack> tracks, std::uint32_t channel, double mix = 0.2);
// Change the speed of the path the channel plays (and of a pending one).
PM_API bool AnimatorSetSpeed(const Rig& rig, Span<AnimatorTrack> tracks, std::uint32_t channel, double speed);

// Declare the channel's behaviours (replacing its previous ones). A
// behaviour that was off starts from where the channel is, without a jump;
// one switched off stops contributing at once. Takes effect at once.
PM_API bool AnimatorSetBehaviours(const Rig& rig, Span<AnimatorTrack> tracks, std::uint32_t channel,
                                  const Behaviours& behaviours);
// Move the channel's look-at target (its look point follows it over the
// behaviour's smoothing time).
PM_API bool AnimatorLookAt(const Rig& rig, Span<AnimatorTrack> tracks, std::uint32_t channel, double x, double y);

// Late joiners: one character's animator as bytes, and back. The bytes
// (a versioned little-endian layout, docs/animation.md "State for late
// joiners") hold every field that affects later updates, each double as
// its 8 bytes, so a peer that loads them and then runs the same commands
// and dt gives the same bits as the peer that saved them. 5 bytes of
// header, then per channel: a stopped one takes 2 bytes; a path playing at
// speed 1 on a running clock 30; mixes, commands not yet applied, a frozen
// blend (24 per pose) and declared behaviours add theirs
// (AnimatorStateSize). Parameters of a behaviour that is switched off are
// not carried (declaring it again restores them).
//
// The largest state of one channel, bytes: flags, four motions of at most
// 21 bytes, the mix and a frozen blend, two mix durations, the clock, then
// the behaviours' masks, parameters and state.
constexpr std::size_t kMaxAnimatorStateBytesPerChannel =
    1 + 4 * 21 + 16 + 24 * format::kMaxPoses + 2 * 8 + 16 + 2 + (44 + 24 + 32 + 24) + (16 + 8 + 32 + 64);
// What AnimatorSave writes for these tracks (0 when the rig is not loaded
// or `tracks` is shorter than its channel count).
PM_API std::size_t AnimatorStateSize(const Rig& rig, Span<const AnimatorTrack> tracks);
// Writes the state into `out` and its length into *written; false (writing
// nothing) when AnimatorStateSize is 0 or above out.size.
PM_API bool AnimatorSave(const Rig& rig, Span<const AnimatorTrack> tracks, Span<unsigned char> out,
                         std::size_t* written);
// Reads a state AnimatorSave wrote for this rig into `tracks` (its channel
// count of them). The bytes are hostile: false, changing nothing, for a
// wrong version or channel count, a size that does not match what its
// flags say, a reserved bit set, a kind out of the enum or a path out of
// range; values are taken as any track's are (animator.h: finite weights
// for any bytes).
PM_API bool AnimatorLoad(const Rig& rig, Span<const unsigned char> bytes, Span<AnimatorTrack> tracks);

// An event an update crossed.
struct AnimatorEvent {
  std::uint32_t character = 0;  // in the batch
  std::uint32_t channel = 0;
  std::uint32_t event = 0;  // index into rig.channel_rig(channel)->event(...)
  bool outgoing = false;    // reported by the motion a mix hands over from
  double time = 0;          // seconds into the update when it was crossed, in [0, dt]
};

// Advances `count` characters sharing one rig by dt and writes their
// weights. Per track, in order: the pending command is applied; the
// behaviours that were switched on start; look-at and the spring take the
// fixed steps that fall within dt; time runs, split where a mix ends or a
// queued path starts (so the result does not depend on how dt is split, up
// to rounding); then the weights are those of the track's motion, or of
// its mix, at points moved by the behaviours, pulsed by a blink.
//
// Events: a path's event at time e is crossed when the playhead passes it,
// half-open: a playhead going from t0 to t1 crosses [t0, t1); a path played
// once also crosses its last key's time on reaching it, and then nothing
// more. A looping path's events repeat every cycle (an event at the last
// key's time is the next cycle's first-key instant). Each crossing is
// reported once, character after character, within a character in time
// order (ties: channel order, outgoing before incoming, event order). When
// `events` is full the rest are counted in *events_missed; the first
// *event_count are written.
//
// Output layouts: channel 0's weights character after character (count x N,
// as MorphBatchJob reads them); channels 1 .. C-1 in AttachJob's layout
// (count x rig.attached_weight_count(): channel by channel, each count x
// that channel's pose count).
//
// Validate() fails (and Run() does nothing) when: rig is null or not
// loaded; count is above kMaxAnimatorBatch; tracks holds fewer than count x
// rig.channel_count(); weights or limited_weights holds fewer than count x
// N; texture_weights is given but shorter; the rig has attachments and
// attached_weights or attached_limited_weights holds fewer than count x
// rig.attached_weight_count(), or attached_texture_weights is given but
// shorter; event_count or events_missed is null while `events` is given.
// A track's fields are checked as it is read (a path index out of range,
// a kind out of the enum or a non-finite time is taken as a stopped
// track), so any bytes give finite weights.
struct PM_API AnimatorUpdateJob {
  const Rig* rig = nullptr;
  std::size_t count = 1;  // characters
  double dt = 0;          // seconds (see kMaxAnimatorStep)
  double sigma = -1;      // texture sharpening; < 0 or NaN: each channel rig's default
  bool limit_weights = true;
  Span<AnimatorTrack> tracks;  // count x C, character after character
  Span<double> weights;        // count x N
  Span<double> limited_weights;
  Span<double> texture_weights;   // optional
  Span<double> attached_weights;  // count x attached_weight_count (layout above)
  Span<double> attached_limited_weights;
  Span<double> attached_texture_weights;   // optional
  Span<AnimatorEvent> events;              // optional
  std::size_t* event_count = nullptr;      // written: events written
  std::uint64_t* events_missed = nullptr;  // written: crossings that did not fit (saturating)

  bool Validate() const;
  bool Run() const;
};

constexpr std::size_t kMaxAnimatorBatch = std::size_t(1) << 24;

}  // namespace posemorph
