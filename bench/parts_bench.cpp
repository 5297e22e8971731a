// SPDX-License-Identifier: MIT
// A layered character's frame cost: its parts glued in one solve (one rig,
// joint vertices shared) against the same parts baked as rigs of their own
// and solved one after the other, as a game without glue would. The
// character is tests/runtime/rigs/make_arm.py's body and arm (an arm turning
// 120 degrees about the shoulder of a leaning body), generated here at two
// densities: the test rig's grids (39 vertices) and grids ten times finer
// each way (2,541 vertices). The counter `joint_gap` is the largest
// distance between the two parts' copies of the shoulder over the frames
// timed, in rig units (0 when glued: the joint is one vertex). Pell, the
// drawn layered sample, is timed the same way (its six joints).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>

#include "posemorph/bake/bake.h"
#include "posemorph/bake/join_parts.h"
#include "posemorph/bake/rig_description.h"
#include "posemorph/jobs.h"
#include "bench_rigs.h"

using namespace posemorph;

namespace {

using Triangles = std::vector<std::array<std::uint32_t, 3>>;

void Grid(int nx, int ny, double x0, double x1, double y0, double y1, std::vector<Eigen::Vector2d>* v, Triangles* t) {
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) v->emplace_back(x0 + (x1 - x0) * i / nx, y0 + (y1 - y0) * j / ny);
  const auto at = [&](int i, int j) { return std::uint32_t(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      t->push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      t->push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
}

Eigen::Vector2d Rotate(const Eigen::Vector2d& p, const Eigen::Vector2d& about, double degrees) {
  return about + Eigen::Rotation2Dd(degrees * M_PI / 180) * (p - about);
}

// `fine` quads per test-rig quad along each side.
bake::RigDescription ArmCharacter(int fine) {
  bake::RigDescription rig;
  rig.file = "parts_bench";
  rig.parameters.compact = false;
  rig.parameters.grid_resolution = 16;
  rig.parameters.pixels_per_unit = 4;
  std::vector<Eigen::Vector2d> body, arm;
  bake::PartDescription b, a;
  b.name = "body", a.name = "arm", a.order = 1;
  Grid(4 * fine, 4 * fine, -20, 20, -60, 0, &body, &b.triangles);
  Grid(4 * fine, 2 * fine, 0, 40, -5, 5, &arm, &a.triangles);
  const Eigen::Vector2d base(0, -60), shoulder(20, 0);
  const std::size_t arm_joint = std::size_t(fine) * std::size_t(4 * fine + 1);  // (0, 0): row `fine`, column 0
  bake::GlueDescription glue;
  glue.part = "arm", glue.to = "body", glue.part_index = 1, glue.to_index = 0;
  const struct {
    const char* name;
    double x, arm_angle, lean;
  } poses[] = {{"rest", 0, -90, 0}, {"mid", 1, -30, 5}, {"up", 2, 30, 10}};
  for (const auto& p : poses) {
    bake::PoseDescription pose;
    pose.name = p.name, pose.point = {p.x, 0};
    rig.poses.push_back(pose);
    const Eigen::Vector2d joint = Rotate(shoulder, base, p.lean);
    bake::PoseDescription bp = pose, ap = pose;
    for (const Eigen::Vector2d& v : body) bp.vertices.push_back(Rotate(v, base, p.lean));
    for (const Eigen::Vector2d& v : arm) ap.vertices.push_back(joint + Rotate(v, {0, 0}, p.arm_angle));
    ap.vertices[arm_joint] = joint;
    b.poses.push_back(bp), a.poses.push_back(ap);
    glue.at.push_back(joint);
  }
  rig.parts = {b, a};
  rig.glue = {glue};
  return rig;
}

// The pose-space point at phase t (radians): the arm's line from rest (0)
// through mid to up (2), or a loop through Pell's four poses.
Eigen::Vector2d PointAt(int density, double t) {
  if (density < 2) return {1 + std::sin(t), 0};
  return {std::sin(t), 0.5 * (1 - std::cos(t))};
}

struct Loaded {
  std::vector<unsigned char> bytes;
  Rig rig;
  explicit Loaded(bake::RigDescription desc) : bytes(bake::BakeRig(desc)) {
    LoadRig(bytes.data(), bytes.size(), &rig, nullptr);
  }
};

// The character glued, or its parts as rigs of their own; for each joint,
// its two copies (rig, vertex) when the parts are apart.
struct Character {
  std::vector<Loaded*> rigs;
  struct Joint {
    std::size_t rig[2];
    std::uint32_t vertex[2];
  };
  std::vector<Joint> joints;  // apart only
  bool missing = false;       // Pell's drawings were not built (no rsvg-convert)
};

// Density 0 and 1: the arm; 2: Pell, the drawn layered sample (seven parts).
bake::RigDescription Description(int density, bool* missing) {
  if (density < 2) return ArmCharacter(density == 0 ? 1 : 10);
  const std::string path = std::string(POSEMORPH_DRAWN_SAMPLES) + "/pell/pell.json";
  *missing = !std::ifstream(path).good();
  if (*missing) return {};
  bake::RigDescription d = bake::ReadRigDescription(path);
  d.parameters.compact = false;
  return d;
}

const Character& Get(int density, bool glued) {
  static std::map<std::pair<int, bool>, Character> made;
  auto [it, inserted] = made.try_emplace({density, glued});
  if (!inserted) return it->second;
  const bake::RigDescription desc = Description(density, &it->second.missing);
  if (it->second.missing) return it->second;
  std::vector<bake::RigDescription> parts;
  if (glued)
    parts.push_back(desc);
  else
    for (std::size_t p = 0; p < desc.parts.size(); ++p) parts.push_back(bake::PartRigDescription(desc, p));
  for (bake::RigDescription& d : parts)
    it->second.rigs.push_back(new Loaded(d));  // kept for the process's life, like the other benchmarks' fixtures
  if (glued) return it->second;
  for (const bake::GlueDescription& glue : desc.glue) {
    // The joint in rig coordinates (a drawing's y points down).
    const bool drawn = desc.parts[glue.part_index].poses[0].drawn;
    const Eigen::Vector2d at(glue.at[0].x(), drawn ? -glue.at[0].y() : glue.at[0].y());
    Character::Joint joint{};
    for (int side = 0; side < 2; ++side) {
      const std::size_t r = side == 0 ? glue.part_index : glue.to_index;
      const Rig& rig = it->second.rigs[r]->rig;
      const Span<const double> rest = rig.pose_positions(0);
      const auto distance = [&](std::uint32_t v) { return std::hypot(rest[2 * v] - at.x(), rest[2 * v + 1] - at.y()); };
      std::uint32_t best = 0;
      for (std::uint32_t v = 1; v < rig.vertex_count(); ++v)
        if (distance(v) < distance(best)) best = v;
      joint.rig[side] = r, joint.vertex[side] = best;
    }
    it->second.joints.push_back(joint);
  }
  return it->second;
}

void Label(benchmark::State& state, const Character& c) {
  std::uint32_t vertices = 0, triangles = 0;
  for (const Loaded* l : c.rigs) vertices += l->rig.vertex_count(), triangles += l->rig.triangle_count();
  const char* names[] = {"arm", "arm, finer", "Pell"};
  state.SetLabel(std::string(names[state.range(0)]) + ": " + std::to_string(vertices) + " vertices, " +
                 std::to_string(triangles) + " triangles, " +
                 (c.rigs.size() == 1 ? "glued, one solve" : std::to_string(c.rigs.size()) + " rigs solved apart"));
}

// One frame: every rig of the character at the same pose-space point.
void BM_PartsFrame(benchmark::State& state) {
  const Character& c = Get(int(state.range(0)), state.range(1) == 0);
  if (c.missing) return state.SkipWithError("Pell's drawings were not built (rsvg-convert)");
  std::vector<std::vector<double>> raw, limited, work, x;
  std::vector<std::vector<float>> xf;
  for (const Loaded* l : c.rigs) {
    raw.emplace_back(l->rig.pose_count()), limited.emplace_back(l->rig.pose_count());
    work.emplace_back(l->rig.morph_workspace_size()), x.emplace_back(2 * l->rig.vertex_count());
    xf.emplace_back(2 * l->rig.vertex_count());
  }
  double t = 0, gap = 0;
  for (auto _ : state) {
    const Eigen::Vector2d p = PointAt(int(state.range(0)), t);
    t += 1.0 / 60;
    for (std::size_t r = 0; r < c.rigs.size(); ++r) {
      WeightsJob wj;
      wj.rig = &c.rigs[r]->rig, wj.x = p.x(), wj.y = p.y();
      wj.raw = MakeSpan(raw[r]), wj.limited = MakeSpan(limited[r]);
      wj.Run();
      MorphJob mj;
      mj.rig = &c.rigs[r]->rig, mj.weights = MakeSpan(raw[r]), mj.limited_weights = MakeSpan(limited[r]);
      mj.workspace = MakeSpan(work[r]), mj.positions = MakeSpan(x[r]), mj.positions_f32 = MakeSpan(xf[r]);
      mj.Run();
    }
    benchmark::DoNotOptimize(xf.data());
    for (const Character::Joint& j : c.joints) {
      const double* a = &x[j.rig[0]][2 * std::size_t(j.vertex[0])];
      const double* b = &x[j.rig[1]][2 * std::size_t(j.vertex[1])];
      gap = std::max(gap, std::hypot(a[0] - b[0], a[1] - b[1]));
    }
  }
  state.counters["joint_gap"] = gap;
  Label(state, c);
}

// A crowd of 1000 characters on one thread, each at its own point.
void BM_PartsCrowd1000(benchmark::State& state) {
  const Character& c = Get(int(state.range(0)), state.range(1) == 0);
  if (c.missing) return state.SkipWithError("Pell's drawings were not built (rsvg-convert)");
  const std::size_t count = 1000;
  std::vector<std::vector<double>> w, ws, work;
  std::vector<std::vector<float>> xf;
  for (const Loaded* l : c.rigs) {
    const std::size_t N = l->rig.pose_count();
    w.emplace_back(count * N), ws.emplace_back(count * N), work.emplace_back(l->rig.batch_workspace_size());
    xf.emplace_back(count * 2 * std::size_t(l->rig.vertex_count()));
    for (std::size_t k = 0; k < count; ++k) {
      WeightsJob wj;
      const Eigen::Vector2d p = PointAt(int(state.range(0)), 2 * M_PI * double(k) / double(count));
      wj.rig = &l->rig, wj.x = p.x(), wj.y = p.y();
      wj.raw = {w.back().data() + k * N, N}, wj.limited = {ws.back().data() + k * N, N};
      wj.Run();
    }
  }
  for (auto _ : state) {
    for (std::size_t r = 0; r < c.rigs.size(); ++r) {
      MorphBatchJob job;
      job.rig = &c.rigs[r]->rig, job.count = count;
      job.weights = MakeSpan(w[r]), job.limited_weights = MakeSpan(ws[r]);
      job.workspace = MakeSpan(work[r]), job.positions_f32 = MakeSpan(xf[r]);
      job.Run();
    }
    benchmark::DoNotOptimize(xf.data());
  }
  Label(state, c);
}

// Pell with a face channel (assets/pell/pell-face.json, exact): the body's
// four parts glued in one solve, the eyes and the mouth attachments solved
// on their own, turned and moved onto their joints (AttachJob).
const Loaded* PellFace() {
  static const Loaded* loaded = [] {
    const std::string path = std::string(POSEMORPH_DRAWN_SAMPLES) + "/pell/pell-face.json";
    if (!std::ifstream(path).good()) return static_cast<const Loaded*>(nullptr);
    bake::RigDescription d = bake::ReadRigDescription(path);
    d.parameters.compact = false;
    return static_cast<const Loaded*>(new Loaded(d));
  }();
  return loaded;
}

// The largest distance between an attachment's joint and its parent's in one frame.
double JointGap(const Rig& rig, const double* body, const double* attached) {
  double gap = 0;
  std::size_t at = 0;
  for (std::uint32_t a = 0; a < rig.attachment_count(); ++a) {
    const AttachmentView v = rig.attachment(a);
    const std::uint32_t* pt = rig.triangles().data + 3 * std::size_t(v.parent_triangle);
    const std::uint32_t* jt = v.rig->triangles().data + 3 * std::size_t(v.joint_triangle);
    double p[2] = {0, 0}, j[2] = {0, 0};
    for (int c = 0; c < 2; ++c)
      for (int k = 0; k < 3; ++k)
        p[c] += v.parent_weights[k] * body[2 * pt[k] + c], j[c] += v.joint_weights[k] * attached[at + 2 * jt[k] + c];
    gap = std::max(gap, std::hypot(p[0] - j[0], p[1] - j[1]));
    at += 2 * std::size_t(v.rig->vertex_count());
  }
  return gap;
}

// One frame of Pell with a face: the body's point on a loop through its
// poses, the face's on a loop through its expressions at another speed.
void BM_ChannelsFrame(benchmark::State& state) {
  const Loaded* l = PellFace();
  if (!l) return state.SkipWithError("Pell's drawings were not built (rsvg-convert)");
  const Rig& rig = l->rig;
  const Rig& face = *rig.channel_rig(1);
  const std::size_t N = rig.pose_count(), NF = face.pose_count();
  std::vector<double> raw(N), limited(N), fraw(NF), flimited(NF), body(2 * std::size_t(rig.vertex_count()));
  std::vector<double> work(std::max(rig.morph_workspace_size(), rig.attach_workspace_size()));
  std::vector<double> attached(2 * std::size_t(rig.attached_vertex_count()));
  std::vector<float> body_f32(body.size()), attached_f32(attached.size());
  double t = 0, gap = 0;
  for (auto _ : state) {
    const Eigen::Vector2d p = PointAt(2, t), q = PointAt(2, 1.7 * t);
    t += 1.0 / 60;
    WeightsJob wj;
    wj.rig = &rig, wj.x = p.x(), wj.y = p.y();
    wj.raw = MakeSpan(raw), wj.limited = MakeSpan(limited);
    wj.Run();
    WeightsJob fj;
    fj.rig = &face, fj.x = q.x(), fj.y = q.y();
    fj.raw = MakeSpan(fraw), fj.limited = MakeSpan(flimited);
    fj.Run();
    MorphJob mj;
    mj.rig = &rig, mj.weights = MakeSpan(raw), mj.limited_weights = MakeSpan(limited);
    mj.workspace = MakeSpan(work), mj.positions = MakeSpan(body), mj.positions_f32 = MakeSpan(body_f32);
    mj.Run();
    AttachJob aj;
    aj.rig = &rig, aj.body_positions = MakeSpan(body);
    aj.weights = MakeSpan(fraw), aj.limited_weights = MakeSpan(flimited);
    aj.workspace = MakeSpan(work), aj.positions = MakeSpan(attached), aj.positions_f32 = MakeSpan(attached_f32);
    aj.Run();
    benchmark::DoNotOptimize(attached_f32.data());
    gap = std::max(gap, JointGap(rig, body.data(), attached.data()));
  }
  state.counters["joint_gap"] = gap;
  state.SetLabel("Pell with a face channel: " + std::to_string(rig.vertex_count() + rig.attached_vertex_count()) +
                 " vertices, body glued + " + std::to_string(rig.attachment_count()) + " attachments");
}

// A crowd of 1000 Pells with faces, each at its own two points: the bodies
// as one MorphBatchJob, the attachments as one AttachJob.
void BM_ChannelsCrowd1000(benchmark::State& state) {
  const Loaded* l = PellFace();
  if (!l) return state.SkipWithError("Pell's drawings were not built (rsvg-convert)");
  const Rig& rig = l->rig;
  const Rig& face = *rig.channel_rig(1);
  const std::size_t count = 1000, N = rig.pose_count(), NF = face.pose_count();
  std::vector<double> w(count * N), ws(count * N), fw(count * NF), fws(count * NF);
  for (std::size_t k = 0; k < count; ++k) {
    const Eigen::Vector2d p = PointAt(2, 2 * M_PI * double(k) / double(count)), q = PointAt(2, 3.7 * double(k));
    WeightsJob wj;
    wj.rig = &rig, wj.x = p.x(), wj.y = p.y();
    wj.raw = {w.data() + k * N, N}, wj.limited = {ws.data() + k * N, N};
    wj.Run();
    WeightsJob fj;
    fj.rig = &face, fj.x = q.x(), fj.y = q.y();
    fj.raw = {fw.data() + k * NF, NF}, fj.limited = {fws.data() + k * NF, NF};
    fj.Run();
  }
  std::vector<double> work(std::max(rig.batch_workspace_size(), rig.attach_workspace_size()));
  std::vector<double> body(count * 2 * std::size_t(rig.vertex_count()));
  std::vector<double> attached(count * 2 * std::size_t(rig.attached_vertex_count()));
  std::vector<float> body_f32(body.size()), attached_f32(attached.size());
  for (auto _ : state) {
    MorphBatchJob job;
    job.rig = &rig, job.count = count;
    job.weights = MakeSpan(w), job.limited_weights = MakeSpan(ws);
    job.workspace = MakeSpan(work), job.positions = MakeSpan(body), job.positions_f32 = MakeSpan(body_f32);
    job.Run();
    AttachJob aj;
    aj.rig = &rig, aj.count = count, aj.body_positions = MakeSpan(body);
    aj.weights = MakeSpan(fw), aj.limited_weights = MakeSpan(fws);
    aj.workspace = MakeSpan(work), aj.positions = MakeSpan(attached), aj.positions_f32 = MakeSpan(attached_f32);
    aj.Run();
    benchmark::DoNotOptimize(attached_f32.data());
  }
  state.SetLabel("Pell with a face channel, 1000 characters");
}

}  // namespace

const Rig* PellFaceRig() {
  const Loaded* l = PellFace();
  return l ? &l->rig : nullptr;
}

BENCHMARK(BM_ChannelsFrame)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ChannelsCrowd1000)->Unit(benchmark::kMillisecond);

// Arguments: the character (0: the arm at the test rig's grids, 1: ten
// times finer, 2: Pell), then 0 glued or 1 apart.
BENCHMARK(BM_PartsFrame)->ArgsProduct({{0, 1, 2}, {0, 1}})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PartsCrowd1000)->ArgsProduct({{0, 1, 2}, {0, 1}})->Unit(benchmark::kMillisecond);
