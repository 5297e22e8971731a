// SPDX-License-Identifier: MIT
// The Animator's update beside the frame it feeds: a crowd of Pells with
// faces (two channels), each body playing its gesture with a spring and
// breath and crossfading into a new start every half second, each face
// chattering, blinking and looking at a target that moves; then the frame
// (MorphBatchJob for the bodies, AttachJob for the faces). Both halves are
// timed inside each iteration, so `update_share` (the update's part of
// update + frame) is a ratio within one run on one machine.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "posemorph/animator.h"
#include "posemorph/jobs.h"
#include "bench_rigs.h"

using namespace posemorph;

namespace {

double Seconds(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

// A crowd of Pells with faces; `full`: with the behaviours and the body's
// crossfades (otherwise each channel plays its path, nothing more).
struct Crowd {
  const Rig* rig;
  std::size_t count, C, N, A;
  bool full;
  std::vector<AnimatorTrack> tracks;
  std::vector<double> raw, limited, ar, al;
  std::vector<AnimatorEvent> events;
  std::size_t written = 0;
  std::uint64_t missed = 0;
  long frame = 0;
  Crowd(const Rig* r, std::size_t characters, bool with_behaviours)
      : rig(r),
        count(characters),
        C(r->channel_count()),
        N(r->pose_count()),
        A(r->attached_weight_count()),
        full(with_behaviours),
        tracks(count * C),
        raw(count * N),
        limited(count * N),
        ar(count * A),
        al(count * A),
        events(4 * count + 16) {
    for (std::size_t i = 0; i < count; ++i) {
      const Span<AnimatorTrack> t{tracks.data() + i * C, C};
      AnimatorReset(*rig, t);
      if (full) {
        Behaviours body;
        body.spring.enabled = body.breath.enabled = true;
        body.breath.y = 0.03;
        AnimatorSetBehaviours(*rig, t, 0, body);
        Behaviours face;
        face.blink.enabled = face.look_at.enabled = true;
        face.blink.pose = 3, face.blink.seed = i;
        face.look_at.strength = 0.5;
        AnimatorSetBehaviours(*rig, t, 1, face);
      }
      PlayOptions o;
      o.start = 0.37 * double(i);
      AnimatorPlay(*rig, t, 0, 0, o);
      AnimatorPlay(*rig, t, 1, 0, o);
    }
  }
  // The frame's commands and one update of everyone by 1/60 s.
  void Update() {
    for (std::size_t i = 0; full && i < count; ++i) {
      const Span<AnimatorTrack> t{tracks.data() + i * C, C};
      if ((frame + long(i)) % 30 == 0) {  // a crossfade into a new start every half second
        PlayOptions o;
        o.mix = 0.4, o.start = 0.1 * double(frame % 48);
        AnimatorPlay(*rig, t, 0, 0, o);
      }
      if ((frame + long(i)) % 20 == 0) AnimatorLookAt(*rig, t, 1, std::sin(0.05 * double(frame)), 0.5);
    }
    AnimatorUpdateJob u;
    u.rig = rig, u.count = count, u.dt = 1.0 / 60;
    u.tracks = MakeSpan(tracks);
    u.weights = MakeSpan(raw), u.limited_weights = MakeSpan(limited);
    u.attached_weights = MakeSpan(ar), u.attached_limited_weights = MakeSpan(al);
    u.events = MakeSpan(events), u.event_count = &written, u.events_missed = &missed;
    u.Run();
    ++frame;
  }
};

// The update alone. Arguments: the characters; 1 with the behaviours and
// crossfades, 0 without.
void BM_AnimatorUpdate(benchmark::State& state) {
  const Rig* rig = PellFaceRig();
  if (!rig) return state.SkipWithError("Pell's drawings were not built (rsvg-convert)");
  Crowd crowd(rig, std::size_t(state.range(0)), state.range(1) != 0);
  for (auto _ : state) {
    crowd.Update();
    benchmark::DoNotOptimize(crowd.al.data());
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(crowd.count));
  state.SetLabel(state.range(1) ? "Pell with a face: 2 channels, spring, breath, blink, look-at, crossfades"
                                : "Pell with a face: 2 channels playing their paths");
}

// Update and frame. Argument: the characters.
void BM_AnimatedCrowd(benchmark::State& state) {
  const Rig* rig = PellFaceRig();
  if (!rig) return state.SkipWithError("Pell's drawings were not built (rsvg-convert)");
  Crowd crowd(rig, std::size_t(state.range(0)), true);
  const std::size_t count = crowd.count;
  std::vector<double> work(std::max(rig->batch_workspace_size(), rig->attach_workspace_size()));
  std::vector<double> body(count * 2 * std::size_t(rig->vertex_count()));
  std::vector<double> attached(count * 2 * std::size_t(rig->attached_vertex_count()));
  std::vector<float> body_f32(body.size()), attached_f32(attached.size());
  double update_s = 0, frame_s = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    crowd.Update();
    const auto t1 = std::chrono::steady_clock::now();
    MorphBatchJob m;
    m.rig = rig, m.count = count;
    m.weights = MakeSpan(crowd.raw), m.limited_weights = MakeSpan(crowd.limited);
    m.workspace = MakeSpan(work), m.positions = MakeSpan(body), m.positions_f32 = MakeSpan(body_f32);
    m.Run();
    AttachJob a;
    a.rig = rig, a.count = count, a.body_positions = MakeSpan(body);
    a.weights = MakeSpan(crowd.ar), a.limited_weights = MakeSpan(crowd.al);
    a.workspace = MakeSpan(work), a.positions = MakeSpan(attached), a.positions_f32 = MakeSpan(attached_f32);
    a.Run();
    benchmark::DoNotOptimize(attached_f32.data());
    const auto t2 = std::chrono::steady_clock::now();
    update_s += Seconds(t0, t1);
    frame_s += Seconds(t1, t2);
  }
  const double per = 1e6 / double(count) / double(std::max(crowd.frame, 1L));
  state.counters["update_us_per_character"] = update_s * per;
  state.counters["frame_us_per_character"] = frame_s * per;
  state.counters["update_share"] = update_s / std::max(update_s + frame_s, 1e-300);
  state.SetItemsProcessed(state.iterations() * std::int64_t(count));
  state.SetLabel("Pell with a face: 2 channels, spring, breath, blink, look-at, a crossfade every 0.5 s");
}

}  // namespace

BENCHMARK(BM_AnimatorUpdate)->ArgsProduct({{1, 1000}, {0, 1}})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_AnimatedCrowd)->Arg(1)->Arg(1000)->Unit(benchmark::kMicrosecond);
