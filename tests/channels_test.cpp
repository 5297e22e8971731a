// SPDX-License-Identifier: MIT
// Control channels (format 1.7): a part driven by its own pose space hangs
// from its joint on the body. The joint holds in every frame, moving one
// channel changes no bit of another's vertices, single, batched and threaded
// evaluation agree bit for bit, bad descriptions are refused naming the
// channel, the part and the pose, and damaged CHAN bytes never crash the
// loader.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "posemorph/bake/bake.h"
#include "posemorph/bake/bake_channels.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/reproduction_check.h"
#include "posemorph/bake/rig_description.h"
#include "posemorph/jobs.h"
#include "posemorph/path.h"
#include "posemorph/rig.h"
#include "posemorph/rig_format.h"

using namespace posemorph;
using nlohmann::json;

namespace {

// tests/runtime/rigs/arm.json with its arm driven by a channel of its own:
// "body" leans the body (rest, mid, up: 0, 5 and 10 degrees), "arm" turns
// the arm 120 degrees about the shoulder.
json ArmChannels() {
  std::ifstream in(std::string(POSEMORPH_SOURCE_DIR) + "/tests/runtime/rigs/arm.json");
  REQUIRE(in.good());
  json d = json::parse(in);
  const json poses = d["poses"], paths = d["paths"];
  d.erase("poses");
  d.erase("paths");
  d["channels"] = json::array(
      {{{"name", "body"}, {"poses", poses}, {"paths", paths}},
       {{"name", "arm"},
        {"poses", poses},
        {"paths", json::array({{{"name", "swing"}, {"loop", true}, {"keys", {{0, 0, 0}, {1, 2, 0}, {2, 0, 0}}}}})}}});
  d["parts"][1]["channel"] = "arm";
  return d;
}

std::vector<unsigned char> BakeBytes(const json& description, bool exact = true, bake::BakeReport* report = nullptr,
                                     const std::string& file = "arm.json", const std::string& dir = ".") {
  json d = description;
  d["bake"]["precision"] = exact ? "exact" : "compact";
  const bake::RigDescription rig = bake::ParseRigDescription(d.dump(), file, dir);
  return bake::BakeRig(rig, report);
}

Rig Load(const std::vector<unsigned char>& bytes) {
  Rig out;
  Error err;
  REQUIRE_MESSAGE(LoadRig(bytes.data(), bytes.size(), &out, &err), err.message);
  return out;
}

std::string BakeError(const json& description) {
  try {
    bake::BakeRig(bake::ParseRigDescription(description.dump(), "arm.json", "."));
  } catch (const bake::BakeError& e) {
    return e.what();
  }
  return "(no error)";
}

// One character's frame: the body (channel 0) and the attachments.
struct Frame {
  std::vector<double> body, attached;
};

// Weights of `rig` at (x, y) into raw and limited.
void WeightsAt(const Rig& rig, double x, double y, double* raw, double* limited) {
  WeightsJob job;
  job.rig = &rig;
  job.x = x, job.y = y;
  job.raw = {raw, rig.pose_count()};
  job.limited = {limited, rig.pose_count()};
  REQUIRE(job.Run());
}

// points: one (x, y) per channel.
Frame Evaluate(const Rig& rig, const std::vector<std::array<double, 2>>& points) {
  const std::size_t N = rig.pose_count(), NW = rig.attached_weight_count();
  std::vector<double> raw(N), limited(N), work(rig.morph_workspace_size());
  Frame f;
  f.body.resize(2 * std::size_t(rig.vertex_count()));
  WeightsAt(rig, points[0][0], points[0][1], raw.data(), limited.data());
  MorphJob morph;
  morph.rig = &rig;
  morph.weights = {raw.data(), N}, morph.limited_weights = {limited.data(), N};
  morph.workspace = {work.data(), work.size()}, morph.positions = {f.body.data(), f.body.size()};
  REQUIRE(morph.Run());
  std::vector<double> w(NW), wl(NW), attach_work(rig.attach_workspace_size());
  for (std::uint32_t c = 1; c < rig.channel_count(); ++c)
    WeightsAt(*rig.channel_rig(c), points[c][0], points[c][1], w.data() + rig.channel_weight_offset(c),
              wl.data() + rig.channel_weight_offset(c));
  f.attached.resize(2 * std::size_t(rig.attached_vertex_count()));
  AttachJob attach;
  attach.rig = &rig;
  attach.body_positions = {f.body.data(), f.body.size()};
  attach.weights = {w.data(), NW}, attach.limited_weights = {wl.data(), NW};
  attach.workspace = {attach_work.data(), attach_work.size()};
  attach.positions = {f.attached.data(), f.attached.size()};
  REQUIRE(attach.Validate());
  REQUIRE(attach.Run());
  return f;
}

// The barycentric point w of triangle t in positions p.
std::array<double, 2> At(const double* p, const std::uint32_t* t, const double* w) {
  return {(w[0] * p[2 * t[0]] + w[1] * p[2 * t[1]]) + w[2] * p[2 * t[2]],
          (w[0] * p[2 * t[0] + 1] + w[1] * p[2 * t[1] + 1]) + w[2] * p[2 * t[2] + 1]};
}

// The largest distance between an attachment's joint and its parent's, in
// one frame.
double JointResidual(const Rig& rig, const Frame& f) {
  double worst = 0;
  std::size_t at = 0;
  for (std::uint32_t a = 0; a < rig.attachment_count(); ++a) {
    const AttachmentView v = rig.attachment(a);
    const auto parent = At(f.body.data(), rig.triangles().data + 3 * std::size_t(v.parent_triangle), v.parent_weights);
    const auto joint =
        At(f.attached.data() + at, v.rig->triangles().data + 3 * std::size_t(v.joint_triangle), v.joint_weights);
    worst = std::max(worst, std::hypot(parent[0] - joint[0], parent[1] - joint[1]));
    at += 2 * std::size_t(v.rig->vertex_count());
  }
  return worst;
}

double Angle(const double* p, std::uint32_t a, std::uint32_t b) {
  return std::atan2(p[2 * b + 1] - p[2 * a + 1], p[2 * b] - p[2 * a]);
}

}  // namespace

