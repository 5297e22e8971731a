// SPDX-License-Identifier: MIT
// The runtime against the general-purpose sparse solvers on the same matrix,
// and batched crowds. Rigs: plates of about 500..4000 vertices bent into N = 4
// or 8 poses, generated here. Run through scripts/bench.sh for the table.
#include <benchmark/benchmark.h>
#include <cholmod.h>

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <map>
#include <random>
#include <thread>
#include <tuple>

#include "kernels/kernel_table.h"
#include "ldlt_solve.h"
#include "posemorph/bake/arap_system.h"
#include "posemorph/bake/bake.h"
#include "posemorph/jobs.h"
#include "strip_rig.h"

using namespace posemorph;

namespace {

// A plate twice as long as wide, `across` quads across, in N bent poses whose
// points sit on a circle around the rest pose.
const int kAcross[] = {15, 22, 31, 44};  // 496, 1035, 2016, 4005 vertices

struct Case {
  std::vector<unsigned char> bytes;
  Rig rig;
  Eigen::SparseMatrix<double> K;  // the same pinned matrix the bake factored
  Eigen::MatrixXd rhs;            // two right-hand sides (x and y)
};

const Case& GetCase(int size, int poses) {
  static std::map<std::pair<int, int>, Case> cases;
  auto [it, inserted] = cases.try_emplace({size, poses});
  if (inserted) {
    bake::RigDescription desc = samples::PlateRig(kAcross[size], poses);
    desc.parameters.compact = false;  // the exact encoding, as these figures were first taken
    it->second.bytes = bake::BakeRig(desc);
    LoadRig(it->second.bytes.data(), it->second.bytes.size(), &it->second.rig, nullptr);
    it->second.K = bake::BuildArapSystem(desc.poses[0].vertices, desc.triangles, "").K;
    it->second.rhs = Eigen::MatrixXd::Random(it->second.K.rows(), 2);
  }
  return it->second;
}

// The same rig loaded with a forced kernel path; null when this CPU lacks it.
const Rig* RigOnPath(int size, int poses, Isa isa) {
  static std::map<std::tuple<int, int, Isa>, Rig> rigs;
  auto [it, inserted] = rigs.try_emplace({size, poses, isa});
  if (inserted) {
    const Case& c = GetCase(size, poses);
    LoadOptions options;
    options.isa = isa;
    if (!LoadRig(c.bytes.data(), c.bytes.size(), &it->second, nullptr, options)) return nullptr;
  }
  return it->second.loaded() ? &it->second : nullptr;
}

void Label(benchmark::State& state, const Rig& rig) {
  state.SetLabel("V=" + std::to_string(rig.vertex_count()) + " N=" + std::to_string(rig.pose_count()) +
                 " nnz(L)=" + std::to_string(rig.factor().value.size + rig.factor().n) + " path=" + IsaName(rig.isa()));
}

struct EigenSolver {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
  Eigen::MatrixXd x;
  explicit EigenSolver(const Case& c) : ldlt(c.K), x(c.rhs.rows(), 2) {}
  void Solve(const Case& c) { x = ldlt.solve(c.rhs); }
};

struct CholmodSolver {
  cholmod_common cm;
  Eigen::SparseMatrix<double> upper;
  cholmod_sparse A{};
  cholmod_factor* L = nullptr;
  cholmod_dense *B = nullptr, *X = nullptr, *Y = nullptr, *E = nullptr;
  explicit CholmodSolver(const Case& c) {
    cholmod_start(&cm);  // CHOLMOD's defaults: AMD/METIS ordering, supernodal when it pays
    upper = c.K.triangularView<Eigen::Upper>();
    upper.makeCompressed();
    A.nrow = A.ncol = std::size_t(upper.rows());
    A.nzmax = std::size_t(upper.nonZeros());
    A.p = upper.outerIndexPtr(), A.i = upper.innerIndexPtr(), A.x = upper.valuePtr();
    A.stype = 1;  // symmetric, upper part stored
    A.itype = CHOLMOD_INT, A.xtype = CHOLMOD_REAL, A.dtype = CHOLMOD_DOUBLE;
    A.sorted = 1, A.packed = 1;
    L = cholmod_analyze(&A, &cm);
    cholmod_factorize(&A, L, &cm);
    B = cholmod_allocate_dense(A.nrow, 2, A.nrow, CHOLMOD_REAL, &cm);
    std::memcpy(B->x, c.rhs.data(), sizeof(double) * 2 * A.nrow);
  }
  ~CholmodSolver() {
    cholmod_free_dense(&X, &cm), cholmod_free_dense(&Y, &cm), cholmod_free_dense(&E, &cm), cholmod_free_dense(&B, &cm);
    cholmod_free_factor(&L, &cm);
    cholmod_finish(&cm);
  }
  void Solve() { cholmod_solve2(CHOLMOD_A, L, B, nullptr, &X, nullptr, &Y, &E, &cm); }  // reuses X, Y, E
};

struct RuntimeSolver {
  std::vector<double> b, scratch, x;
  explicit RuntimeSolver(const Case& c) : b(2 * c.rig.factor().n), scratch(b.size()), x(b.size()) {
    for (std::size_t k = 0; k < c.rig.factor().n; ++k) b[2 * k] = c.rhs(k, 0), b[2 * k + 1] = c.rhs(k, 1);
  }
  void Solve(const Case& c) { detail::SolvePinned(c.rig, b.data(), scratch.data(), x.data()); }
};

struct RuntimeFrame {
  std::vector<double> w, ws, work, x;
  double t = 0;
  explicit RuntimeFrame(const Rig& rig)
      : w(rig.pose_count()), ws(rig.pose_count()), work(rig.morph_workspace_size()), x(2 * rig.vertex_count()) {}
  void Run(const Rig& rig) {
    WeightsJob wj;
    wj.rig = &rig, wj.x = 0.8 * std::cos(t), wj.y = 0.8 * std::sin(t);
    wj.raw = MakeSpan(w), wj.limited = MakeSpan(ws);
    wj.Run();
    MorphJob mj;
    mj.rig = &rig, mj.weights = MakeSpan(w), mj.limited_weights = MakeSpan(ws);
    mj.workspace = MakeSpan(work), mj.positions = MakeSpan(x);
    mj.Run();
    t += 0.01;
  }
};

void BM_RuntimeFrame(benchmark::State& state) {
  const Rig& rig = GetCase(int(state.range(0)), int(state.range(1))).rig;
  RuntimeFrame frame(rig);
  for (auto _ : state) {
    frame.Run(rig);
    benchmark::DoNotOptimize(frame.x.data());
  }
  Label(state, rig);
}

void BM_RuntimeSolve(benchmark::State& state) {
  const Case& c = GetCase(int(state.range(0)), int(state.range(1)));
  RuntimeSolver solver(c);
  for (auto _ : state) {
    solver.Solve(c);
    benchmark::DoNotOptimize(solver.x.data());
  }
  Label(state, c.rig);
}

void BM_EigenSolve(benchmark::State& state) {
  const Case& c = GetCase(int(state.range(0)), int(state.range(1)));
  EigenSolver solver(c);
  for (auto _ : state) {
    solver.Solve(c);
    benchmark::DoNotOptimize(solver.x.data());
  }
  Label(state, c.rig);
}

// What a naive implementation does: factor the (unchanged) matrix every frame.
// Eigen's symbolic analysis is reused, so this counts only the numeric work.
void BM_EigenRefactorEveryFrame(benchmark::State& state) {
  const Case& c = GetCase(int(state.range(0)), int(state.range(1)));
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
  ldlt.analyzePattern(c.K);
  Eigen::MatrixXd x(c.rhs.rows(), 2);
  for (auto _ : state) {
    ldlt.factorize(c.K);
    x = ldlt.solve(c.rhs);
    benchmark::DoNotOptimize(x.data());
  }
  Label(state, c.rig);
}

void BM_CholmodSolve(benchmark::State& state) {
  const Case& c = GetCase(int(state.range(0)), int(state.range(1)));
  CholmodSolver solver(c);
  for (auto _ : state) {
    solver.Solve();
    benchmark::DoNotOptimize(solver.X->x);
  }
  state.counters["supernodal"] = solver.L->is_super;
  state.counters["cholmod_nnz_L"] = solver.cm.lnz;
  state.counters["cholmod_ordering"] = solver.cm.method[solver.cm.selected].ordering;
  Label(state, c.rig);
}

double Median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// Ratios measured in pairs: each iteration times a short burst of every
// contender back to back, and the counters are the medians of the per-burst
// ratios, so a machine that speeds up or slows down between bursts moves
// numerator and denominator together.
void BM_PairedRatios(benchmark::State& state) {
  const Case& c = GetCase(int(state.range(0)), int(state.range(1)));
  RuntimeSolver runtime(c);
  EigenSolver eigen(c);
  CholmodSolver cholmod(c);
  RuntimeFrame frame(c.rig);
  using Clock = std::chrono::steady_clock;
  auto burst = [](auto&& f) {
    const auto start = Clock::now();
    for (int k = 0; k < 8; ++k) f();
    return std::chrono::duration<double>(Clock::now() - start).count();
  };
  std::vector<double> vs_eigen, vs_cholmod, frame_vs_eigen;
  int round = 0;
  for (auto _ : state) {
    // The order rotates each iteration, so no contender always follows the
    // same one into a cache it left cold.
    double t[4];
    for (int k = 0; k < 4; ++k) {
      const int which = (k + round) % 4;
      t[which] = which == 0   ? burst([&] { runtime.Solve(c); })
                 : which == 1 ? burst([&] { eigen.Solve(c); })
                 : which == 2 ? burst([&] { cholmod.Solve(); })
                              : burst([&] { frame.Run(c.rig); });
    }
    ++round;
    vs_eigen.push_back(t[0] / t[1]), vs_cholmod.push_back(t[0] / t[2]), frame_vs_eigen.push_back(t[3] / t[1]);
  }
  state.counters["solve_vs_eigen"] = Median(vs_eigen);
  state.counters["solve_vs_cholmod"] = Median(vs_cholmod);
  state.counters["frame_vs_eigen_solve"] = Median(frame_vs_eigen);
  Label(state, c.rig);
}

// A persistent pool: workers wait for a frame number, run their share, report.
class Pool {
 public:
  explicit Pool(int threads) : threads_(threads) {
    for (int t = 1; t < threads; ++t) workers_.emplace_back([this, t] { Work(t); });
  }
  ~Pool() {
    stop_ = true;
    frame_.fetch_add(1);
    for (auto& w : workers_) w.join();
  }
  template <typename F>
  void Run(F& part) {  // part(thread index, thread count)
    task_ = [](void* f, int t, int n) { (*static_cast<F*>(f))(t, n); };
    arg_ = &part;
    done_ = 0;
    frame_.fetch_add(1);
    part(0, threads_);
    while (done_.load() != threads_ - 1) std::this_thread::yield();
  }

