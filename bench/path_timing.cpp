// SPDX-License-Identifier: MIT
// Per-path timing with the runtime alone (no Google Benchmark, no bake), so
// it builds for every target: aarch64 under qemu, Windows, WebAssembly under
// node. Emulated figures are reported, never tuned for (docs/runtime.md "Targets").
// Usage: posemorph-path-timing RIG.pmrig [characters]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "posemorph/jobs.h"
#include "posemorph/rig.h"

using namespace posemorph;

namespace {

double Seconds(std::chrono::steady_clock::duration d) { return std::chrono::duration<double>(d).count(); }

// Median over 7 runs of `reps` calls of f, in microseconds per call.
template <typename F>
double MedianMicros(int reps, F&& f) {
  double runs[7];
  for (double& r : runs) {
    const auto start = std::chrono::steady_clock::now();
    for (int k = 0; k < reps; ++k) f(k);
    r = Seconds(std::chrono::steady_clock::now() - start) / reps * 1e6;
  }
  for (int i = 0; i < 7; ++i)
    for (int j = i + 1; j < 7; ++j)
      if (runs[j] < runs[i]) std::swap(runs[i], runs[j]);
  return runs[3];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: posemorph-path-timing RIG.pmrig [characters]\n");
    return 2;
  }
  std::vector<unsigned char> bytes;
  if (std::FILE* f = std::fopen(argv[1], "rb")) {
    int c;
    while ((c = std::fgetc(f)) != EOF) bytes.push_back(static_cast<unsigned char>(c));
    std::fclose(f);
  }
  const std::size_t count = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 200;
  std::printf("%s: %zu bytes; crowd of %zu; microseconds (median of 7)\n", argv[1], bytes.size(), count);
  std::printf("| path | frame (weights + morph) | crowd per character |\n|---|---|---|\n");
  for (Isa isa : {Isa::kAvx512, Isa::kAvx2, Isa::kSse2, Isa::kNeon, Isa::kWasmSimd, Isa::kScalar}) {
    if (!IsaAvailable(isa)) continue;
    Rig rig;
    Error err;
    LoadOptions options;
    options.isa = isa;
    if (!LoadRig(bytes.data(), bytes.size(), &rig, &err, options)) {
      std::fprintf(stderr, "%s: %s\n", argv[1], err.message);
      return 1;
    }
    const std::size_t N = rig.pose_count(), v2 = 2 * std::size_t(rig.vertex_count());
    std::vector<double> w(count * N), ws(count * N), work(rig.batch_workspace_size()), x(v2);
    std::vector<float> xf(count * v2);
    auto weights_at = [&](std::size_t k, double t) {
      WeightsJob job;
      job.rig = &rig, job.x = std::cos(t + 0.1 * k), job.y = std::sin(1.3 * t + 0.2 * k);
      job.raw = {w.data() + k * N, N}, job.limited = {ws.data() + k * N, N};
      job.Run();
    };
    const double frame = MedianMicros(200, [&](int k) {
      weights_at(0, 0.01 * k);
      MorphJob job;
      job.rig = &rig, job.weights = {w.data(), N}, job.limited_weights = {ws.data(), N};
      job.workspace = {work.data(), rig.morph_workspace_size()}, job.positions = {x.data(), v2};
      job.positions_f32 = {xf.data(), v2};
      job.Run();
    });
    const double crowd = MedianMicros(3, [&](int k) {
      for (std::size_t c = 0; c < count; ++c) weights_at(c, 0.01 * k);
      MorphBatchJob job;
      job.rig = &rig, job.count = count;
      job.weights = {w.data(), w.size()}, job.limited_weights = {ws.data(), ws.size()};
      job.workspace = {work.data(), work.size()}, job.positions_f32 = {xf.data(), xf.size()};
      job.Run();
    });
    std::printf("| %s | %.1f | %.2f |\n", IsaName(isa), frame, crowd / double(count));
  }
  return 0;
}