TEST_CASE("channels: the arm's channel turns it 120 degrees about the shoulder, the body's leans it, the joint holds") {
  bake::BakeReport report;
  const Rig rig = Load(BakeBytes(ArmChannels(), true, &report));
  REQUIRE(rig.channel_count() == 2);
  REQUIRE(rig.attachment_count() == 1);
  CHECK(std::string(rig.channel_name(0).data, rig.channel_name(0).size) == "body");
  CHECK(rig.FindChannel("arm") == 1);
  CHECK(rig.FindChannel("face") == -1);
  const AttachmentView arm = rig.attachment(0);
  REQUIRE(arm.rig);
  CHECK(arm.channel == 1);
  CHECK(rig.channel_rig(1) == arm.rig);
  CHECK(rig.channel_rig(2) == nullptr);
  CHECK(rig.vertex_count() == 25);  // the body alone
  CHECK(arm.rig->vertex_count() == 15);
  CHECK(rig.attached_vertex_count() == 15);
  CHECK(rig.attached_weight_count() == 3);
  CHECK(std::string(arm.rig->part(0).name.data, arm.rig->part(0).name.size) == "arm");
  REQUIRE(report.attachments.size() == 1);
  CHECK(report.attachments[0].part == "arm");
  CHECK(report.attachments[0].parent == "body");
  MESSAGE("placed within " << report.attachments[0].placed_error << " units");
  CHECK(report.attachments[0].placed_error < 1e-9 * rig.bounding_box_diagonal());

  // Every pair of the channels' paths' samples: the joint stays on the body.
  double residual = 0;
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 20; ++j) {
      double bx, by, ax, ay;
      REQUIRE(SamplePath(rig.path(0), rig.path(0).end_time() * i / 20, &bx, &by));
      REQUIRE(SamplePath(arm.rig->path(0), arm.rig->path(0).end_time() * j / 20, &ax, &ay));
      residual = std::max(residual, JointResidual(rig, Evaluate(rig, {{{bx, by}}, {{ax, ay}}})));
    }
  MESSAGE("joint residual over 441 frames: " << residual << " units");
  CHECK(residual < 1e-9 * rig.bounding_box_diagonal());

  // The arm's own channel turns it about the shoulder: 120 degrees from rest
  // to up, with the body at rest. Its first edge (vertex 0 -> 1) turns so.
  const Frame rest = Evaluate(rig, {{{0, 0}}, {{0, 0}}}), up = Evaluate(rig, {{{0, 0}}, {{2, 0}}});
  const double pi = std::acos(-1.0);
  double turn = Angle(up.attached.data(), 0, 4) - Angle(rest.attached.data(), 0, 4);
  turn = std::remainder(turn, 2 * pi);
  CHECK(std::fabs(std::fabs(turn) - 2 * pi / 3) < 1e-6);
  // The body's channel turns the attached arm with the body: with the arm at
  // rest, the arm turns as the body's triangles turn (10 degrees at "up").
  const Frame lean = Evaluate(rig, {{{2, 0}}, {{0, 0}}});
  const double body_turn = std::remainder(Angle(lean.body.data(), 0, 4) - Angle(rest.body.data(), 0, 4), 2 * pi);
  const double arm_turn = std::remainder(Angle(lean.attached.data(), 0, 4) - Angle(rest.attached.data(), 0, 4), 2 * pi);
  MESSAGE("body turns " << body_turn * 180 / pi << " degrees, the attached arm " << arm_turn * 180 / pi);
  CHECK(std::fabs(body_turn) > 0.1);
  CHECK(std::fabs(arm_turn - body_turn) < 1e-6);
}

