// SPDX-License-Identifier: MIT
// Evaluating a frame allocates nothing: every global operator new and malloc
// is counted while frames run.
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <string>

#include "posemorph/animator.h"
#include "posemorph/state_machine.h"
#include "posemorph/path.h"
#include "posemorph/posemorph.h"
#include "posemorph/quantize.h"
#include "posemorph/draw_list.h"
#include "animator_support.h"
#include "runtime_support.h"

// GCC cannot see that these replacements pair malloc with free on purpose.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

namespace {
std::atomic<long> g_allocations{0};
std::atomic<bool> g_counting{false};
// When >= 0: the number of nothrow allocations to let through before one fails.
std::atomic<int> g_fail_nothrow_after{-1};
}  // namespace

void* operator new(std::size_t n) {
  if (g_counting) ++g_allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  if (g_counting) ++g_allocations;
  if (g_fail_nothrow_after.load() >= 0 && g_fail_nothrow_after.fetch_sub(1) == 0) return nullptr;
  return std::malloc(n ? n : 1);
}
void* operator new[](std::size_t n, const std::nothrow_t& t) noexcept { return operator new(n, t); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

// malloc itself, for code that would bypass operator new (glibc lets a
// program replace it; elsewhere operator new is what is counted).
#if defined(__GLIBC__)
extern "C" void* __libc_malloc(std::size_t);
extern "C" void* malloc(std::size_t n) {
  if (g_counting) ++g_allocations;
  return __libc_malloc(n);
}
#endif

using namespace posemorph;
using namespace posemorph::test;

TEST_CASE("a frame performs zero heap allocations") {
  for (const char* name : {"snake", "snake.compact"}) {
    const Rig rig = LoadTestRig(name);
    const std::uint32_t N = rig.pose_count();
    std::vector<double> raw(N), limited(N), tex(N), work(rig.morph_workspace_size()), x(2 * rig.vertex_count());
    std::vector<float> xf(x.size());
    const int slither = rig.FindPath("slither");

    g_allocations = 0;
    g_counting = true;
    bool ok = true;
    for (int frame = 0; frame < 500; ++frame) {
      double px, py;
      ok &= SamplePath(rig, std::uint32_t(slither), frame / 60.0, &px, &py);
      unsigned char wire[4];
      PackPoint(QuantizePoint(rig.grid(), px, py), wire);
      DequantizePoint(rig.grid(), UnpackPoint(wire), &px, &py);
      WeightsJob wj;
      wj.rig = &rig, wj.x = px, wj.y = py, wj.sigma = 0.4;
      wj.raw = MakeSpan(raw), wj.limited = MakeSpan(limited), wj.texture = MakeSpan(tex);
      ok &= wj.Run();
      MorphJob mj;
      mj.rig = &rig, mj.weights = MakeSpan(raw), mj.limited_weights = MakeSpan(limited);
      mj.workspace = MakeSpan(work), mj.positions = MakeSpan(x), mj.positions_f32 = MakeSpan(xf);
      mj.interpolation = frame % 2 ? Interpolation::kRigid : Interpolation::kLinear;
      ok &= mj.Run();
    }
    g_counting = false;
    CHECK(ok);
    CHECK(g_allocations.load() == 0);

    // A batch of 20 characters (two full groups and a partial one) too.
    const std::size_t count = 20;
    std::vector<double> bw, bws, bwork(rig.batch_workspace_size()), bx(count * x.size());
    for (std::size_t k = 0; k < count; ++k)
      bw.insert(bw.end(), raw.begin(), raw.end()), bws.insert(bws.end(), limited.begin(), limited.end());
    MorphBatchJob batch;
    batch.rig = &rig, batch.count = count;
    batch.weights = MakeSpan(bw), batch.limited_weights = MakeSpan(bws);
    batch.workspace = MakeSpan(bwork), batch.positions = MakeSpan(bx);
    g_allocations = 0;
    g_counting = true;
    for (int frame = 0; frame < 50; ++frame) ok &= batch.Run();
    g_counting = false;
    CHECK(ok);
    CHECK(g_allocations.load() == 0);
  }
}

TEST_CASE("a character with channels: weights per channel, the body and its attachments allocate nothing") {
  const Rig rig = LoadTestRig("pell-face.compact");
  REQUIRE(rig.attachment_count() == 3);
  const Rig& face = *rig.channel_rig(1);
  const std::uint32_t N = rig.pose_count(), NF = face.pose_count();
  const std::size_t count = 13, v2 = 2 * std::size_t(rig.vertex_count()),
                    a2 = 2 * std::size_t(rig.attached_vertex_count());
  std::vector<double> raw(count * N), limited(count * N), fraw(count * NF), flimited(count * NF);
  std::vector<double> work(std::max(rig.batch_workspace_size(), rig.attach_workspace_size()));
  std::vector<double> body(count * v2), attached(count * a2);
  std::vector<float> attached_f32(count * a2);
  g_allocations = 0;
  g_counting = true;
  bool ok = true;
  for (int frame = 0; frame < 20; ++frame) {
    for (std::size_t k = 0; k < count; ++k) {
      double bx, by, fx, fy;
      ok &= SamplePath(rig, 0, 0.1 * double(frame + k), &bx, &by);
      ok &= SamplePath(face, 0, 0.13 * double(frame + k), &fx, &fy);
      WeightsJob wj;
      wj.rig = &rig, wj.x = bx, wj.y = by;
      wj.raw = {raw.data() + k * N, N}, wj.limited = {limited.data() + k * N, N};
      ok &= wj.Run();
      WeightsJob fj;
      fj.rig = &face, fj.x = fx, fj.y = fy;
      fj.raw = {fraw.data() + k * NF, NF}, fj.limited = {flimited.data() + k * NF, NF};
      ok &= fj.Run();
    }
    MorphBatchJob batch;
    batch.rig = &rig, batch.count = count;
    batch.weights = MakeSpan(raw), batch.limited_weights = MakeSpan(limited);
    batch.workspace = MakeSpan(work), batch.positions = MakeSpan(body);
    ok &= batch.Run();
    AttachJob attach;
    attach.rig = &rig, attach.count = frame % 2 ? count : 1;
    attach.body_positions = MakeSpan(body);
    attach.weights = MakeSpan(fraw), attach.limited_weights = MakeSpan(flimited);
    attach.workspace = MakeSpan(work), attach.positions = MakeSpan(attached),
    attach.positions_f32 = MakeSpan(attached_f32);
    ok &= attach.Run();
  }
  g_counting = false;
  CHECK(ok);
  CHECK(g_allocations.load() == 0);
  // Draw lists with the attachments' lists, in one block bound beforehand.
  const CharacterBuffers sizes = CharacterBuffers::For(rig, count);
  std::vector<double> block((sizes.bytes + sizeof(double) - 1) / sizeof(double));
  DrawListJob lists;
  REQUIRE(sizes.Bind(rig, block.data(), block.size() * sizeof(double), &lists));
  std::vector<double> points(2 * count, 0.25), face_points(2 * count, 0.5);
  lists.points = MakeSpan(points);
  lists.channel_points = MakeSpan(face_points);
  g_allocations = 0;
  g_counting = true;
  for (int frame = 0; frame < 10; ++frame) ok &= lists.Run();
  g_counting = false;
  CHECK(ok);
  CHECK(g_allocations.load() == 0);
}

TEST_CASE("draw lists for a crowd allocate nothing, in C++ and through the C API") {
  const Rig rig = LoadTestRig("snake");
  constexpr std::size_t kCount = 12;
  const CharacterBuffers sizes = CharacterBuffers::For(rig, kCount);
  std::vector<double> block(sizes.bytes / sizeof(double) + 1);
  DrawListJob job;
  REQUIRE(sizes.Bind(rig, block.data(), block.size() * sizeof(double), &job));
  std::vector<double> points(2 * kCount);
  std::vector<Transform2D> place(kCount);
  job.points = MakeSpan(points);
  job.transforms = MakeSpan(place);
  const std::vector<unsigned char> bytes = TestRigBytes("snake");
  pm_rig* crig = nullptr;
  pm_error err;
  REQUIRE(pm_rig_load(bytes.data(), bytes.size(), &crig, &err) == PM_OK);
  std::size_t cw = 0, cp = 0;
  REQUIRE(pm_draw_list_buffers(crig, kCount, &cw, &cp) == PM_OK);
  std::vector<double> cwork(cw);
  std::vector<float> cpos(cp);
  std::vector<pm_draw_list> clists(kCount);
  g_allocations = 0;
  g_counting = true;
  bool ok = true;
  for (int frame = 0; frame < 50; ++frame) {
    for (std::size_t k = 0; k < kCount; ++k) {
      points[2 * k] = -1 + 0.02 * double(frame + k), points[2 * k + 1] = 0.3;
      place[k] = Transform2D::Make(double(k), 0, 0.1, 1, 1, k % 2 == 1);
    }
    job.max_drawings = 1 + std::uint32_t(frame % 8);
    job.interpolation = frame % 5 ? Interpolation::kRigid : Interpolation::kLinear;
    ok &= job.Run();
    ok &= pm_draw_lists(crig, nullptr, kCount, points.data(), nullptr, cwork.data(), cwork.size(), cpos.data(),
                        cpos.size(), clists.data(), clists.size()) == PM_OK;
  }
  g_counting = false;
  CHECK(ok);
  CHECK(g_allocations.load() == 0);
  pm_rig_free(crig);
}

TEST_CASE("the C API draws a whole character without allocating: every channel, the attachments, the steps") {
  const std::vector<unsigned char> bytes = TestRigBytes("pell-face.compact");
  pm_rig* rig = nullptr;
  pm_error err;
  REQUIRE(pm_rig_load(bytes.data(), bytes.size(), &rig, &err) == PM_OK);
  constexpr std::size_t kCount = 6;
  pm_character_buffer_sizes sizes;
  REQUIRE(pm_character_buffers(rig, kCount, &sizes) == PM_OK);
  std::vector<double> work(sizes.workspace_doubles), points(2 * kCount), face(2 * kCount);
  std::vector<float> positions(sizes.position_floats), attached_positions(sizes.attached_position_floats);
  std::vector<pm_draw_list> lists(kCount), attached(sizes.attached_lists);
  pm_character_inputs in{};
  in.points = points.data();
  in.channel_points = face.data();
  const std::size_t A = pm_rig_attachment_count(rig);
  pm_draw_step steps[16];
  g_allocations = 0;
  g_counting = true;
  bool ok = true;
  for (int frame = 0; frame < 40; ++frame) {
    for (std::size_t k = 0; k < kCount; ++k) {
      points[2 * k] = -0.5 + 0.02 * double(frame + k), points[2 * k + 1] = 0.2;
      face[2 * k] = 0.3, face[2 * k + 1] = -0.4 + 0.01 * double(frame);
    }
    ok &= pm_character_draw_lists(rig, nullptr, kCount, &in, work.data(), work.size(), positions.data(),
                                  positions.size(), attached_positions.data(), attached_positions.size(), lists.data(),
                                  lists.size(), attached.data(), attached.size()) == PM_OK;
    for (std::size_t k = 0; k < kCount; ++k)
      ok &= pm_character_draw_steps(rig, &lists[k], &attached[k * A], steps, 16) == 7;
  }
  g_counting = false;
  CHECK(ok);
  CHECK(g_allocations.load() == 0);
  pm_rig_free(rig);
}

TEST_CASE("the C API evaluates frames without allocating either") {
  const std::vector<unsigned char> bytes = TestRigBytes("worm-line");
  pm_rig* rig = nullptr;
  pm_error err;
  REQUIRE(pm_rig_load(bytes.data(), bytes.size(), &rig, &err) == PM_OK);
  pm_rig_info info;
  pm_rig_get_info(rig, &info);
  std::vector<double> raw(info.pose_count), limited(info.pose_count), work(pm_morph_workspace_size(rig)),
      x(2 * info.vertex_count);
  g_allocations = 0;
  g_counting = true;
  int status = 0;
  for (int frame = 0; frame < 200; ++frame) {
    status |= pm_weights(rig, -1.5 + frame * 0.015, 0.1, 0.5, 1, raw.data(), limited.data(), nullptr, raw.size());
    status |= pm_morph(rig, raw.data(), limited.data(), 0, work.data(), work.size(), x.data(), nullptr, x.size());
  }
  g_counting = false;
  CHECK(status == PM_OK);
  CHECK(g_allocations.load() == 0);
  pm_rig_free(rig);
}

TEST_CASE("state machine steps allocate nothing: inputs, transitions, pads, blends, colour fades") {
  const Rig rig = LoadTestRig("pell-face");
  const std::size_t count = 8;
  Crowd crowd(rig, count, 16);
  std::vector<MachineInstance> machines(count);
  for (MachineInstance& m : machines) REQUIRE(MachineReset(rig, &m));
  std::vector<MachineChange> changes(4);
  std::size_t written = 0;
  std::uint64_t missed = 0;
  const std::uint32_t wave = std::uint32_t(rig.FindMachineInput("wave")),
                      sway = std::uint32_t(rig.FindMachineInput("sway")),
                      looking = std::uint32_t(rig.FindMachineInput("looking")),
                      gaze = std::uint32_t(rig.FindMachineInput("gaze")),
                      ghost = std::uint32_t(rig.FindMachineInput("ghost"));
  std::vector<Colour> colours(count);
  std::vector<float> part_opacities(count * rig.part_count());
  bool ok = true;
  g_allocations = 0;
  g_counting = true;
  for (int f = 0; f < 300; ++f) {
    for (std::size_t i = 0; i < count; ++i) {
      MachineInstance& m = machines[i];
      if ((f + int(i)) % 50 == 0) ok &= MachineFire(rig, &m, wave);
      if ((f + int(i)) % 70 == 20) ok &= MachineSetNumber(rig, &m, sway, ((f / 70) % 2) * 0.6);
      if ((f + int(i)) % 40 == 10) ok &= MachineSetBool(rig, &m, looking, (f / 40) % 2 == 0);
      ok &= MachineSetPoint(rig, &m, gaze, 0.01 * (f % 50), 0.3);
      if ((f + int(i)) % 60 == 30) ok &= MachineSetBool(rig, &m, ghost, (f / 60) % 2 == 0);
    }
    MachineStepJob step;
    step.rig = &rig, step.count = count;
    step.machines = MakeSpan(machines), step.tracks = MakeSpan(crowd.tracks);
    step.changes = MakeSpan(changes), step.change_count = &written, step.changes_missed = &missed;
    ok &= step.Run();
    ok &= crowd.Job(1.0 / 60).Run();
    MachineColourJob colour;
    colour.rig = &rig, colour.count = count, colour.dt = 1.0 / 60, colour.machines = MakeSpan(machines);
    colour.colours = MakeSpan(colours), colour.part_opacities = MakeSpan(part_opacities);
    ok &= colour.Run();
  }
  g_counting = false;
  CHECK(ok);
  CHECK(g_allocations.load() == 0);
}

TEST_CASE("the C API animates a crowd without allocating: commands, behaviours, machines, colours, updates, states") {
  const std::vector<unsigned char> bytes = TestRigBytes("pell-face");
  pm_rig* rig = nullptr;
  pm_error err;
  REQUIRE(pm_rig_load(bytes.data(), bytes.size(), &rig, &err) == PM_OK);
  pm_rig_info info;
  pm_rig_get_info(rig, &info);
  const std::size_t count = 8, N = info.pose_count, A = pm_rig_attached_weight_count(rig);
  const std::size_t size = pm_animator_size(rig, count);
  std::vector<double> tracks((size + sizeof(double) - 1) / sizeof(double));
  std::vector<double> raw(count * N), limited(count * N), ar(count * A), al(count * A);
  std::vector<pm_animator_event> events(4);
  std::size_t written = 0;
  std::uint64_t missed = 0, most_missed = 0;
  unsigned char state[4096];
  pm_behaviours b;
  pm_behaviours_default(&b);
  b.blink_enabled = b.breath_enabled = b.look_at_enabled = b.spring_enabled = 1;
  const std::size_t msize = pm_machine_size(rig, count);
  std::vector<double> machines((msize + sizeof(double) - 1) / sizeof(double));
  const std::uint32_t wave = std::uint32_t(pm_machine_find_input(rig, "wave"));
  std::vector<pm_colour> colours(count);
  std::vector<float> parts(count * pm_rig_part_count(rig));
  g_allocations = 0;
  g_counting = true;
  int status =
      pm_animator_reset(rig, tracks.data(), size, count) | pm_machine_reset(rig, machines.data(), msize, count);
  for (int f = 0; f < 120; ++f) {
    for (std::size_t i = 0; i < count; ++i) {
      if (f == 0) status |= pm_animator_set_behaviours(rig, tracks.data(), size, i, 1, &b);
      if ((f + int(i)) % 30 == 0) status |= pm_animator_play(rig, tracks.data(), size, i, 0, 0, nullptr);
      if ((f + int(i)) % 17 == 0) status |= pm_animator_look_at(rig, tracks.data(), size, i, 1, 0.5, 0.5);
    }
    if (f % 25 == 0) status |= pm_machine_fire(rig, machines.data(), msize, std::size_t(f) % count, wave);
    status |= pm_machine_step(rig, machines.data(), msize, count, tracks.data(), size);
    if (f % 10 == 0) {  // a late joiner: character 0's state into character 1
      std::size_t n = 0;
      status |= pm_animator_save(rig, tracks.data(), size, 0, state, sizeof state, &n);
      status |= pm_animator_load(rig, state, n, tracks.data(), size, 1);
    }
    status |= pm_animator_update(rig, tracks.data(), size, count, f % 40 == 0 ? 5.0 : 1.0 / 60, -1, 1, raw.data(),
                                 limited.data(), nullptr, raw.size(), ar.data(), al.data(), nullptr, ar.size(),
                                 events.data(), events.size(), &written, &missed);
    most_missed = std::max(most_missed, missed);
    status |=
        pm_machine_colours(rig, machines.data(), msize, count, 1.0 / 60, colours.data(), parts.data(), parts.size());
  }
  g_counting = false;
  CHECK(status == PM_OK);
  CHECK(most_missed > 0);  // the 5 s updates overflow the 4 entries
  CHECK(g_allocations.load() == 0);
  pm_rig_free(rig);
}

TEST_CASE("the C API reports a failed allocation with a message, whichever allocation fails") {
  const std::vector<unsigned char> bytes = TestRigBytes("small");
  const char* expected[] = {"rig handle", "cannot allocate"};  // the handle, then the rig's arena
  for (int after = 0; after < 2; ++after) {
    CAPTURE(after);
    pm_rig* rig = nullptr;
    pm_error err;
    g_fail_nothrow_after = after;
    const int status = pm_rig_load(bytes.data(), bytes.size(), &rig, &err);
    g_fail_nothrow_after = -1;
    CHECK(status == PM_ERROR_OUT_OF_MEMORY);
    CHECK(err.code == PM_ERROR_OUT_OF_MEMORY);
    CHECK(std::string(err.message).find(expected[after]) != std::string::npos);
    CHECK(rig == nullptr);
  }
  // And with memory to spare it loads.
  pm_rig* rig = nullptr;
  REQUIRE(pm_rig_load(bytes.data(), bytes.size(), &rig, nullptr) == PM_OK);
  pm_rig_free(rig);
}

TEST_CASE("loading in place allocates nothing at all, in C++ and through the C API") {
  // The exact rig, and the compact one (whose factor, angles and grid are
  // computed at load, in the caller's memory too).
  for (const char* name : {"snake", "snake.compact", "pell-face.compact"}) {
    const std::string rig_name = name;
    CAPTURE(rig_name);
    const std::vector<unsigned char> bytes = TestRigBytes(name);
    std::size_t needed = 0, c_needed = 0;
    REQUIRE(RigMemorySize(bytes.data(), bytes.size(), &needed, nullptr));
    REQUIRE(pm_rig_memory_size(bytes.data(), bytes.size(), &c_needed, nullptr) == PM_OK);
    std::vector<unsigned char> memory_block(needed + kRigMemoryAlignment),
        c_memory_block(c_needed + kRigMemoryAlignment);
    auto align = [](std::vector<unsigned char>& v) {
      const std::uintptr_t p = reinterpret_cast<std::uintptr_t>(v.data());
      return v.data() + (kRigMemoryAlignment - p % kRigMemoryAlignment) % kRigMemoryAlignment;
    };
    unsigned char* memory = align(memory_block);
    unsigned char* c_memory = align(c_memory_block);
    Rig rig;
    pm_rig* c_rig = nullptr;
    g_allocations = 0;
    g_counting = true;
    std::size_t again = 0;
    const bool sized = RigMemorySize(bytes.data(), bytes.size(), &again, nullptr);
    const bool loaded = LoadRigInPlace(bytes.data(), bytes.size(), memory, needed, &rig, nullptr);
    const int c_status = pm_rig_load_in_place(bytes.data(), bytes.size(), c_memory, c_needed, &c_rig, nullptr);
    g_counting = false;
    CHECK(sized);
    CHECK(loaded);
    CHECK(c_status == PM_OK);
    CHECK(g_allocations.load() == 0);
    pm_rig_free(c_rig);
  }
}

TEST_CASE("animator commands and updates allocate nothing: mixes, queues, snapshots, events, behaviours") {
  const Rig rig = LoadTestRig("pell-face");
  const std::size_t count = 16, C = rig.channel_count();
  Crowd crowd(rig, count, 8);  // a small event buffer: it fills
  std::size_t most = 0;
  std::uint64_t most_missed = 0;
  g_allocations = 0;
  g_counting = true;
  bool ok = true;
  Behaviours b;  // every behaviour on every channel
  b.blink.enabled = b.breath.enabled = b.look_at.enabled = b.spring.enabled = true;
  b.blink.interval = 0.5, b.breath.y = 0.05;
  for (std::size_t i = 0; i < count; ++i) {
    const Span<AnimatorTrack> t = crowd.Tracks(i);
    ok &= AnimatorReset(rig, t);
    b.blink.seed = i;
    for (std::uint32_t c = 0; c < C; ++c) ok &= AnimatorSetBehaviours(rig, t, c, b);
  }
  for (int f = 0; f < 240; ++f) {
    for (std::size_t i = 0; i < count; ++i) {
      const Span<AnimatorTrack> t = crowd.Tracks(i);
      PlayOptions o;
      o.mix = 0.25;
      if ((f + int(i)) % 40 == 0) ok &= AnimatorPlay(rig, t, std::uint32_t(i % C), 0, o);
      if ((f + int(i)) % 40 == 10) ok &= AnimatorPlay(rig, t, std::uint32_t(i % C), 0, o);  // interrupts a mix
      if ((f + int(i)) % 40 == 20) ok &= AnimatorQueue(rig, t, 0, 0, o);
      if ((f + int(i)) % 40 == 30) ok &= AnimatorSetPoint(rig, t, 1, 0.5, 0.5, 0.3);
      if ((f + int(i)) % 97 == 0) ok &= AnimatorStop(rig, t, 0, 0.2);
      if ((f + int(i)) % 13 == 0) ok &= AnimatorLookAt(rig, t, std::uint32_t(f % C), 0.01 * f, -0.5);
    }
    ok &= crowd.Job(f == 120 ? 1e9 : f % 50 == 0 ? 7.0 : 1.0 / 60).Run();  // 1e9: the behaviours settle
    most = std::max(most, crowd.written);
    most_missed = std::max(most_missed, crowd.missed);
  }
  g_counting = false;
  CHECK(ok);
  CHECK(most == crowd.buffer.size());  // the 7 s updates fill the buffer
  CHECK(most_missed > 0);
  CHECK(g_allocations.load() == 0);
}
