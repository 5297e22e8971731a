// SPDX-License-Identifier: MIT
// The C API for the animator (posemorph/animator.h): tracks in caller
// memory, commands, the batch update, path events.
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "c_api_internal.h"
#include "posemorph/animator.h"
#include "posemorph/posemorph.h"

using namespace posemorph::c_api;  // NOLINT(google-build-using-namespace): the C API's own helpers
using posemorph::AnimatorTrack;
using posemorph::Span;

static_assert(PM_ANIMATOR_ALIGNMENT >= alignof(AnimatorTrack) && PM_ANIMATOR_ALIGNMENT % alignof(AnimatorTrack) == 0,
              "published alignment");

namespace {

// The tracks of `count` characters in caller memory (an empty span when the
// memory is misaligned or too short).
int Tracks(const pm_rig* rig, void* tracks, size_t capacity, size_t count, Span<AnimatorTrack>* out) {
  if (!rig || !tracks || !Aligned(static_cast<AnimatorTrack*>(tracks))) return PM_ERROR_INVALID_ARGUMENT;
  const std::size_t C = rig->rig.channel_count();
  if (count > posemorph::kMaxAnimatorBatch) return PM_ERROR_INVALID_ARGUMENT;
  if (capacity / sizeof(AnimatorTrack) < count * C) return PM_ERROR_BUFFER_TOO_SMALL;
  *out = {static_cast<AnimatorTrack*>(tracks), count * C};
  return PM_OK;
}

// One character's tracks.
int CharacterTracks(const pm_rig* rig, void* tracks, size_t capacity, size_t character, Span<AnimatorTrack>* out) {
  if (character >= posemorph::kMaxAnimatorBatch) return PM_ERROR_INVALID_ARGUMENT;
  Span<AnimatorTrack> all;
  const int r = Tracks(rig, tracks, capacity, character + 1, &all);
  if (r != PM_OK) return r;
  const std::size_t C = rig->rig.channel_count();
  *out = {all.data + character * C, C};
  return PM_OK;
}

posemorph::PlayOptions Options(const pm_play_options* o) {
  posemorph::PlayOptions p;
  if (o) p.speed = o->speed, p.loop = o->loop, p.mix = o->mix, p.start = o->start;
  return p;
}

int Result(bool ok) { return ok ? PM_OK : PM_ERROR_INVALID_ARGUMENT; }

}  // namespace

