// SPDX-License-Identifier: MIT
// Draw lists from an animator's weights (DrawListJob::weights): the same
// lists and bits as the points that give those weights, the same bits as the
// morph and attach jobs on a mix's weights, and each refusal.
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>

#include "animator_support.h"
#include "posemorph/draw_list.h"
#include "posemorph/path.h"

using namespace posemorph;
using namespace posemorph::test;

namespace {

// Draw-list buffers for `count` characters of `rig`, with its attachments.
struct Frame {
  std::vector<double> block;
  DrawListJob job;
  Frame(const Rig& rig, std::size_t count) {
    const CharacterBuffers sizes = CharacterBuffers::For(rig, count);
    block.resize((sizes.bytes + sizeof(double) - 1) / sizeof(double));
    REQUIRE(sizes.Bind(rig, block.data(), block.size() * sizeof(double), &job));
  }
  // Every float the frame wrote: the body's and the attachments' positions.
  std::vector<float> Floats() const {
    std::vector<float> f(job.positions.data, job.positions.data + job.positions.size);
    f.insert(f.end(), job.attached_positions.data, job.attached_positions.data + job.attached_positions.size);
    return f;
  }
};

void FromWeights(DrawListJob& job, const Crowd& crowd) {
  job.weights = MakeSpan(crowd.raw);
  job.limited_weights = MakeSpan(crowd.limited);
  job.texture_weights = MakeSpan(crowd.texture);
  job.attached_weights = MakeSpan(crowd.attached_raw);
  job.attached_limited_weights = MakeSpan(crowd.attached_limited);
  job.attached_texture_weights = MakeSpan(crowd.attached_texture);
}

bool SameList(const DrawList& a, const DrawList& b) {
  if (a.positions.size != b.positions.size || a.drawing_count != b.drawing_count || a.parts.data != b.parts.data)
    return false;
  if (std::memcmp(a.positions.data, b.positions.data, a.positions.size * sizeof(float)) != 0) return false;
  for (std::uint32_t d = 0; d < a.drawing_count; ++d)
    if (a.drawings[d].pose != b.drawings[d].pose || a.drawings[d].weight != b.drawings[d].weight ||
        a.drawings[d].uvs != b.drawings[d].uvs)
      return false;
  return true;
}

}  // namespace

TEST_CASE("draw lists from an animator's weights: the lists its points give, bit for bit") {
  const Rig rig = LoadTestRig("pell-face.compact");
  const Rig& face = *rig.channel_rig(1);
  const std::size_t count = 5, A = rig.attachment_count();
  REQUIRE(A > 0);
  // Each character follows a point on each channel (cut: no mix), so its
  // weights are WeightsJob's at those points.
  Crowd crowd(rig, count, 16);
  std::vector<double> points, face_points;
  for (std::size_t k = 0; k < count; ++k) {
    double bx, by, fx, fy;
    REQUIRE(SamplePath(rig, 0, 0.45 * double(k), &bx, &by));
    REQUIRE(SamplePath(face, 0, 0.3 * double(k), &fx, &fy));
    points.push_back(bx), points.push_back(by), face_points.push_back(fx), face_points.push_back(fy);
    REQUIRE(AnimatorSetPoint(rig, crowd.Tracks(k), 0, bx, by, 0));
    REQUIRE(AnimatorSetPoint(rig, crowd.Tracks(k), 1, fx, fy, 0));
  }
  REQUIRE(crowd.Job(1.0 / 60).Run());
  Frame by_points(rig, count), by_weights(rig, count);
  by_points.job.points = MakeSpan(points);
  by_points.job.channel_points = MakeSpan(face_points);
  REQUIRE(by_points.job.Run());
  FromWeights(by_weights.job, crowd);
  REQUIRE(by_weights.job.Validate());
  REQUIRE(by_weights.job.Run());
  CHECK(by_weights.Floats() == by_points.Floats());
  for (std::size_t k = 0; k < count; ++k) {
    CAPTURE(k);
    CHECK(SameList(by_weights.job.output[k], by_points.job.output[k]));
    for (std::size_t a = 0; a < A; ++a)
      CHECK(SameList(by_weights.job.attached_output[k * A + a], by_points.job.attached_output[k * A + a]));
  }
}