TEST_CASE("channels: moving one channel's point changes no bit of the other's vertices") {
  const Rig rig = Load(BakeBytes(ArmChannels(), false));
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(-0.5, 2.5);
  for (int k = 0; k < 50; ++k) {
    const std::array<double, 2> b{u(random), u(random)}, a1{u(random), u(random)}, a2{u(random), u(random)};
    const Frame f1 = Evaluate(rig, {b, a1}), f2 = Evaluate(rig, {b, a2});
    REQUIRE(std::memcmp(f1.body.data(), f2.body.data(), f1.body.size() * sizeof(double)) == 0);
    // The arm's point changes the arm (not always by much: only its joint is pinned).
    if (std::hypot(a1[0] - a2[0], a1[1] - a2[1]) > 0.5) CHECK(f1.attached != f2.attached);
  }
  // And the body's point moves the attached arm as a whole: never its shape's
  // bits relative to the joint in a pure translation, but its place.
  const Frame f1 = Evaluate(rig, {{{0, 0}}, {{1, 0}}}), f2 = Evaluate(rig, {{{2, 0}}, {{1, 0}}});
  CHECK(f1.attached != f2.attached);
}

TEST_CASE("channels: single, batched and threaded evaluation give the same bits") {
  const Rig rig = Load(BakeBytes(ArmChannels(), false));
  const std::size_t count = 19, V2 = 2 * std::size_t(rig.vertex_count()),
                    A2 = 2 * std::size_t(rig.attached_vertex_count());
  const std::size_t N = rig.pose_count(), NA = rig.channel_rig(1)->pose_count();
  std::mt19937 random(11);
  std::uniform_real_distribution<double> u(-0.5, 2.5);
  std::vector<std::array<double, 2>> body_points(count), arm_points(count);
  for (std::size_t k = 0; k < count; ++k)
    body_points[k] = {u(random), u(random)}, arm_points[k] = {u(random), u(random)};
  // One by one.
  std::vector<Frame> single;
  for (std::size_t k = 0; k < count; ++k) single.push_back(Evaluate(rig, {body_points[k], arm_points[k]}));
  // Batched: the bodies with MorphBatchJob, the attachments with one AttachJob
  // over a range of characters (channel-major weights, attachment-major positions).
  auto batch = [&](std::size_t first, std::size_t n, std::vector<double>* attached) {
    std::vector<double> raw(n * N), limited(n * N), body(n * V2), w(n * NA), wl(n * NA);
    for (std::size_t k = 0; k < n; ++k) {
      WeightsAt(rig, body_points[first + k][0], body_points[first + k][1], raw.data() + k * N, limited.data() + k * N);
      WeightsAt(*rig.channel_rig(1), arm_points[first + k][0], arm_points[first + k][1], w.data() + k * NA,
                wl.data() + k * NA);
    }
    std::vector<double> work(std::max(rig.batch_workspace_size(), rig.attach_workspace_size()));
    MorphBatchJob morph;
    morph.rig = &rig;
    morph.count = n;
    morph.weights = {raw.data(), raw.size()}, morph.limited_weights = {limited.data(), limited.size()};
    morph.workspace = {work.data(), work.size()}, morph.positions = {body.data(), body.size()};
    REQUIRE(morph.Run());
    attached->assign(n * A2, 0);
    std::vector<float> f32(n * A2);
    AttachJob attach;
    attach.rig = &rig;
    attach.count = n;
    attach.body_positions = {body.data(), body.size()};
    attach.weights = {w.data(), w.size()}, attach.limited_weights = {wl.data(), wl.size()};
    attach.workspace = {work.data(), work.size()};
    attach.positions = {attached->data(), attached->size()};
    attach.positions_f32 = {f32.data(), f32.size()};
    REQUIRE(attach.Run());
    for (std::size_t k = 0; k < n * A2; ++k) REQUIRE(f32[k] == float((*attached)[k]));
  };
  std::vector<double> all;
  batch(0, count, &all);
  for (std::size_t k = 0; k < count; ++k)
    REQUIRE(std::memcmp(all.data() + k * A2, single[k].attached.data(), A2 * sizeof(double)) == 0);
  // Three threads over disjoint ranges, each with its own buffers.
  std::vector<double> parts[3];
  const std::size_t first[4] = {0, 7, 12, count};
  std::vector<std::thread> threads;
  for (int t = 0; t < 3; ++t) threads.emplace_back([&, t] { batch(first[t], first[t + 1] - first[t], &parts[t]); });
  for (std::thread& t : threads) t.join();
  for (int t = 0; t < 3; ++t)
    for (std::size_t k = first[t]; k < first[t + 1]; ++k)
      REQUIRE(std::memcmp(parts[t].data() + (k - first[t]) * A2, single[k].attached.data(), A2 * sizeof(double)) == 0);
}

