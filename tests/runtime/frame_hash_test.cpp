// SPDX-License-Identifier: MIT
// Frames are the same bits on every kernel path, compiler and target: for
// each sample rig, weights and positions (double and float) at fixed
// pose-space points and path times hash to the values committed in
// tests/goldens/frame-hashes.txt. This is what lets network peers in
// lockstep compute the same vertices from the same 4 bytes. The same test
// runs natively (GCC, Clang, every x86-64 path), under qemu-aarch64, wine
// and node (.ci/run). Animator timelines on the character with channels
// (behaviours, mixes, events) are hashed the same way. POSEMORPH_BLESS=1
// rewrites the file.
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "animator_support.h"
#include "posemorph/animator.h"
#include "posemorph/path.h"
#include "runtime_support.h"

using namespace posemorph;
using namespace posemorph::test;

namespace {

// The exact rigs and their compact encodings (derived at load: the same
// bits on every target too); Pell and the arm are layered (parts glued in
// one solve); Pell with a face channel has attachments (format 1.7), whose
// positions join its hashes.
const char* const kSampleRigs[] = {"snake",
                                   "worm-line",
                                   "gingerbread",
                                   "pip",
                                   "sprout",
                                   "pell",
                                   "arm",
                                   "pell-face",
                                   "snake.compact",
                                   "worm-line.compact",
                                   "gingerbread.compact",
                                   "pip.compact",
                                   "sprout.compact",
                                   "pell.compact",
                                   "arm.compact",
                                   "pell-face.compact"};

// FNV-1a, 64 bits, over the bytes of every value in order.
struct Fnv64 {
  std::uint64_t h = 0xcbf29ce484222325ull;
  void Add(const void* data, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
  }
  template <typename T>
  void Add(const std::vector<T>& v) {
    Add(v.data(), v.size() * sizeof(T));
  }
};

std::string Hex(std::uint64_t v) {
  char s[17];
  std::snprintf(s, sizeof(s), "%016llx", static_cast<unsigned long long>(v));
  return s;
}

// Pose-space points: every pose point, the midpoints of consecutive ones,
// points beyond the grid (extrapolation, clamping), a few irregular inner
// points, and each path at fixed times (also past its end).
std::vector<std::pair<double, double>> FramePoints(const Rig& rig) {
  std::vector<std::pair<double, double>> pts;
  const std::uint32_t N = rig.pose_count();
  const Span<const double> p = rig.pose_points();
  for (std::uint32_t i = 0; i < N; ++i) {
    pts.push_back({p[2 * i], p[2 * i + 1]});
    const std::uint32_t j = (i + 1) % N;
    pts.push_back({0.5 * (p[2 * i] + p[2 * j]), 0.5 * (p[2 * i + 1] + p[2 * j + 1])});
  }
  const PoseSpaceGrid& g = rig.grid();
  const double w = g.cell * g.cells_x, h = g.cell * g.cells_y;
  for (double fx : {-0.3, 0.137, 0.5, 0.71, 1.4})
    for (double fy : {-0.2, 0.29, 0.618, 1.25}) pts.push_back({g.origin_x + fx * w, g.origin_y + fy * h});
  for (std::uint32_t path = 0; path < rig.path_count(); ++path)
    for (int k = 0; k < 9; ++k) {
      double x = 0, y = 0;
      REQUIRE(SamplePath(rig, path, 0.37 * k, &x, &y));
      pts.push_back({x, y});
    }
  return pts;
}

// A character with channels: frame k puts every other channel at its own
// k-th frame point; the attachments' positions (AttachJob, one character at
// a time, then all as one batch, which must agree) join the hashes.
void HashAttachments(const Rig& rig, const std::vector<std::pair<double, double>>& pts,
                     const std::vector<double>& singles, const std::vector<double>& batch, Fnv64* hw, Fnv64* hx,
                     Fnv64* hf) {
  const std::size_t count = pts.size(), v2 = 2 * std::size_t(rig.vertex_count());
  const std::size_t a2 = 2 * std::size_t(rig.attached_vertex_count()), NW = rig.attached_weight_count();
  std::vector<std::vector<std::pair<double, double>>> channel_points(rig.channel_count());
  for (std::uint32_t c = 1; c < rig.channel_count(); ++c) channel_points[c] = FramePoints(*rig.channel_rig(c));
  std::vector<double> all_w(count * NW), all_ws(count * NW), single_out(count * a2);
  std::vector<double> work(rig.attach_workspace_size());
  for (std::size_t k = 0; k < count; ++k) {
    std::vector<double> w(NW), ws(NW), xa(a2);
    std::vector<float> xaf(a2);
    for (std::uint32_t c = 1; c < rig.channel_count(); ++c) {
      const Rig& channel = *rig.channel_rig(c);
      const auto& pt = channel_points[c][k % channel_points[c].size()];
      const Weights cw = WeightsAt(channel, pt.first, pt.second, 0.5);
      hw->Add(cw.raw), hw->Add(cw.limited), hw->Add(cw.texture);
      const std::size_t n = channel.pose_count(), at = rig.channel_weight_offset(c);
      for (std::size_t i = 0; i < n; ++i) {
        w[at + i] = cw.raw[i], ws[at + i] = cw.limited[i];
        all_w[at * count + k * n + i] = cw.raw[i], all_ws[at * count + k * n + i] = cw.limited[i];
      }
    }
    AttachJob job;
    job.rig = &rig;
    job.body_positions = {singles.data() + k * v2, v2};
    job.weights = MakeSpan(w), job.limited_weights = MakeSpan(ws);
    job.workspace = MakeSpan(work), job.positions = MakeSpan(xa), job.positions_f32 = MakeSpan(xaf);
    REQUIRE(job.Run());
    hx->Add(xa), hf->Add(xaf);
    std::memcpy(single_out.data() + k * a2, xa.data(), a2 * sizeof(double));
  }
  std::vector<double> batch_out(count * a2);
  AttachJob job;
  job.rig = &rig, job.count = count;
  job.body_positions = {batch.data(), batch.size()};
  job.weights = MakeSpan(all_w), job.limited_weights = MakeSpan(all_ws);
  job.workspace = MakeSpan(work), job.positions = MakeSpan(batch_out);
  REQUIRE(job.Run());
  // The batch holds attachment after attachment, each character after character.
  std::size_t at = 0;
  bool same = true;
  for (std::uint32_t a = 0; a < rig.attachment_count(); ++a) {
    const std::size_t p2 = 2 * std::size_t(rig.attachment(a).rig->vertex_count());
    for (std::size_t k = 0; k < count; ++k)
      same = same && std::memcmp(batch_out.data() + at * count + k * p2, single_out.data() + k * a2 + at,
                                 p2 * sizeof(double)) == 0;
    at += p2;
  }
  CHECK(same);
}

struct FrameHashes {
  std::string weights, positions, positions_f32;
};

// Single evaluations for every point, then all of them as one batch, which
// must give the same bits.
FrameHashes HashFrames(const Rig& rig) {
  const auto pts = FramePoints(rig);
  const std::size_t N = rig.pose_count(), v2 = 2 * std::size_t(rig.vertex_count());
  Fnv64 hw, hx, hf;
  std::vector<double> all_w, all_ws, singles;
  std::vector<float> singles_f32;
  for (const auto& pt : pts) {
    const Weights w = WeightsAt(rig, pt.first, pt.second, 0.5);
    hw.Add(w.raw), hw.Add(w.limited), hw.Add(w.texture);
    std::vector<double> work(rig.morph_workspace_size()), x(v2);
    std::vector<float> xf(v2);
    MorphJob job;
    job.rig = &rig, job.weights = MakeSpan(w.raw), job.limited_weights = MakeSpan(w.limited);
    job.workspace = MakeSpan(work), job.positions = MakeSpan(x), job.positions_f32 = MakeSpan(xf);
    REQUIRE(job.Run());
    hx.Add(x), hf.Add(xf);
    all_w.insert(all_w.end(), w.raw.begin(), w.raw.end());
    all_ws.insert(all_ws.end(), w.limited.begin(), w.limited.end());
    singles.insert(singles.end(), x.begin(), x.end());
    singles_f32.insert(singles_f32.end(), xf.begin(), xf.end());
  }
  std::vector<double> work(rig.batch_workspace_size()), batch(pts.size() * v2);
  std::vector<float> batch_f32(batch.size());
  MorphBatchJob job;
  job.rig = &rig, job.count = pts.size();
  job.weights = MakeSpan(all_w), job.limited_weights = MakeSpan(all_ws);
  job.workspace = MakeSpan(work), job.positions = MakeSpan(batch), job.positions_f32 = MakeSpan(batch_f32);
  REQUIRE(job.Run());
  CHECK(std::memcmp(batch.data(), singles.data(), batch.size() * sizeof(double)) == 0);
  CHECK(std::memcmp(batch_f32.data(), singles_f32.data(), batch_f32.size() * sizeof(float)) == 0);
  (void)N;
  if (rig.attachment_count() > 0) HashAttachments(rig, pts, singles, batch, &hw, &hx, &hf);
  return {Hex(hw.h), Hex(hx.h), Hex(hf.h)};
}

// An animator timeline on a character with channels: three characters in
// one batch with every behaviour (spring, breath, blink, look-at), plays,
// mixes, queues, an interrupted mix, pad points and look targets, over
// uneven steps (a long one too). Weights and events of every update, and
// every tenth update's positions (body and attachments) join the hashes.
FrameHashes HashAnimator(const Rig& rig) {
  const std::size_t count = 3, C = rig.channel_count(), A = rig.attached_weight_count();
  const std::size_t v2 = 2 * std::size_t(rig.vertex_count()), a2 = 2 * std::size_t(rig.attached_vertex_count());
  Crowd crowd(rig, count, 64);
  for (std::size_t i = 0; i < count; ++i) {
    const Span<AnimatorTrack> t = crowd.Tracks(i);
    Behaviours body;
    body.spring.enabled = true, body.spring.frequency = 2 + double(i), body.spring.damping = 0.25;
    body.breath.enabled = true, body.breath.period = 3.1, body.breath.y = 0.04;
    REQUIRE(AnimatorSetBehaviours(rig, t, 0, body));
    Behaviours face;
    face.blink.enabled = true, face.blink.pose = 3, face.blink.interval = 0.7, face.blink.seed = 11 + i;
    face.look_at.enabled = true, face.look_at.smoothing = 0.15, face.look_at.strength = 0.7;
    face.spring.enabled = true, face.spring.frequency = 3.5;
    if (C > 1) REQUIRE(AnimatorSetBehaviours(rig, t, 1, face));
  }
  Fnv64 hw, hx, hf;
  std::vector<double> work(rig.batch_workspace_size()), x(count * v2), attach_work(rig.attach_workspace_size()),
      xa(count * a2);
  std::vector<float> xf(count * v2);
  const double dts[] = {1.0 / 60, 1.0 / 144, 0.05, 0, 1.0 / 30};
  for (int f = 0; f < 200; ++f) {
    for (std::size_t i = 0; i < count; ++i) {
      const Span<AnimatorTrack> t = crowd.Tracks(i);
      const int g = f + 7 * int(i);
      PlayOptions o;
      o.mix = 0.3, o.speed = 0.8 + 0.2 * double(i), o.start = 0.05 * g;
      if (g % 37 == 0) AnimatorPlay(rig, t, 0, 0, o);
      if (g % 37 == 6) AnimatorPlay(rig, t, 0, 0, o);  // interrupts the mix
      if (g % 41 == 7) AnimatorQueue(rig, t, 0, 0, o);
      if (g % 53 == 5) AnimatorSetPoint(rig, t, C - 1, 0.3, 0.6, 0.2);
      if (g % 43 == 9) AnimatorPlay(rig, t, C - 1, 0, o);
      if (g % 29 == 3) AnimatorLookAt(rig, t, C - 1, std::cos(0.1 * g), std::sin(0.1 * g));
      if (g % 61 == 20) AnimatorSetPoint(rig, t, 0, -1, 0, 0);  // a cut: the spring rings
    }
    REQUIRE(crowd.Job(f == 100 ? 3.0 : dts[f % 5]).Run());
    hw.Add(crowd.raw), hw.Add(crowd.limited), hw.Add(crowd.texture);
    hw.Add(crowd.attached_raw), hw.Add(crowd.attached_limited), hw.Add(crowd.attached_texture);
    for (std::size_t k = 0; k < crowd.written; ++k) {
      const AnimatorEvent& e = crowd.buffer[k];
      const std::uint32_t fields[] = {e.character, e.channel, e.event, e.outgoing ? 1u : 0u};
      hw.Add(fields, sizeof(fields)), hw.Add(&e.time, sizeof(e.time));
    }
    hw.Add(&crowd.missed, sizeof(crowd.missed));
    if (f % 10 != 0) continue;
    MorphBatchJob morph;
    morph.rig = &rig, morph.count = count;
    morph.weights = MakeSpan(crowd.raw), morph.limited_weights = MakeSpan(crowd.limited);
    morph.workspace = MakeSpan(work), morph.positions = MakeSpan(x), morph.positions_f32 = MakeSpan(xf);
    REQUIRE(morph.Run());
    hx.Add(x), hf.Add(xf);
    if (A == 0) continue;
    AttachJob attach;
    attach.rig = &rig, attach.count = count;
    attach.body_positions = MakeSpan(x);
    attach.weights = MakeSpan(crowd.attached_raw), attach.limited_weights = MakeSpan(crowd.attached_limited);
    attach.workspace = MakeSpan(attach_work), attach.positions = MakeSpan(xa);
    REQUIRE(attach.Run());
    hx.Add(xa);
  }
  return {Hex(hw.h), Hex(hx.h), Hex(hf.h)};
}

const char* const kAnimatorRigs[] = {"pell-face", "pell-face.compact"};

std::string GoldenPath() {
  if (const char* env = std::getenv("POSEMORPH_GOLDENS")) return std::string(env) + "/frame-hashes.txt";
#ifdef POSEMORPH_SOURCE_DIR
  return std::string(POSEMORPH_SOURCE_DIR) + "/tests/goldens/frame-hashes.txt";
#else
  return "frame-hashes.txt";
#endif
}

std::map<std::string, FrameHashes> ReadGoldens() {
  std::map<std::string, FrameHashes> goldens;
  std::ifstream in(GoldenPath());
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string rig;
    FrameHashes h;
    if (fields >> rig >> h.weights >> h.positions >> h.positions_f32) goldens[rig] = h;
  }
  return goldens;
}

