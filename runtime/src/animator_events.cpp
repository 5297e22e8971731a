// SPDX-License-Identifier: MIT
// A character's event streams merged into the caller's buffer (animator_events.h).
#include "animator_events.h"

namespace posemorph::detail {

void EmitEvents(EventStreams* streams, std::uint32_t character, double dt, const Span<AnimatorEvent>& events,
                std::size_t* written, double* missed) {
  for (;;) {
    int best = -1;
    double best_time = 0;
    for (int k = 0; k < streams->count; ++k) {
      const EventStream& s = streams->s[k];
      if (!s.has) continue;
      const double f = s.FireTime();
      if (best < 0 || f < best_time) best = k, best_time = f;
    }
    if (best < 0) return;  // every crossing written: none missed
    if (*written >= events.size) break;
    EventStream& s = streams->s[best];
    AnimatorEvent& e = events.data[(*written)++];
    e.character = character;
    e.channel = s.channel;
    e.event = s.base + s.j;
    e.outgoing = s.outgoing;
    e.time = best_time < 0 ? 0.0 : (best_time > dt ? dt : best_time);
    ++s.emitted;
    s.Next();
  }
  for (int k = 0; k < streams->count; ++k) {  // the buffer is full: count what did not fit
    const EventStream& s = streams->s[k];
    const double rest = s.Total() - double(s.emitted);
    if (rest > 0) *missed += rest;
  }
}

}  // namespace posemorph::detail