TEST_CASE("channels: AttachJob validates its inputs") {
  const Rig rig = Load(BakeBytes(ArmChannels(), false));
  const std::size_t V2 = 2 * std::size_t(rig.vertex_count()), A2 = 2 * std::size_t(rig.attached_vertex_count());
  std::vector<double> body(V2, 0.0), w(3, 1.0 / 3), work(rig.attach_workspace_size()), out(A2);
  for (std::size_t k = 0; k < V2; ++k) body[k] = rig.pose_positions(0)[k];
  AttachJob good;
  good.rig = &rig;
  good.body_positions = {body.data(), body.size()};
  good.weights = {w.data(), w.size()}, good.limited_weights = {w.data(), w.size()};
  good.workspace = {work.data(), work.size()};
  good.positions = {out.data(), out.size()};
  REQUIRE(good.Validate());
  REQUIRE(good.Run());
  for (double v : out) REQUIRE(std::isfinite(v));
  auto refused = [&](auto change) {
    AttachJob job = good;
    change(job);
    std::vector<double> before = out;
    const bool ran = job.Run();
    CHECK(out == before);  // nothing written
    return !job.Validate() && !ran;
  };
  CHECK(refused([](AttachJob& j) { j.rig = nullptr; }));
  CHECK(refused([&](AttachJob& j) { j.body_positions = {body.data(), V2 - 1}; }));
  CHECK(refused([&](AttachJob& j) { j.weights = {w.data(), 2}; }));
  CHECK(refused([&](AttachJob& j) { j.limited_weights = {nullptr, 3}; }));
  CHECK(refused([&](AttachJob& j) { j.workspace = {work.data(), work.size() - 1}; }));
  CHECK(refused([&](AttachJob& j) { j.positions = {out.data(), A2 - 1}; }));
  CHECK(refused([&](AttachJob& j) { j.interpolation = Interpolation(7); }));
  std::vector<double> bad = w;
  bad[1] = NAN;
  CHECK(refused([&](AttachJob& j) { j.weights = {bad.data(), bad.size()}; }));
  bad[1] = 2 * kMaxJobWeight;
  CHECK(refused([&](AttachJob& j) { j.limited_weights = {bad.data(), bad.size()}; }));
  std::vector<double> bad_body = body;
  bad_body[3] = INFINITY;
  CHECK(refused([&](AttachJob& j) { j.body_positions = {bad_body.data(), bad_body.size()}; }));
  // A rig with one channel (or none loaded) has nothing to attach.
  std::ifstream in(std::string(POSEMORPH_SOURCE_DIR) + "/tests/runtime/rigs/arm.json");
  const Rig one = Load(BakeBytes(json::parse(in)));
  CHECK(one.channel_count() == 1);
  CHECK(one.attachment_count() == 0);
  CHECK(one.channel_rig(0) == &one);
  CHECK(one.channel_name(0).size == 0);
  AttachJob none = good;
  none.rig = &one;
  CHECK(!none.Validate());
  Rig empty;
  none.rig = &empty;
  CHECK(!none.Validate());
  // count 0 does nothing, whatever the spans.
  AttachJob zero;
  zero.rig = &rig;
  zero.count = 0;
  CHECK(zero.Validate());
  CHECK(zero.Run());
}

