// SPDX-License-Identifier: MIT
// Validity tests in the ozz-animation manner: for every job, a valid job
// runs, and each failure case listed in its header (jobs.h, draw_list.h)
// makes Validate() false and Run() refuse without touching the outputs.
#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <type_traits>
#include <vector>

#include "posemorph/draw_list.h"
#include "posemorph/jobs.h"
#include "runtime_support.h"

using namespace posemorph;
using namespace posemorph::test;

namespace {

constexpr double kSentinel = -12345.0;

struct WeightsBuffers {
  std::vector<double> raw, limited, texture, out;
};

struct MorphBuffers {
  std::vector<double> weights, limited, workspace, positions, out;
  std::vector<float> f32;
};

template <typename Job, typename Buffers>
using Breaks = std::vector<std::pair<const char*, std::function<void(Job&, Buffers&)>>>;

// From a valid job over a copy of `fresh`, each case breaks one thing:
// Validate() is false, Run() refuses, and `untouched` finds the outputs as
// they were.
template <typename Job, typename Buffers, typename Valid, typename Untouched>
void CheckRefusals(const Buffers& fresh, Valid valid, const Breaks<Job, Buffers>& cases, Untouched untouched) {
  for (const auto& c : cases) {
    const char* what = c.first;  // (Clang 14 cannot capture a structured binding)
    CAPTURE(what);
    Buffers b = fresh;
    Job j;
    valid(j, b);
    REQUIRE(j.Validate());
    c.second(j, b);
    CHECK_FALSE(j.Validate());
    CHECK_FALSE(j.Run());
    untouched(b);
  }
}

}  // namespace

TEST_CASE("WeightsJob: a valid job runs, and each failure case of its header is refused") {
  const Rig rig = LoadTestRig("snake");
  const std::size_t N = rig.pose_count();
  WeightsBuffers fresh;
  fresh.raw.assign(N, kSentinel), fresh.limited.assign(N, kSentinel), fresh.texture.assign(N, kSentinel);
  auto valid = [&](WeightsJob& j, WeightsBuffers& b) {
    j.rig = &rig;
    j.x = 0.3, j.y = 0.2;
    j.raw = MakeSpan(b.raw), j.limited = MakeSpan(b.limited), j.texture = MakeSpan(b.texture);
  };
  {
    WeightsBuffers b = fresh;
    WeightsJob j;
    valid(j, b);
    REQUIRE(j.Run());
    double sum = 0;
    for (double w : b.raw) sum += w;
    CHECK(std::fabs(sum - 1) < 1e-12);
  }
  const Rig empty;
  const Breaks<WeightsJob, WeightsBuffers> cases = {
      {"null rig", [](WeightsJob& j, WeightsBuffers&) { j.rig = nullptr; }},
      {"rig not loaded", [&](WeightsJob& j, WeightsBuffers&) { j.rig = &empty; }},
      {"raw null", [](WeightsJob& j, WeightsBuffers&) { j.raw = {}; }},
      {"raw short",
       [](WeightsJob& j, WeightsBuffers& b) {
         j.raw = {b.raw.data(), b.raw.size() - 1};
       }},
      {"limited given but null",
       [](WeightsJob& j, WeightsBuffers& b) {
         j.limited = {nullptr, b.limited.size()};
       }},
      {"limited short",
       [](WeightsJob& j, WeightsBuffers& b) {
         j.limited = {b.limited.data(), b.limited.size() - 1};
       }},
      {"texture given but null",
       [](WeightsJob& j, WeightsBuffers& b) {
         j.texture = {nullptr, b.texture.size()};
       }},
      {"texture short",
       [](WeightsJob& j, WeightsBuffers& b) {
         j.texture = {b.texture.data(), b.texture.size() - 1};
       }},
  };
  CheckRefusals<WeightsJob>(fresh, valid, cases, [](const WeightsBuffers& b) {
    for (const std::vector<double>* out : {&b.raw, &b.limited, &b.texture})
      for (double v : *out) REQUIRE(v == kSentinel);
  });
}