const Isa kEveryPath[] = {Isa::kScalar, Isa::kSse2, Isa::kAvx2, Isa::kAvx512, Isa::kNeon, Isa::kWasmSimd};

}  // namespace

TEST_CASE("frames hash to the committed values on every kernel path") {
  const bool bless = std::getenv("POSEMORPH_BLESS") != nullptr;
  const std::map<std::string, FrameHashes> goldens = ReadGoldens();
  if (!bless) REQUIRE_MESSAGE(!goldens.empty(), "cannot read " << GoldenPath());
  std::ostringstream blessed;
  blessed << "# Frame hashes (FNV-1a 64) per sample rig: weights (raw, limited, texture), positions (double),\n"
             "# positions (float), at the points of tests/runtime/frame_hash_test.cpp; animator:R lines hash an\n"
             "# animator timeline on R (HashAnimator there). POSEMORPH_BLESS=1 rewrites.\n";
  int paths_run = 0;
  std::vector<std::string> names(std::begin(kSampleRigs), std::end(kSampleRigs));
  for (const char* name : kAnimatorRigs) names.push_back(std::string("animator:") + name);
  for (const std::string& key : names) {
    // "animator:R": the animator timeline (HashAnimator) on rig R.
    const bool animator = key.rfind("animator:", 0) == 0;
    const std::string name = animator ? key.substr(9) : key;
    auto hash = [&](const Rig& r) { return animator ? HashAnimator(r) : HashFrames(r); };
    const Rig rig = LoadTestRig(name);  // the default path (POSEMORPH_ISA when set)
    const FrameHashes h = hash(rig);
    blessed << key << ' ' << h.weights << ' ' << h.positions << ' ' << h.positions_f32 << '\n';
    const std::string rig_name = key;
    CAPTURE(rig_name);
    const std::string path = IsaName(rig.isa());
    CAPTURE(path);
    if (!bless) {
      REQUIRE_MESSAGE(goldens.count(key), "no golden for " << key);
      const FrameHashes& g = goldens.at(key);
      CHECK(h.weights == g.weights);
      CHECK(h.positions == g.positions);
      CHECK(h.positions_f32 == g.positions_f32);
    }
    // Every other path this build and CPU run gives the same bits.
    for (Isa isa : kEveryPath) {
      if (!IsaAvailable(isa) || isa == rig.isa()) continue;
      const std::string other_path = IsaName(isa);
      CAPTURE(other_path);
      const FrameHashes other = hash(LoadTestRig(name, isa));
      CHECK(other.weights == h.weights);
      CHECK(other.positions == h.positions);
      CHECK(other.positions_f32 == h.positions_f32);
      ++paths_run;
    }
  }
  MESSAGE("default path " << std::string(IsaName(BestIsa())) << "; " << paths_run << " other path runs compared");
  if (bless) {
    std::ofstream(GoldenPath()) << blessed.str();
    MESSAGE("wrote " << GoldenPath());
  }
}