TEST_CASE("channels: bad channels are refused naming the channel, the part and the problem") {
  const json good = ArmChannels();
  {
    json d = good;
    d["channels"][1]["poses"].erase(1);
    d["channels"][1]["poses"].erase(1);
    CHECK(BakeError(d) == "arm.json: channels[1].poses: channel 'arm' has 1 poses: a channel needs 2 to 64");
  }
  {
    json d = good;
    d["parts"][1]["channel"] = "leg";
    CHECK(BakeError(d) == "arm.json: parts[1].channel: no channel is named 'leg'");
  }
  {
    json d = good;
    d["channels"][1]["poses"].erase(2);
    CHECK(BakeError(d) ==
          "arm.json: parts[1].poses: part 'arm' has 3 poses, its channel 'arm' 2: every part is drawn in every pose "
          "(one that should vanish is drawn tiny, or hidden behind another by its order)");
  }
  {
    json d = good;
    d["channels"][1]["name"] = "body";
    CHECK(BakeError(d) == "arm.json: channels[1].name: channel 'body' is defined twice");
  }
  {
    json d = good;
    d["channels"] = json::array({d["channels"][0]});
    CHECK(BakeError(d) == "arm.json: channels: 1 channels: give 2 to 8 (the rig format's limit), or none");
  }
  {
    json d = good;
    for (int k = 2; k < 9; ++k) {
      json c = d["channels"][1];
      c["name"] = "c" + std::to_string(k);
      d["channels"].push_back(c);
    }
    CHECK(BakeError(d) == "arm.json: channels: 9 channels: give 2 to 8 (the rig format's limit), or none");
  }
  {
    json d = good;
    d["poses"] = d["channels"][0]["poses"];
    CHECK(BakeError(d) ==
          "arm.json: poses: with \"channels\", each channel lists its poses: move them into channels[0].poses");
  }
  {
    json d = good;
    d["glue"][0]["part"] = "body";
    d["glue"][0]["to"] = "arm";
    CHECK(BakeError(d) ==
          "arm.json: glue[0].to: part 'arm' is driven by channel 'arm': a part is glued to a part of the first "
          "channel ('body'), which carries the others");
  }
  {
    json d = good;
    d["glue"].push_back(d["glue"][0]);
    CHECK(BakeError(d) ==
          "arm.json: glue[1]: part 'arm' (channel 'arm') is glued twice: a part of another channel hangs from one "
          "joint");
  }
  {
    json d = good;
    d["glue"] = json::array();
    CHECK(BakeError(d) ==
          "arm.json: glue: part 'arm' (channel 'arm') is glued to nothing: glue it to a part of channel 'body'");
  }
  {
    json d = good;
    d["parts"][0]["channel"] = "arm";
    d["parts"][1]["channel"] = "arm";
    CHECK(BakeError(d) ==
          "arm.json: glue[0].to: part 'body' is driven by channel 'arm': a part is glued to a part "
          "of the first channel ('body'), which carries the others");
  }
  {
    json d = good;
    d["glue"][0]["at"] = json::array({{60, 0}, {60, 0}, {60, 0}});
    CHECK(BakeError(d) ==
          "arm.json: glue of part 'arm' to 'body': the joint (60, 0) lies off part 'body' in pose "
          "'rest' (index 0): a joint lies on both parts");
  }
  {
    json d = good;
    d["parts"][1]["poses"][1]["vertices"][3] = {15, -10};  // arm pose 'mid' turned over
    const std::string e = BakeError(d);
    CHECK(e.find("arm.json: part 'arm'") == 0);
    CHECK(e.find("part 'arm': part 'arm'") == std::string::npos);  // the part named once
  }
  {
    json d = good;
    d["channels"][1]["poses"][2]["name"] = d["channels"][1]["poses"][0]["name"];
    CHECK(BakeError(d) ==
          "arm.json: channels[1].poses[2].name: channel 'arm' names two poses 'rest' (poses 0 and 2): each pose of "
          "a channel has its own name");
  }
  {
    json d = good;
    json tail = d["channels"][1];
    tail["name"] = "tail";
    d["channels"].push_back(tail);
    CHECK(BakeError(d) ==
          "arm.json: channels[2]: channel 'tail' drives no part: give a part \"channel\": \"tail\", or remove the "
          "channel");
  }
}