 private:
  void Work(int t) {
    long seen = 0;
    for (;;) {
      while (frame_.load() == seen) std::this_thread::yield();
      seen = frame_.load();
      if (stop_) return;
      task_(arg_, t, threads_);
      done_.fetch_add(1);
    }
  }
  int threads_;
  std::vector<std::thread> workers_;
  std::atomic<long> frame_{0};
  std::atomic<int> done_{0};
  std::atomic<bool> stop_{false};
  void (*task_)(void*, int, int) = nullptr;
  void* arg_ = nullptr;
};

// Characters [begin, end) of a crowd of one rig: each one's weights, then
// the batched morph (float output, what a game hands the GPU).
struct CrowdBuffers {
  std::vector<double> w, ws;
  std::vector<float> x;
  CrowdBuffers(const Rig& rig, std::size_t count)
      : w(count * rig.pose_count()), ws(w.size()), x(count * 2 * std::size_t(rig.vertex_count())) {}
};

void CrowdPart(const Rig& rig, double time, std::size_t begin, std::size_t end, CrowdBuffers& b,
               std::vector<double>& work) {
  const std::size_t N = rig.pose_count(), v2 = 2 * std::size_t(rig.vertex_count());
  for (std::size_t k = begin; k < end; ++k) {
    WeightsJob wj;
    wj.rig = &rig, wj.x = std::cos(time + 0.1 * k), wj.y = std::sin(1.3 * time + 0.2 * k);
    wj.raw = {b.w.data() + k * N, N}, wj.limited = {b.ws.data() + k * N, N};
    wj.Run();
  }
  MorphBatchJob job;
  job.rig = &rig, job.count = end - begin;
  job.weights = {b.w.data() + begin * N, job.count * N}, job.limited_weights = {b.ws.data() + begin * N, job.count * N};
  job.workspace = MakeSpan(work), job.positions_f32 = {b.x.data() + begin * v2, job.count * v2};
  job.Run();
}

// K characters of one rig per frame: each one's weights, then the batched morph.
void BM_Crowd(benchmark::State& state) {
  const Rig& rig = GetCase(1, 8).rig;  // ~1000 vertices, N = 8
  const std::size_t count = std::size_t(state.range(0));
  const int threads = int(state.range(1));
  CrowdBuffers buffers(rig, count);
  std::vector<std::vector<double>> work(threads, std::vector<double>(rig.batch_workspace_size()));
  Pool pool(threads);
  double time = 0;
  auto part = [&](int t, int n) { CrowdPart(rig, time, count * t / n, count * (t + 1) / n, buffers, work[t]); };
  for (auto _ : state) {
    pool.Run(part);
    time += 1.0 / 60;
    benchmark::DoNotOptimize(buffers.x.data());
  }
  state.counters["us_per_character"] =
      benchmark::Counter(double(count), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert,
                         benchmark::Counter::kIs1000);
  Label(state, rig);
}

// Each kernel path against the fastest this CPU runs, measured in pairs as
// BM_PairedRatios does (bursts back to back, order rotating): a single frame
// and a 1000-character crowd (one thread) of the 1035-vertex, N = 8 plate;
// and the path's solve against Eigen's and CHOLMOD's. Argument: Isa value.
void BM_PathRatios(benchmark::State& state) {
  const Isa isa = Isa(state.range(0));
  const Case& c = GetCase(1, 8);
  const Rig* rig = RigOnPath(1, 8, isa);
  const Rig* best = RigOnPath(1, 8, BestIsa());
  if (!rig || !best) {
    state.SkipWithError("this CPU does not run this path");
    return;
  }
  const std::size_t count = 1000;
  RuntimeFrame frame(*rig), best_frame(*best);
  CrowdBuffers crowd(*rig, count), best_crowd(*best, count);
  std::vector<double> work(rig->batch_workspace_size());
  RuntimeSolver solver(c);
  EigenSolver eigen(c);
  CholmodSolver cholmod(c);
  using Clock = std::chrono::steady_clock;
  // One untimed call first: each burst starts from its own data in cache,
  // whatever ran before it (without it, the path that always follows the
  // other path on the same rig looked 14% faster against itself).
  auto burst = [](int reps, auto&& f) {
    f();
    const auto start = Clock::now();
    for (int k = 0; k < reps; ++k) f();
    return std::chrono::duration<double>(Clock::now() - start).count();
  };
  std::vector<double> frame_ratio, crowd_ratio, vs_eigen, vs_cholmod;
  double time = 0;
  std::mt19937 rng(7);
  int order[7] = {0, 1, 2, 3, 4, 5, 6};
  for (auto _ : state) {
    double t[7] = {};
    // A new order every round: no contender always follows the same one.
    std::shuffle(order, order + 7, rng);
    for (int which : order) {
      switch (which) {
        case 0:
          t[0] = burst(8, [&] { frame.Run(*rig); });
          break;
        case 1:
          t[1] = burst(8, [&] { best_frame.Run(*best); });
          break;
        case 2:
          t[2] = burst(1, [&] { CrowdPart(*rig, time, 0, count, crowd, work); });
          break;
        case 3:
          t[3] = burst(1, [&] { CrowdPart(*best, time, 0, count, best_crowd, work); });
          break;
        case 4:
          t[4] = burst(8, [&] { detail::SolvePinned(*rig, solver.b.data(), solver.scratch.data(), solver.x.data()); });
          break;
        case 5:
          t[5] = burst(8, [&] { eigen.Solve(c); });
          break;
        default:
          t[6] = burst(8, [&] { cholmod.Solve(); });
          break;
      }
    }
    time += 1.0 / 60;
    frame_ratio.push_back(t[0] / t[1]), crowd_ratio.push_back(t[2] / t[3]);
    vs_eigen.push_back(t[4] / t[5]), vs_cholmod.push_back(t[4] / t[6]);
  }
  state.counters["frame_vs_best"] = Median(frame_ratio);
  state.counters["crowd_vs_best"] = Median(crowd_ratio);
  state.counters["solve_vs_eigen"] = Median(vs_eigen);
  state.counters["solve_vs_cholmod"] = Median(vs_cholmod);
  state.SetLabel(std::string("path=") + IsaName(isa) + " best=" + IsaName(BestIsa()));
}

// Absolute times per path: one frame, and a crowd of 1000 on 1 or 2 threads.
void BM_PathFrame(benchmark::State& state) {
  const Rig* rig = RigOnPath(1, 8, Isa(state.range(0)));
  if (!rig) return state.SkipWithError("this CPU does not run this path");
  RuntimeFrame frame(*rig);
  for (auto _ : state) {
    frame.Run(*rig);
    benchmark::DoNotOptimize(frame.x.data());
  }
  Label(state, *rig);
}

void BM_PathCrowd(benchmark::State& state) {
  const Rig* rig = RigOnPath(1, 8, Isa(state.range(0)));
  if (!rig) return state.SkipWithError("this CPU does not run this path");
  const std::size_t count = 1000;
  const int threads = int(state.range(1));
  CrowdBuffers buffers(*rig, count);
  std::vector<std::vector<double>> work(threads, std::vector<double>(rig->batch_workspace_size()));
  Pool pool(threads);
  double time = 0;
  auto part = [&](int t, int n) { CrowdPart(*rig, time, count * t / n, count * (t + 1) / n, buffers, work[t]); };
  for (auto _ : state) {
    pool.Run(part);
    time += 1.0 / 60;
    benchmark::DoNotOptimize(buffers.x.data());
  }
  Label(state, *rig);
}

// The paths this build has, by Isa value.
const Isa kAllPaths[] = {Isa::kAvx512, Isa::kAvx2, Isa::kSse2, Isa::kScalar, Isa::kNeon, Isa::kWasmSimd};
void Paths(benchmark::internal::Benchmark* b) {
  for (Isa isa : kAllPaths)
    if (detail::CompiledKernels(isa)) b->Arg(int(isa));
}
void PathsAndThreads(benchmark::internal::Benchmark* b) {
  for (Isa isa : kAllPaths)
    if (detail::CompiledKernels(isa))
      for (int threads : {1, 2}) b->Args({int(isa), threads});
}

void SizesAndPoses(benchmark::internal::Benchmark* b) {
  for (int poses : {4, 8})
    for (int size = 0; size < 4; ++size) b->Args({size, poses});
}

}  // namespace

BENCHMARK(BM_RuntimeFrame)->Apply(SizesAndPoses);
BENCHMARK(BM_RuntimeSolve)->Apply(SizesAndPoses);
BENCHMARK(BM_EigenSolve)->Apply(SizesAndPoses);
BENCHMARK(BM_CholmodSolve)->Apply(SizesAndPoses);
BENCHMARK(BM_EigenRefactorEveryFrame)->Apply(SizesAndPoses);
BENCHMARK(BM_PairedRatios)->Apply(SizesAndPoses)->MinTime(1.0);
BENCHMARK(BM_Crowd)->ArgsProduct({{1, 4, 8, 64, 1000}, {1, 2}})->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PathRatios)->Apply(Paths)->MinTime(2.0);
BENCHMARK(BM_PathFrame)->Apply(Paths)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PathCrowd)->Apply(PathsAndThreads)->UseRealTime()->Unit(benchmark::kMillisecond);
