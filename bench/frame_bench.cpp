// SPDX-License-Identifier: MIT
// Per-frame cost of the runtime on the bundled samples (and a larger strip),
// plus load and bake time. Run: build/release/bin/posemorph-bench
#include <benchmark/benchmark.h>

#include "ldlt_solve.h"
#include "posemorph/bake/bake.h"
#include "posemorph/jobs.h"
#include "posemorph/path.h"
#include "gingerbread_rig.h"
#include "posemorph/bake/arap_deformer.h"
#include "strip_rig.h"

using namespace posemorph;

namespace {

bake::RigDescription LargeStrip() {
  // About 1000 vertices: 199 x 4 quads, 5 poses.
  bake::RigDescription rig = samples::SnakeRig();
  samples::StripShape shape;
  shape.segments = 199;
  shape.across = 4;
  const double L = shape.length;
  rig.name = "strip-1000";
  rig.triangles = samples::StripTriangles(shape);
  const double turns[] = {0, 120, -120, 300, 90};
  for (std::size_t i = 0; i < rig.poses.size(); ++i) {
    const double k = samples::Degrees(turns[i]) / L;
    rig.poses[i].vertices = samples::BentStrip(shape, [=](double) { return k; });
  }
  return rig;
}

struct Fixture {
  std::vector<unsigned char> bytes;
  Rig rig;
  Fixture(bake::RigDescription desc, bool compact) {
    desc.parameters.compact = compact;
    bytes = bake::BakeRig(desc);
    LoadRig(bytes.data(), bytes.size(), &rig, nullptr);
  }
};

// 0..2: snake, worm-line, 1000-vertex strip, exact; 3..5: the same, compact.
Fixture& Get(int which) {
  static Fixture snake(samples::SnakeRig(), false), worm(samples::WormLineRig(), false), large(LargeStrip(), false);
  static Fixture snake_c(samples::SnakeRig(), true), worm_c(samples::WormLineRig(), true), large_c(LargeStrip(), true);
  Fixture* all[] = {&snake, &worm, &large, &snake_c, &worm_c, &large_c};
  return *all[which];
}

void Label(benchmark::State& state, const Rig& rig) {
  state.SetLabel(std::to_string(rig.vertex_count()) + " vertices, " + std::to_string(rig.triangle_count()) +
                 " triangles, " + std::to_string(rig.pose_count()) + " poses, " +
                 (state.range(0) >= 3 ? "compact" : "exact"));
}

void BM_Frame(benchmark::State& state) {
  const Rig& rig = Get(int(state.range(0))).rig;
  const std::uint32_t N = rig.pose_count();
  std::vector<double> raw(N), limited(N), tex(N), work(rig.morph_workspace_size()), x(2 * rig.vertex_count());
  std::vector<float> xf(x.size());
  double t = 0;
  for (auto _ : state) {
    double px, py;
    SamplePath(rig, 0, t, &px, &py);
    t += 1.0 / 60;
    WeightsJob wj;
    wj.rig = &rig, wj.x = px, wj.y = py, wj.sigma = 0.25;
    wj.raw = MakeSpan(raw), wj.limited = MakeSpan(limited), wj.texture = MakeSpan(tex);
    wj.Run();
    MorphJob mj;
    mj.rig = &rig, mj.weights = MakeSpan(raw), mj.limited_weights = MakeSpan(limited);
    mj.workspace = MakeSpan(work), mj.positions = MakeSpan(x), mj.positions_f32 = MakeSpan(xf);
    mj.Run();
    benchmark::DoNotOptimize(xf.data());
  }
  Label(state, rig);
}

void BM_Weights(benchmark::State& state) {
  const Rig& rig = Get(int(state.range(0))).rig;
  std::vector<double> raw(rig.pose_count()), limited(raw.size()), tex(raw.size());
  double x = -1.3;
  for (auto _ : state) {
    WeightsJob wj;
    wj.rig = &rig, wj.x = x, wj.y = 0.3, wj.sigma = 0.25;
    wj.raw = MakeSpan(raw), wj.limited = MakeSpan(limited), wj.texture = MakeSpan(tex);
    wj.Run();
    x = x > 1.3 ? -1.3 : x + 0.01;
    benchmark::DoNotOptimize(tex.data());
  }
  Label(state, rig);
}

void BM_Solve(benchmark::State& state) {
  const Rig& rig = Get(int(state.range(0))).rig;
  const std::size_t n = rig.factor().n;
  std::vector<double> b(2 * n, 0.5), scratch(2 * n), x(2 * n);
  for (auto _ : state) {
    detail::SolvePinned(rig, b.data(), scratch.data(), x.data());
    benchmark::DoNotOptimize(x.data());
  }
  Label(state, rig);
}

// A crowd of 1000 on one thread, each character at its own point of the
// first path: exact (0..2) against compact (3..5) rigs, same run.
void BM_Crowd1000(benchmark::State& state) {
  const Rig& rig = Get(int(state.range(0))).rig;
  const std::size_t count = 1000, N = rig.pose_count();
  std::vector<double> w(count * N), ws(count * N), work(rig.batch_workspace_size());
  std::vector<float> xf(count * 2 * std::size_t(rig.vertex_count()));
  for (std::size_t c = 0; c < count; ++c) {
    double px, py;
    SamplePath(rig, 0, 0.003 * double(c), &px, &py);
    WeightsJob wj;
    wj.rig = &rig, wj.x = px, wj.y = py;
    wj.raw = {w.data() + c * N, N}, wj.limited = {ws.data() + c * N, N};
    wj.Run();
  }
  for (auto _ : state) {
    MorphBatchJob job;
    job.rig = &rig, job.count = count;
    job.weights = MakeSpan(w), job.limited_weights = MakeSpan(ws);
    job.workspace = MakeSpan(work), job.positions_f32 = MakeSpan(xf);
    job.Run();
    benchmark::DoNotOptimize(xf.data());
  }
  Label(state, rig);
}

void BM_Load(benchmark::State& state) {
  const Fixture& f = Get(int(state.range(0)));
  for (auto _ : state) {
    Rig rig;
    LoadRig(f.bytes.data(), f.bytes.size(), &rig, nullptr);
    benchmark::DoNotOptimize(rig.vertex_count());
  }
  state.SetLabel(std::to_string(f.bytes.size()) + " bytes, " + (state.range(0) >= 3 ? "compact" : "exact"));
}

void BM_Bake(benchmark::State& state) {
  const bake::RigDescription desc = state.range(0) == 0   ? samples::SnakeRig()
                                    : state.range(0) == 1 ? samples::WormLineRig()
                                                          : LargeStrip();
  for (auto _ : state) {
    bake::RigDescription d = desc;
    benchmark::DoNotOptimize(bake::BakeRig(d).size());
  }
}

// The edit-mode loop: handles chosen once (factor), then dragged (solve).
const std::vector<std::uint32_t> kDragHandles = {0, 40, 117, 200, 236};

void BM_DeformerSetup(benchmark::State& state) {
  const bake::RigDescription g = samples::GingerbreadRig();
  for (auto _ : state) {
    bake::ArapDeformer deformer(g.poses[0].vertices, g.triangles, kDragHandles);
    benchmark::DoNotOptimize(&deformer);
  }
  state.SetLabel(std::to_string(g.poses[0].vertices.size()) + " vertices, " + std::to_string(kDragHandles.size()) +
                 " handles");
}

void BM_DeformerDrag(benchmark::State& state) {
  const bake::RigDescription g = samples::GingerbreadRig();
  const bake::ArapDeformer deformer(g.poses[0].vertices, g.triangles, kDragHandles);
  std::vector<Eigen::Vector2d> targets;
  for (std::uint32_t h : kDragHandles) targets.push_back(g.poses[0].vertices[h]);
  bake::Points out;
  double t = 0;
  for (auto _ : state) {
    targets[2] = g.poses[0].vertices[kDragHandles[2]] + Eigen::Vector2d(std::sin(t), std::cos(t)) * 0.5;
    t += 0.01;
    deformer.Deform(targets, &out);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetLabel(std::to_string(g.poses[0].vertices.size()) + " vertices, " + std::to_string(kDragHandles.size()) +
                 " handles");
}

}  // namespace

BENCHMARK(BM_DeformerSetup)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DeformerDrag)->Unit(benchmark::kMicrosecond);

// 0: snake sample, 1: worm-line sample, 2: 1000-vertex strip.
BENCHMARK(BM_Frame)->DenseRange(0, 5);
BENCHMARK(BM_Weights)->DenseRange(0, 2);
BENCHMARK(BM_Solve)->DenseRange(0, 2);
BENCHMARK(BM_Load)->DenseRange(0, 5);
BENCHMARK(BM_Crowd1000)->DenseRange(0, 5)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Bake)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