TEST_CASE("MorphJob: a valid job runs, and each failure case of its header is refused") {
  const Rig rig = LoadTestRig("snake");
  const std::size_t N = rig.pose_count(), v2 = 2 * std::size_t(rig.vertex_count());
  MorphBuffers fresh;
  fresh.weights.assign(N, 1.0 / double(N)), fresh.limited = fresh.weights;
  fresh.workspace.assign(rig.morph_workspace_size(), 0);
  fresh.positions.assign(v2, kSentinel);
  fresh.f32.assign(v2, float(kSentinel));
  auto valid = [&](MorphJob& j, MorphBuffers& b) {
    j.rig = &rig;
    j.weights = MakeSpan(b.weights), j.limited_weights = MakeSpan(b.limited);
    j.workspace = MakeSpan(b.workspace), j.positions = MakeSpan(b.positions), j.positions_f32 = MakeSpan(b.f32);
  };
  {
    MorphBuffers b = fresh;
    MorphJob j;
    valid(j, b);
    REQUIRE(j.Run());
    for (double v : b.positions) REQUIRE(std::isfinite(v));
  }
  const Rig empty;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const Breaks<MorphJob, MorphBuffers> cases = {
      {"null rig", [](MorphJob& j, MorphBuffers&) { j.rig = nullptr; }},
      {"rig not loaded", [&](MorphJob& j, MorphBuffers&) { j.rig = &empty; }},
      {"weights null", [](MorphJob& j, MorphBuffers&) { j.weights = {}; }},
      {"weights short",
       [](MorphJob& j, MorphBuffers& b) {
         j.weights = {b.weights.data(), b.weights.size() - 1};
       }},
      {"limited weights null", [](MorphJob& j, MorphBuffers&) { j.limited_weights = {}; }},
      {"limited weights short",
       [](MorphJob& j, MorphBuffers& b) {
         j.limited_weights = {b.limited.data(), b.limited.size() - 1};
       }},
      {"a NaN weight", [nan](MorphJob&, MorphBuffers& b) { b.weights[1] = nan; }},
      {"an infinite limited weight", [inf](MorphJob&, MorphBuffers& b) { b.limited[0] = -inf; }},
      {"a weight above kMaxJobWeight", [](MorphJob&, MorphBuffers& b) { b.weights[0] = 2 * kMaxJobWeight; }},
      {"workspace null", [](MorphJob& j, MorphBuffers&) { j.workspace = {}; }},
      {"workspace short",
       [](MorphJob& j, MorphBuffers& b) {
         j.workspace = {b.workspace.data(), b.workspace.size() - 1};
       }},
      {"positions null", [](MorphJob& j, MorphBuffers&) { j.positions = {}; }},
      {"positions short",
       [](MorphJob& j, MorphBuffers& b) {
         j.positions = {b.positions.data(), b.positions.size() - 1};
       }},
      {"float copy given but null",
       [](MorphJob& j, MorphBuffers& b) {
         j.positions_f32 = {nullptr, b.f32.size()};
       }},
      {"float copy short",
       [](MorphJob& j, MorphBuffers& b) {
         j.positions_f32 = {b.f32.data(), b.f32.size() - 1};
       }},
      {"unknown interpolation", [](MorphJob& j, MorphBuffers&) { j.interpolation = Interpolation(7); }},
  };
  CheckRefusals<MorphJob>(fresh, valid, cases, [](const MorphBuffers& b) {
    for (double v : b.positions) REQUIRE(v == kSentinel);
    for (float v : b.f32) REQUIRE(v == float(kSentinel));
  });
}