TEST_CASE("channels: damaged CHAN bytes are refused with a message or load into a rig that evaluates finite") {
  const std::vector<unsigned char> bytes = BakeBytes(ArmChannels(), false);
  RigSection sections[format::kMaxSections];
  std::uint32_t count = 0;
  REQUIRE(ReadRigSections(bytes.data(), bytes.size(), sections, format::kMaxSections, &count));
  const RigSection* chan = nullptr;
  for (std::uint32_t k = 0; k < count; ++k)
    if (sections[k].tag == format::kChannels) chan = &sections[k];
  REQUIRE(chan);
  LoadOptions unchecked;
  unchecked.verify_checksum = false;
  // Every byte of the table and the names, and a spread of the nested rig's,
  // set to a few values: the loader refuses or loads a rig every job evaluates finite.
  std::size_t refused = 0, loaded = 0;
  const std::size_t table = format::kChannelsHeaderSize + format::kAttachmentEntrySize + 16;
  std::vector<std::size_t> where;
  for (std::size_t k = 0; k < table; ++k) where.push_back(k);
  for (std::size_t k = table; k < chan->size; k += 37) where.push_back(k);
  for (std::size_t k : where)
    for (unsigned char value : {0x00, 0x01, 0x7f, 0x80, 0xff}) {
      std::vector<unsigned char> damaged = bytes;
      if (damaged[chan->offset + k] == value) continue;
      damaged[chan->offset + k] = value;
      Rig rig;
      Error err;
      if (!LoadRig(damaged.data(), damaged.size(), &rig, &err, unchecked)) {
        REQUIRE(err.message[0] != 0);
        ++refused;
        continue;
      }
      ++loaded;
      std::vector<std::array<double, 2>> points(rig.channel_count(), std::array<double, 2>{0.7, 0.3});
      if (rig.attachment_count() == 0) continue;
      const Frame f = Evaluate(rig, points);
      for (double v : f.attached) REQUIRE(std::isfinite(v));
    }
  MESSAGE(refused << " damaged rigs refused, " << loaded << " loaded and evaluated finite");
  CHECK(refused > 0);
  // The checksum catches any of them when it is checked.
  std::vector<unsigned char> damaged = bytes;
  damaged[chan->offset + 5] ^= 1;
  Rig rig;
  Error err;
  CHECK(!LoadRig(damaged.data(), damaged.size(), &rig, &err));
  CHECK(err.code == ErrorCode::kBadChecksum);
  // A few messages, exactly.
  auto message = [&](std::size_t at, std::uint32_t value) {
    std::vector<unsigned char> d = bytes;
    std::memcpy(d.data() + chan->offset + at, &value, 4);
    Rig r;
    Error e;
    CHECK(!LoadRig(d.data(), d.size(), &r, &e, unchecked));
    return std::string(e.message);
  };
  CHECK(message(0, 9) == "channel count 9 outside 2..8");
  CHECK(message(4, 0) == "attachment count 0 outside 1..32");
  CHECK(message(16, 2) == "attachment 0: channel 2 outside 1..1");
  CHECK(message(20, 1000) == "attachment 0: parent triangle 1000 of 32");
  CHECK(message(24, 1000) == "attachment 0: joint triangle 1000 of 16");
}