TEST_CASE("draw lists from an animator's weights: mid-mix, the morph and attach jobs' bits") {
  const Rig rig = LoadTestRig("pell-face.compact");
  const std::size_t count = 3, A = rig.attachment_count();
  const std::size_t v2 = 2 * std::size_t(rig.vertex_count()), a2 = 2 * std::size_t(rig.attached_vertex_count());
  Crowd crowd(rig, count, 64);
  for (std::size_t k = 0; k < count; ++k) {
    REQUIRE(AnimatorPlay(rig, crowd.Tracks(k), 0, 0, PlayOptions{1, 1, 0, 0.2 * double(k)}));
    REQUIRE(AnimatorPlay(rig, crowd.Tracks(k), 1, 0, PlayOptions{1, 1, 0, 0.1 * double(k)}));
  }
  REQUIRE(crowd.Job(0.4).Run());
  for (std::size_t k = 0; k < count; ++k) REQUIRE(AnimatorStop(rig, crowd.Tracks(k), 0, 0.5));
  REQUIRE(crowd.Job(0.2).Run());  // halfway through the hand-over to the rest pose
  REQUIRE(crowd.tracks[0].mixing);
  Frame frame(rig, count);
  FromWeights(frame.job, crowd);
  frame.job.sigma = 0.3;  // not read: the given texture weights pick the drawings
  REQUIRE(frame.job.Run());

  std::vector<double> work(rig.batch_workspace_size() + rig.attach_workspace_size()), body(count * v2),
      attached(count * a2);
  std::vector<float> body_f32(count * v2), attached_f32(count * a2);
  MorphBatchJob mb;
  mb.rig = &rig, mb.count = count, mb.weights = MakeSpan(crowd.raw), mb.limited_weights = MakeSpan(crowd.limited);
  mb.workspace = MakeSpan(work), mb.positions = MakeSpan(body), mb.positions_f32 = MakeSpan(body_f32);
  REQUIRE(mb.Run());
  AttachJob aj;
  aj.rig = &rig, aj.count = count, aj.body_positions = MakeSpan(body);
  aj.weights = MakeSpan(crowd.attached_raw), aj.limited_weights = MakeSpan(crowd.attached_limited);
  aj.workspace = MakeSpan(work), aj.positions = MakeSpan(attached), aj.positions_f32 = MakeSpan(attached_f32);
  REQUIRE(aj.Run());
  CHECK(std::memcmp(frame.job.positions.data, body_f32.data(), body_f32.size() * sizeof(float)) == 0);
  CHECK(std::memcmp(frame.job.attached_positions.data, attached_f32.data(), attached_f32.size() * sizeof(float)) == 0);
  const std::size_t n = rig.pose_count();
  for (std::size_t k = 0; k < count; ++k) {
    BlendedDrawing want[kMaxBlendDrawings];
    const std::uint32_t d = PickDrawings({crowd.texture.data() + k * n, n}, kMaxBlendDrawings, {want, 8});
    REQUIRE(frame.job.output[k].drawing_count == d);
    for (std::uint32_t i = 0; i < d; ++i) CHECK(frame.job.output[k].drawings[i].weight == want[i].weight);
    CHECK(frame.job.attached_output[k * A].drawing_count > 0);
  }
}

TEST_CASE("DrawListJob with weights refuses each listed failure case") {
  const Rig rig = LoadTestRig("pell-face.compact");
  const std::size_t count = 2;
  Crowd crowd(rig, count, 4);
  REQUIRE(crowd.Job(0.1).Run());
  std::vector<double> points(2 * count, 0.0), channel_points(2 * count, 0.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    const char* what;
    std::function<void(DrawListJob&)> spoil;
  } cases[] = {
      {"points and weights", [&](DrawListJob& j) { j.points = MakeSpan(points); }},
      {"short weights", [](DrawListJob& j) { j.weights.size -= 1; }},
      {"no limited weights", [](DrawListJob& j) { j.limited_weights = {}; }},
      {"no texture weights", [](DrawListJob& j) { j.texture_weights = {}; }},
      {"limited weights without weights",
       [](DrawListJob& j) {
         j.weights = {}, j.texture_weights = {}, j.attached_weights = {}, j.attached_limited_weights = {},
         j.attached_texture_weights = {};
       }},
      {"a NaN weight", [&](DrawListJob& j) { const_cast<double*>(j.weights.data)[1] = nan; }},
      {"a limited weight above kMaxJobWeight",
       [&](DrawListJob& j) { const_cast<double*>(j.limited_weights.data)[0] = 2 * kMaxJobWeight; }},
      {"channel points with weights", [&](DrawListJob& j) { j.channel_points = MakeSpan(channel_points); }},
      {"short attached weights", [](DrawListJob& j) { j.attached_weights.size -= 1; }},
      {"no attached texture weights", [](DrawListJob& j) { j.attached_texture_weights = {}; }},
      {"an infinite attached weight",
       [&](DrawListJob& j) { const_cast<double*>(j.attached_limited_weights.data)[2] = HUGE_VAL; }},
      {"attached weights without attached lists",
       [](DrawListJob& j) { j.attached_output = {}, j.attached_positions = {}; }},
  };
  for (const Case& c : cases) {
    CAPTURE(c.what);
    Crowd copy = crowd;
    Frame frame(rig, count);
    FromWeights(frame.job, copy);
    REQUIRE(frame.job.Validate());
    c.spoil(frame.job);
    CHECK(!frame.job.Validate());
    const std::vector<float> before = frame.Floats();
    CHECK(!frame.job.Run());
    CHECK(frame.Floats() == before);
  }
  // The body alone from weights (no attachment spans at all) runs.
  Frame body(rig, count);
  body.job.weights = MakeSpan(crowd.raw), body.job.limited_weights = MakeSpan(crowd.limited);
  body.job.texture_weights = MakeSpan(crowd.texture);
  body.job.attached_output = {}, body.job.attached_positions = {};
  CHECK(body.job.Run());
}
