// SPDX-License-Identifier: MIT
// Internal to the Animator (animator.cpp): the crossings of one path's
// events by one layer of a track over one segment of an update, and their
// merge, character by character, in time order into the caller's buffer.
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "posemorph/animator.h"

namespace posemorph::detail {

// Segments one track's update is split into, at most (where a mix ends or a
// queued path takes over), and so the streams one character can have.
constexpr int kMaxAnimatorSegments = 8;
constexpr int kMaxEventStreams = int(format::kMaxChannels) * kMaxAnimatorSegments * 2;

// Crossings of one path's events by one layer over one segment of time.
struct EventStream {
  const EventView* events = nullptr;
  std::uint32_t n = 0, base = 0;  // base: the first event's index in the channel rig
  std::uint32_t channel = 0;
  bool outgoing = false, loop = false, closed = false;
  double t0 = 0, t1 = 0;  // path clock: [t0, t1), or [t0, t1] when closed
  double start = 0, period = 0, speed = 1, offset = 0;
  // The next crossing: cycle (looping) and event.
  double cycle = 0;
  std::uint32_t j = 0;
  bool has = false;
  double u = 0;  // its time on the path's clock
  std::uint64_t emitted = 0;

  bool Inside(double v) const { return v >= t0 && (closed ? v <= t1 : v < t1); }
  double At(double c, std::uint32_t k) const {
    return loop ? start + c * period + (events[k].time - start) : events[k].time;
  }
  void Step() {
    if (++j == n) {
      j = 0;
      cycle += 1;
      if (!loop) {
        has = false;
        return;
      }
    }
    u = At(cycle, j);
  }
  // Moves to the first crossing at or after t0, then checks it is inside.
  void Begin() {
    cycle = loop ? std::floor((t0 - start) / period) - 1 : 0;
    j = 0;
    has = true;
    u = At(cycle, j);
    for (int guard = 0; has && u < t0 && guard < int(3 * n + 3); ++guard) Step();
    Check();
  }
  void Check() {
    if (has && !Inside(u)) has = false;
  }
  void Next() {
    Step();
    Check();
  }
  double FireTime() const { return offset + (u - t0) / speed; }
  // Crossings in the interval in all (for the missed count).
  double Total() const {
    if (!loop) {
      double c = 0;
      for (std::uint32_t k = 0; k < n; ++k) c += Inside(events[k].time) ? 1 : 0;
      return c;
    }
    double c = 0;
    for (std::uint32_t k = 0; k < n; ++k) {
      const double e = events[k].time;
      const double d = std::ceil((t1 - e) / period) - std::ceil((t0 - e) / period);
      if (d > 0) c += d;
    }
    return c;
  }
};

struct EventStreams {
  EventStream s[kMaxEventStreams];
  int count = 0;
};

// A character's streams into the buffer, in time order (ties: stream order);
// what does not fit is added to *missed.
void EmitEvents(EventStreams* streams, std::uint32_t character, double dt, const Span<AnimatorEvent>& events,
                std::size_t* written, double* missed);

}  // namespace posemorph::detail