TEST_CASE("channels: Pell's face reproduces every expression on the head, and its joints hold along both paths") {
  std::ifstream in(std::string(POSEMORPH_TEST_RIGS) + "/pell-face.pmrig", std::ios::binary);
  REQUIRE(in.good());
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const Rig rig = Load(bytes);
  REQUIRE(rig.channel_count() == 2);
  REQUIRE(rig.attachment_count() == 3);
  CHECK(rig.FindChannel("face") == 1);
  const Rig& face = *rig.channel_rig(1);
  CHECK(face.pose_count() == 4);
  const double size = rig.bounding_box_diagonal();
  // Each expression with the body at rest: every attachment is its drawn
  // shape in that expression, its joint on the head's (the rest drawings
  // share one canvas, so that is where it was drawn).
  double placed = 0;
  for (std::uint32_t i = 0; i < face.pose_count(); ++i) {
    const Frame f = Evaluate(rig, {{{rig.pose_points()[0], rig.pose_points()[1]}},
                                   {{face.pose_points()[2 * i], face.pose_points()[2 * i + 1]}}});
    std::size_t at = 0;
    for (std::uint32_t a = 0; a < rig.attachment_count(); ++a) {
      const AttachmentView v = rig.attachment(a);
      const double* drawn = v.rig->pose_positions(i).data;
      const auto parent =
          At(rig.pose_positions(0).data, rig.triangles().data + 3 * std::size_t(v.parent_triangle), v.parent_weights);
      const auto joint = At(drawn, v.rig->triangles().data + 3 * std::size_t(v.joint_triangle), v.joint_weights);
      for (std::uint32_t k = 0; k < v.rig->vertex_count(); ++k)
        placed = std::max(placed, std::hypot(f.attached[at + 2 * k] - (drawn[2 * k] + parent[0] - joint[0]),
                                             f.attached[at + 2 * k + 1] - (drawn[2 * k + 1] + parent[1] - joint[1])));
      at += 2 * std::size_t(v.rig->vertex_count());
    }
  }
  MESSAGE("expressions on the rest head: within " << placed / size << " of the rig size");
  CHECK(placed < 1e-9 * size);
  // Both channels on their paths at once (greet and chatter, different
  // lengths): the eyes and the mouth stay on the head.
  double residual = 0;
  for (int k = 0; k <= 120; ++k) {
    double bx, by, fx, fy;
    REQUIRE(SamplePath(rig.path(0), 0.05 * k, &bx, &by));
    REQUIRE(SamplePath(face.path(0), 0.05 * k, &fx, &fy));
    residual = std::max(residual, JointResidual(rig, Evaluate(rig, {{{bx, by}}, {{fx, fy}}})));
  }
  MESSAGE("joint residual over 121 frames of both paths: " << residual << " px");
  CHECK(residual < 0.25);
  CHECK(residual < 1e-9 * size);
}