TEST_CASE("MorphBatchJob: a valid job runs, and each failure case of its header is refused") {
  const Rig rig = LoadTestRig("snake");
  const std::size_t N = rig.pose_count(), v2 = 2 * std::size_t(rig.vertex_count()), count = 3;
  MorphBuffers fresh;
  fresh.weights.assign(count * N, 1.0 / double(N)), fresh.limited = fresh.weights;
  fresh.workspace.assign(rig.batch_workspace_size(), 0);
  fresh.positions.assign(count * v2, kSentinel);
  fresh.f32.assign(count * v2, float(kSentinel));
  auto valid = [&](MorphBatchJob& j, MorphBuffers& b) {
    j.rig = &rig;
    j.count = count;
    j.weights = MakeSpan(b.weights), j.limited_weights = MakeSpan(b.limited);
    j.workspace = MakeSpan(b.workspace), j.positions = MakeSpan(b.positions), j.positions_f32 = MakeSpan(b.f32);
  };
  {
    MorphBuffers b = fresh;
    MorphBatchJob j;
    valid(j, b);
    REQUIRE(j.Run());
    for (double v : b.positions) REQUIRE(std::isfinite(v));
  }
  const Rig empty;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Breaks<MorphBatchJob, MorphBuffers> cases = {
      {"null rig", [](MorphBatchJob& j, MorphBuffers&) { j.rig = nullptr; }},
      {"rig not loaded", [&](MorphBatchJob& j, MorphBuffers&) { j.rig = &empty; }},
      {"count overflows", [](MorphBatchJob& j, MorphBuffers&) { j.count = std::size_t(-1) / 4; }},
      {"weights null", [](MorphBatchJob& j, MorphBuffers&) { j.weights = {}; }},
      {"weights short for the count", [](MorphBatchJob& j, MorphBuffers&) { ++j.count; }},
      {"limited weights short",
       [](MorphBatchJob& j, MorphBuffers& b) {
         j.limited_weights = {b.limited.data(), b.limited.size() - 1};
       }},
      {"a NaN weight of the last character", [nan](MorphBatchJob&, MorphBuffers& b) { b.weights.back() = nan; }},
      {"a weight above kMaxJobWeight", [](MorphBatchJob&, MorphBuffers& b) { b.limited[0] = -2 * kMaxJobWeight; }},
      {"workspace short",
       [](MorphBatchJob& j, MorphBuffers& b) {
         j.workspace = {b.workspace.data(), b.workspace.size() - 1};
       }},
      {"no output at all", [](MorphBatchJob& j, MorphBuffers&) { j.positions = {}, j.positions_f32 = {}; }},
      {"positions given but null",
       [](MorphBatchJob& j, MorphBuffers& b) {
         j.positions = {nullptr, b.positions.size()};
       }},
      {"positions short",
       [](MorphBatchJob& j, MorphBuffers& b) {
         j.positions = {b.positions.data(), b.positions.size() - 1};
       }},
      {"float copy short",
       [](MorphBatchJob& j, MorphBuffers& b) {
         j.positions_f32 = {b.f32.data(), b.f32.size() - 1};
       }},
  };
  CheckRefusals<MorphBatchJob>(fresh, valid, cases, [](const MorphBuffers& b) {
    for (double v : b.positions) REQUIRE(v == kSentinel);
    for (float v : b.f32) REQUIRE(v == float(kSentinel));
  });
}

TEST_CASE("MakeSpan takes containers and C arrays, keeping their constness") {
  double plain[5] = {};
  const float fixed[3] = {1, 2, 3};
  std::vector<std::uint32_t> v(7);
  const Span<double> a = MakeSpan(plain);
  const Span<const float> b = MakeSpan(fixed);
  const Span<std::uint32_t> c = MakeSpan(v);
  CHECK(a.data == plain);
  CHECK(a.size == 5);
  CHECK(b.data == fixed);
  CHECK(b.size == 3);
  CHECK(b[2] == 3.0f);
  CHECK(c.data == v.data());
  CHECK(c.size == 7);
  static_assert(std::is_same<decltype(MakeSpan(fixed)), Span<const float>>::value, "a const array gives a const span");
}
