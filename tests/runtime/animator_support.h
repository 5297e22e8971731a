// SPDX-License-Identifier: MIT
// A character for the Animator's tests: its tracks, its weights on every
// channel and an event buffer, updated by one AnimatorUpdateJob.
#pragma once
#include <cstdint>
#include <vector>

#include "posemorph/animator.h"
#include "runtime_support.h"

namespace posemorph::test {

// `count` characters sharing a rig: their tracks, their weights on every
// channel (in AnimatorUpdateJob's layouts) and an event buffer.
struct Crowd {
  const Rig* rig;
  std::size_t count;
  std::vector<AnimatorTrack> tracks;
  std::vector<double> raw, limited, texture, attached_raw, attached_limited, attached_texture;
  std::vector<AnimatorEvent> buffer;
  std::size_t written = 0;
  std::uint64_t missed = 0;
  Crowd(const Rig& r, std::size_t characters, std::size_t capacity)
      : rig(&r),
        count(characters),
        tracks(count * r.channel_count()),
        raw(count * r.pose_count()),
        limited(count * r.pose_count()),
        texture(count * r.pose_count()),
        attached_raw(count * r.attached_weight_count()),
        attached_limited(count * r.attached_weight_count()),
        attached_texture(count * r.attached_weight_count()),
        buffer(capacity) {
    for (std::size_t i = 0; i < count; ++i) REQUIRE(AnimatorReset(r, Tracks(i)));
  }
  // Character i's tracks.
  Span<AnimatorTrack> Tracks(std::size_t i = 0) {
    return {tracks.data() + i * rig->channel_count(), rig->channel_count()};
  }
  // An update of everyone by dt into these buffers (events into `written`, `missed`).
  AnimatorUpdateJob Job(double dt) {
    AnimatorUpdateJob job;
    job.rig = rig;
    job.count = count;
    job.dt = dt;
    job.tracks = MakeSpan(tracks);
    job.weights = MakeSpan(raw);
    job.limited_weights = MakeSpan(limited);
    job.texture_weights = MakeSpan(texture);
    job.attached_weights = MakeSpan(attached_raw);
    job.attached_limited_weights = MakeSpan(attached_limited);
    job.attached_texture_weights = MakeSpan(attached_texture);
    job.events = MakeSpan(buffer);
    job.event_count = &written;
    job.events_missed = &missed;
    return job;
  }
};

// One character of a rig: its tracks and its outputs.
struct Character : Crowd {
  explicit Character(const Rig& r, std::size_t capacity = 4096) : Crowd(r, 1, capacity) {}
  // Channel c's weights (raw, limited or texture) from the last update.
  std::vector<double> ChannelWeights(std::uint32_t c, int which = 0) const {
    const std::vector<double>* body[] = {&raw, &limited, &texture};
    const std::vector<double>* attached[] = {&attached_raw, &attached_limited, &attached_texture};
    const std::vector<double>& all = c == 0 ? *body[which] : *attached[which];
    const std::size_t at = c == 0 ? 0 : rig->channel_weight_offset(c), n = rig->channel_rig(c)->pose_count();
    return {all.begin() + std::ptrdiff_t(at), all.begin() + std::ptrdiff_t(at + n)};
  }
  // Runs one update; returns its events.
  std::vector<AnimatorEvent> Update(double dt, std::uint64_t* missed_out = nullptr) {
    REQUIRE(Job(dt).Run());
    if (missed_out) *missed_out = missed;
    return {buffer.begin(), buffer.begin() + std::ptrdiff_t(written)};
  }
};

}  // namespace posemorph::test