extern "C" {

size_t pm_animator_size(const pm_rig* rig, size_t count) {
  if (!rig || count > posemorph::kMaxAnimatorBatch) return 0;
  return count * rig->rig.channel_count() * sizeof(AnimatorTrack);
}

int pm_animator_reset(const pm_rig* rig, void* tracks, size_t capacity, size_t count) {
  Span<AnimatorTrack> all;
  const int r = Tracks(rig, tracks, capacity, count, &all);
  if (r != PM_OK) return r;
  const std::size_t C = rig->rig.channel_count();
  for (std::size_t i = 0; i < count; ++i) posemorph::AnimatorReset(rig->rig, {all.data + i * C, C});
  return PM_OK;
}

void pm_play_options_default(pm_play_options* out) {
  if (!out) return;
  const posemorph::PlayOptions p;
  out->speed = p.speed, out->loop = p.loop, out->mix = p.mix, out->start = p.start;
}

int pm_animator_play(const pm_rig* rig, void* tracks, size_t capacity, size_t character, uint32_t channel,
                     uint32_t path, const pm_play_options* options) {
  Span<AnimatorTrack> t;
  const int r = CharacterTracks(rig, tracks, capacity, character, &t);
  return r != PM_OK ? r : Result(posemorph::AnimatorPlay(rig->rig, t, channel, path, Options(options)));
}

int pm_animator_queue(const pm_rig* rig, void* tracks, size_t capacity, size_t character, uint32_t channel,
                      uint32_t path, const pm_play_options* options) {
  Span<AnimatorTrack> t;
  const int r = CharacterTracks(rig, tracks, capacity, character, &t);
  return r != PM_OK ? r : Result(posemorph::AnimatorQueue(rig->rig, t, channel, path, Options(options)));
}

int pm_animator_set_point(const pm_rig* rig, void* tracks, size_t capacity, size_t character, uint32_t channel,
                          double x, double y, double mix) {
  Span<AnimatorTrack> t;
  const int r = CharacterTracks(rig, tracks, capacity, character, &t);
  return r != PM_OK ? r : Result(posemorph::AnimatorSetPoint(rig->rig, t, channel, x, y, mix));
}

int pm_animator_stop(const pm_rig* rig, void* tracks, size_t capacity, size_t character, uint32_t channel, double mix) {
  Span<AnimatorTrack> t;
  const int r = CharacterTracks(rig, tracks, capacity, character, &t);
  return r != PM_OK ? r : Result(posemorph::AnimatorStop(rig->rig, t, channel, mix));
}

int pm_animator_set_speed(const pm_rig* rig, void* tracks, size_t capacity, size_t character, uint32_t channel,
                          double speed) {
  Span<AnimatorTrack> t;
  const int r = CharacterTracks(rig, tracks, capacity, character, &t);
  return r != PM_OK ? r : Result(posemorph::AnimatorSetSpeed(rig->rig, t, channel, speed));
}

void pm_behaviours_default(pm_behaviours* out) {
  if (!out) return;
  const posemorph::Behaviours b;
  out->blink_enabled = 0, out->blink_pose = b.blink.pose, out->blink_interval = b.blink.interval;
  out->blink_jitter = b.blink.jitter, out->blink_duration = b.blink.duration, out->blink_strength = b.blink.strength;
  out->blink_seed = b.blink.seed;
  out->breath_enabled = 0, out->breath_period = b.breath.period, out->breath_x = b.breath.x;
  out->breath_y = b.breath.y;
  out->look_at_enabled = 0, out->look_at_x = b.look_at.x, out->look_at_y = b.look_at.y;
  out->look_at_smoothing = b.look_at.smoothing, out->look_at_strength = b.look_at.strength;
  out->spring_enabled = 0, out->spring_frequency = b.spring.frequency, out->spring_damping = b.spring.damping;
  out->spring_strength = b.spring.strength;
}

int pm_animator_set_behaviours(const pm_rig* rig, void* tracks, size_t capacity, size_t character, uint32_t channel,
                               const pm_behaviours* in) {
  if (!in) return PM_ERROR_INVALID_ARGUMENT;
  Span<AnimatorTrack> t;
  const int r = CharacterTracks(rig, tracks, capacity, character, &t);
  if (r != PM_OK) return r;
  posemorph::Behaviours b;
  b.blink.enabled = in->blink_enabled != 0, b.blink.pose = in->blink_pose, b.blink.interval = in->blink_interval;
  b.blink.jitter = in->blink_jitter, b.blink.duration = in->blink_duration, b.blink.strength = in->blink_strength;
  b.blink.seed = in->blink_seed;
  b.breath.enabled = in->breath_enabled != 0, b.breath.period = in->breath_period, b.breath.x = in->breath_x;
  b.breath.y = in->breath_y;
  b.look_at.enabled = in->look_at_enabled != 0, b.look_at.x = in->look_at_x, b.look_at.y = in->look_at_y;
  b.look_at.smoothing = in->look_at_smoothing, b.look_at.strength = in->look_at_strength;
  b.spring.enabled = in->spring_enabled != 0, b.spring.frequency = in->spring_frequency;
  b.spring.damping = in->spring_damping, b.spring.strength = in->spring_strength;
  return Result(posemorph::AnimatorSetBehaviours(rig->rig, t, channel, b));
}

int pm_animator_look_at(const pm_rig* rig, void* tracks, size_t capacity, size_t character, uint32_t channel, double x,
                        double y) {
  Span<AnimatorTrack> t;
  const int r = CharacterTracks(rig, tracks, capacity, character, &t);
  return r != PM_OK ? r : Result(posemorph::AnimatorLookAt(rig->rig, t, channel, x, y));
}

// The update writes its events as posemorph::AnimatorEvent into the
// caller's buffer, then turns each into a pm_animator_event in place (the
// same size and alignment; copied through bytes).
static_assert(sizeof(pm_animator_event) == sizeof(posemorph::AnimatorEvent), "events convert in place");
static_assert(alignof(pm_animator_event) == alignof(posemorph::AnimatorEvent), "events convert in place");

int pm_animator_update(const pm_rig* rig, void* tracks, size_t capacity, size_t count, double dt, double sigma,
                       int limit_weights, double* weights, double* limited_weights, double* texture_weights,
                       size_t weights_capacity, double* attached_weights, double* attached_limited_weights,
                       double* attached_texture_weights, size_t attached_capacity, pm_animator_event* events,
                       size_t events_capacity, size_t* event_count, uint64_t* events_missed) {
  Span<AnimatorTrack> all;
  const int r = Tracks(rig, tracks, capacity, count, &all);
  if (r != PM_OK) return r;
  if (!weights || !limited_weights || (events && (!event_count || !events_missed))) return PM_ERROR_INVALID_ARGUMENT;
  if (!Aligned(weights) || !Aligned(limited_weights) || (texture_weights && !Aligned(texture_weights)))
    return PM_ERROR_INVALID_ARGUMENT;
  const posemorph::Rig& R = rig->rig;
  const std::size_t N = R.pose_count(), A = R.attached_weight_count();
  if (weights_capacity / (N ? N : 1) < count) return PM_ERROR_BUFFER_TOO_SMALL;
  if (A) {
    if (!attached_weights || !attached_limited_weights) return PM_ERROR_INVALID_ARGUMENT;
    if (!Aligned(attached_weights) || !Aligned(attached_limited_weights) ||
        (attached_texture_weights && !Aligned(attached_texture_weights)))
      return PM_ERROR_INVALID_ARGUMENT;
    if (attached_capacity / A < count) return PM_ERROR_BUFFER_TOO_SMALL;
  }
  if (events && !Aligned(events)) return PM_ERROR_INVALID_ARGUMENT;
  posemorph::AnimatorUpdateJob job;
  job.rig = &R, job.count = count, job.dt = dt, job.sigma = sigma, job.limit_weights = limit_weights != 0;
  job.tracks = all;
  job.weights = {weights, count * N}, job.limited_weights = {limited_weights, count * N};
  if (texture_weights) job.texture_weights = {texture_weights, count * N};
  if (A) {
    job.attached_weights = {attached_weights, count * A};
    job.attached_limited_weights = {attached_limited_weights, count * A};
    if (attached_texture_weights) job.attached_texture_weights = {attached_texture_weights, count * A};
  }
  if (events && events_capacity) {
    job.events = {reinterpret_cast<posemorph::AnimatorEvent*>(events), events_capacity};
    job.event_count = event_count, job.events_missed = events_missed;
  } else if (event_count || events_missed) {
    if (event_count) *event_count = 0;
    if (events_missed) *events_missed = 0;
  }
  if (!job.Run()) return PM_ERROR_INVALID_ARGUMENT;
  auto* bytes = reinterpret_cast<unsigned char*>(events);
  for (std::size_t k = 0; events && k < *event_count; ++k) {
    posemorph::AnimatorEvent e;
    std::memcpy(&e, bytes + k * sizeof(e), sizeof(e));
    pm_animator_event c;
    std::memset(&c, 0, sizeof(c));
    c.character = e.character, c.channel = e.channel, c.event = e.event, c.outgoing = e.outgoing ? 1 : 0;
    c.time = e.time;
    std::memcpy(bytes + k * sizeof(c), &c, sizeof(c));
  }
  return PM_OK;
}

size_t pm_animator_state_size(const pm_rig* rig, const void* tracks, size_t capacity, size_t character) {
  Span<AnimatorTrack> t;
  if (CharacterTracks(rig, const_cast<void*>(tracks), capacity, character, &t) != PM_OK) return 0;
  return posemorph::AnimatorStateSize(rig->rig, t);
}

int pm_animator_save(const pm_rig* rig, const void* tracks, size_t capacity, size_t character, unsigned char* out,
                     size_t out_capacity, size_t* written) {
  Span<AnimatorTrack> t;
  const int r = CharacterTracks(rig, const_cast<void*>(tracks), capacity, character, &t);
  if (r != PM_OK) return r;
  if (!out || !written) return PM_ERROR_INVALID_ARGUMENT;
  if (posemorph::AnimatorStateSize(rig->rig, t) > out_capacity) return PM_ERROR_BUFFER_TOO_SMALL;
  return posemorph::AnimatorSave(rig->rig, t, {out, out_capacity}, written) ? PM_OK : PM_ERROR_INVALID_ARGUMENT;
}

int pm_animator_load(const pm_rig* rig, const unsigned char* bytes, size_t size, void* tracks, size_t capacity,
                     size_t character) {
  Span<AnimatorTrack> t;
  const int r = CharacterTracks(rig, tracks, capacity, character, &t);
  if (r != PM_OK) return r;
  if (!bytes) return PM_ERROR_INVALID_ARGUMENT;
  return posemorph::AnimatorLoad(rig->rig, {bytes, size}, t) ? PM_OK : PM_ERROR_BAD_VALUE;
}

uint32_t pm_channel_event_count(const pm_rig* rig, uint32_t channel) {
  const posemorph::Rig* c = rig ? rig->rig.channel_rig(channel) : nullptr;
  return c ? c->event_count() : 0;
}

int pm_channel_event(const pm_rig* rig, uint32_t channel, uint32_t event, uint32_t* path, double* time) {
  const posemorph::Rig* c = rig ? rig->rig.channel_rig(channel) : nullptr;
  if (!c || event >= c->event_count() || !path || !time) return PM_ERROR_INVALID_ARGUMENT;
  const posemorph::EventView e = c->event(event);
  *path = e.path, *time = e.time;
  return PM_OK;
}

int pm_channel_event_name(const pm_rig* rig, uint32_t channel, uint32_t event, char* out, size_t capacity,
                          size_t* length) {
  const posemorph::Rig* c = rig ? rig->rig.channel_rig(channel) : nullptr;
  const bool valid = c && event < c->event_count();
  return CopyString(valid ? c->event(event).name : posemorph::StringView{}, valid, out, capacity, length);
}

}  // extern "C"