TEST_CASE("channels: the character is planned before anything is baked: the body and each attachment") {
  const bake::RigDescription d = bake::ParseRigDescription(ArmChannels().dump(), "arm.json", ".");
  const bake::CharacterPlan plan = bake::PlanCharacter(d);
  CHECK(plan.channels == std::vector<std::string>{"body", "arm"});
  // The body: the first channel's parts alone, without channels.
  REQUIRE(plan.body.parts.size() == 1);
  CHECK(plan.body.parts[0].name == d.parts[0].name);
  CHECK(plan.body.channels.empty());
  // One attachment: the arm, over its channel's poses, pinned by its glue.
  REQUIRE(plan.attachments.size() == 1);
  const bake::AttachmentPlan& arm = plan.attachments[0];
  CHECK(arm.part == 1);
  CHECK(arm.description.file == "arm.json: part '" + d.parts[1].name + "'");
  CHECK(arm.description.poses.size() == d.channels[1].poses.size());
  CHECK(arm.description.paths.size() == 1);
  CHECK(arm.glue.to == d.parts[0].name);
  // BakeRig bakes a character with channels through it, to the same bytes each time.
  bake::BakeReport report;
  const std::vector<unsigned char> bytes = bake::BakeCharacter(d, &report);
  CHECK(bytes == bake::BakeRig(d));
  CHECK(report.attachments.size() == 1);
  CHECK(Load(bytes).attachment_count() == 1);
}

TEST_CASE("channels: the file written is verified from its one load: every pose space gives its poses back") {
  const bake::RigDescription d = bake::ParseRigDescription(ArmChannels().dump(), "arm.json", ".");
  const bake::CharacterPlan plan = bake::PlanCharacter(d);
  bake::BakeReport report;
  const Rig whole = Load(bake::BakeCharacter(d, &report));
  REQUIRE(whole.attachment_count() == 1);
  REQUIRE(report.attachments.size() == 1);
  // What is reported is measured in the character's file: the body with the
  // body's poses, the arm's rig inside it with the arm's.
  const bake::BakedRig body = bake::BakeOne(plan.body), arm = bake::BakeOne(plan.attachments[0].description);
  const Rig& arm_in_file = *whole.attachment(0).rig;
  CHECK(report.max_reproduction_error ==
        bake::MeasureReproduction(whole, body.meshes, body.reproduction_tolerance, d.file, "body"));
  CHECK(report.attachments[0].max_reproduction_error ==
        bake::MeasureReproduction(arm_in_file, arm.meshes, arm.reproduction_tolerance, d.file, "part 'arm'"));
  CHECK(report.max_reproduction_error <= body.reproduction_tolerance);
  CHECK(report.attachments[0].max_reproduction_error <= arm.reproduction_tolerance);
  // A pose space that is not the one baked is refused, naming it.
  CHECK_THROWS_WITH_AS(
      bake::MeasureReproduction(arm_in_file, body.meshes, body.reproduction_tolerance, d.file, "part 'arm'"),
      "arm.json: internal error: the baked rig's part 'arm' does not hold the poses and vertices baked",
      bake::BakeError);
  // Poses moved after the bake (here by one unit) come back too far.
  bake::PoseMeshes moved = arm.meshes;
  moved.poses.back().vertices[0].x() += 1;
  CHECK_THROWS_WITH_AS(
      bake::MeasureReproduction(arm_in_file, moved, arm.reproduction_tolerance, d.file, "part 'arm'"),
      doctest::Contains("arm.json: internal error: the baked rig's part 'arm' reproduces its poses only to"),
      bake::BakeError);
}
