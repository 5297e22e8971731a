// SPDX-License-Identifier: MIT
// Batched evaluation equals single evaluation bit for bit, whatever the
// group boundaries or the split across threads.
#include <cstring>
#include <random>
#include <thread>

#include "runtime_support.h"

using namespace posemorph;
using namespace posemorph::test;

namespace {

struct Crowd {
  std::size_t count;
  std::vector<double> w, ws;
};

Crowd RandomCrowd(const Rig& rig, std::size_t count, unsigned seed) {
  const PoseSpaceGrid& g = rig.grid();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> ux(g.origin_x - 1, g.origin_x + g.cell * g.cells_x + 1);
  std::uniform_real_distribution<double> uy(g.origin_y - 1, g.origin_y + g.cell * g.cells_y + 1);
  Crowd c{count, {}, {}};
  for (std::size_t k = 0; k < count; ++k) {
    const Weights w = WeightsAt(rig, ux(rng), uy(rng));
    c.w.insert(c.w.end(), w.raw.begin(), w.raw.end());
    c.ws.insert(c.ws.end(), w.limited.begin(), w.limited.end());
  }
  return c;
}

std::vector<double> RunBatch(const Rig& rig, const Crowd& c, std::size_t begin, std::size_t end,
                             std::vector<float>* f32 = nullptr) {
  const std::size_t N = rig.pose_count(), v2 = 2 * std::size_t(rig.vertex_count());
  std::vector<double> work(rig.batch_workspace_size()), x((end - begin) * v2);
  MorphBatchJob job;
  job.rig = &rig;
  job.count = end - begin;
  job.weights = {c.w.data() + begin * N, job.count * N};
  job.limited_weights = {c.ws.data() + begin * N, job.count * N};
  job.workspace = MakeSpan(work);
  job.positions = MakeSpan(x);
  if (f32) {
    f32->resize(x.size());
    job.positions_f32 = MakeSpan(*f32);
  }
  REQUIRE(job.Run());
  return x;
}

bool SameBits(const double* a, const double* b, std::size_t n) { return std::memcmp(a, b, n * sizeof(double)) == 0; }

}  // namespace

TEST_CASE("a batch gives each character exactly what MorphJob gives it") {
  for (const char* name : {"snake", "gingerbread", "snake.compact", "pip.compact", "pell"}) {
    const Rig rig = LoadTestRig(name);
    const std::size_t N = rig.pose_count(), v2 = 2 * std::size_t(rig.vertex_count());
    for (std::size_t count : {1u, 3u, 8u, 13u, 64u}) {
      const Crowd crowd = RandomCrowd(rig, count, unsigned(count));
      std::vector<float> f32;
      const std::vector<double> batch = RunBatch(rig, crowd, 0, count, &f32);
      for (std::size_t k = 0; k < count; ++k) {
        const std::vector<double> w(crowd.w.begin() + k * N, crowd.w.begin() + (k + 1) * N);
        const std::vector<double> ws(crowd.ws.begin() + k * N, crowd.ws.begin() + (k + 1) * N);
        const std::vector<double> single = Morph(rig, w, ws);
        CAPTURE(count);
        CAPTURE(k);
        CHECK(SameBits(single.data(), batch.data() + k * v2, v2));
        for (std::size_t i = 0; i < v2; ++i) REQUIRE(f32[k * v2 + i] == float(single[i]));
      }
    }
  }
}

TEST_CASE("splitting a crowd across threads changes no bit") {
  for (const char* name : {"snake", "snake.compact", "pell.compact"}) {
    const Rig rig = LoadTestRig(name);
    const std::size_t count = 100, v2 = 2 * std::size_t(rig.vertex_count());
    const Crowd crowd = RandomCrowd(rig, count, 42);
    const std::vector<double> whole = RunBatch(rig, crowd, 0, count);
    for (std::size_t threads : {2u, 3u, 7u}) {
      std::vector<std::vector<double>> parts(threads);
      std::vector<std::thread> pool;
      for (std::size_t t = 0; t < threads; ++t) {
        auto part = [&, t] {
          const std::size_t begin = count * t / threads, end = count * (t + 1) / threads;
          std::vector<double> work(rig.batch_workspace_size()), x((end - begin) * v2);
          MorphBatchJob job;
          job.rig = &rig, job.count = end - begin;
          job.weights = {crowd.w.data() + begin * rig.pose_count(), job.count * rig.pose_count()};
          job.limited_weights = {crowd.ws.data() + begin * rig.pose_count(), job.count * rig.pose_count()};
          job.workspace = MakeSpan(work), job.positions = MakeSpan(x);
          job.Run();
          parts[t] = std::move(x);
        };
#if defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
        part();  // WebAssembly built without threads: the same ranges, one after another
#else
        pool.emplace_back(part);
#endif
      }
      for (auto& th : pool) th.join();
      std::vector<double> joined;
      for (const auto& p : parts) joined.insert(joined.end(), p.begin(), p.end());
      CAPTURE(threads);
      REQUIRE(joined.size() == whole.size());
      CHECK(SameBits(joined.data(), whole.data(), whole.size()));
    }
  }
}

TEST_CASE("a batch can write only the single-precision copy") {
  const Rig rig = LoadTestRig("snake");
  for (std::size_t count : {2u, 11u}) {  // the one-by-one fallback and a group
    const Crowd crowd = RandomCrowd(rig, count, 9);
    std::vector<float> with_doubles;
    const std::vector<double> doubles = RunBatch(rig, crowd, 0, count, &with_doubles);
    std::vector<double> work(rig.batch_workspace_size());
    std::vector<float> only(doubles.size());
    MorphBatchJob job;
    job.rig = &rig, job.count = count;
    job.weights = MakeSpan(crowd.w), job.limited_weights = MakeSpan(crowd.ws);
    job.workspace = MakeSpan(work), job.positions_f32 = MakeSpan(only);
    REQUIRE(job.Run());
    CHECK(only == with_doubles);
  }
}

TEST_CASE("a batch refuses inputs that do not fit") {
  const Rig rig = LoadTestRig("snake");
  const Crowd crowd = RandomCrowd(rig, 4, 1);
  std::vector<double> work(rig.batch_workspace_size()), x(4 * 2 * rig.vertex_count());
  MorphBatchJob job;
  job.rig = &rig, job.count = 4;
  job.weights = MakeSpan(crowd.w), job.limited_weights = MakeSpan(crowd.ws);
  job.workspace = MakeSpan(work), job.positions = MakeSpan(x);
  CHECK(job.Validate());
  job.count = 5;  // more characters than weights
  CHECK_FALSE(job.Run());
  job.count = 4;
  job.workspace.size -= 1;
  CHECK_FALSE(job.Run());
  job.workspace = MakeSpan(work);
  job.positions = {};
  CHECK_FALSE(job.Run());  // no output at all
  job.positions = MakeSpan(x);
  std::vector<double> bad = crowd.w;
  bad[3] = std::nan("");
  job.weights = MakeSpan(bad);
  CHECK_FALSE(job.Run());
}
