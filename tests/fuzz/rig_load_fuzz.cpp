// SPDX-License-Identifier: MIT
// libFuzzer harness: the rig loader, then frames. The header's file size and
// CRC-32 are rewritten after every mutation so mutated bytes reach the
// section parsers and the compact decoder instead of stopping at the
// checksum. A rig that loads must give finite weights, positions and uvs at
// every pose point and at points far outside the pose space, and so must its
// attachments (format 1.7: each a nested rig with its own checksum, which is
// not checked here, so that mutations reach the nested rigs' parsers too),
// and a crowd's draw lists (DrawListJob: finite positions, drawing weights
// that are finite and sum to 1, finite transforms, for the body and each
// attachment), and its state machine's steps (finite weights on every
// channel); anything else aborts (a finding).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "posemorph/animator.h"
#include "posemorph/draw_list.h"
#include "posemorph/jobs.h"
#include "posemorph/rig.h"
#include "posemorph/rig_format.h"
#include "posemorph/state_machine.h"

namespace {

using namespace posemorph;

void RequireFinite(const double* v, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) std::abort();
}

// A job's positions: within kMaxPosition when it succeeded, zeros when it
// failed (a factor that amplifies the solve, jobs.h).
void RequireWithin(const double* v, std::size_t n, bool succeeded) {
  for (std::size_t i = 0; i < n; ++i)
    if (succeeded ? !(std::fabs(v[i]) <= kMaxPosition) : v[i] != 0) std::abort();
}

void Frame(const Rig& rig, double x, double y, std::vector<double>& raw, std::vector<double>& limited,
           std::vector<double>& texture, std::vector<double>& work, std::vector<double>& positions) {
  WeightsJob weights;
  weights.rig = &rig;
  weights.x = x, weights.y = y;
  weights.raw = MakeSpan(raw), weights.limited = MakeSpan(limited), weights.texture = MakeSpan(texture);
  if (!weights.Run()) std::abort();  // a loaded rig and right-sized spans: Run may not fail
  RequireFinite(raw.data(), raw.size());
  RequireFinite(limited.data(), limited.size());
  RequireFinite(texture.data(), texture.size());
  MorphJob morph;
  morph.rig = &rig;
  morph.weights = MakeSpan(raw), morph.limited_weights = MakeSpan(limited);
  morph.workspace = MakeSpan(work), morph.positions = MakeSpan(positions);
  // Run fails only where the solve went beyond kMaxPosition, and then writes zeros.
  if (!morph.Validate()) std::abort();
  RequireWithin(positions.data(), positions.size(), morph.Run());
}

// One list's drawings and transform: what a renderer is handed.
void RequireDrawable(const DrawList& list) {
  if (list.drawing_count < 1 || list.drawing_count > kMaxBlendDrawings) std::abort();
  double sum = 0;
  for (std::uint32_t d = 0; d < list.drawing_count; ++d) {
    const float w = list.drawings[d].weight;
    if (!(w >= 0 && w <= 1)) std::abort();
    sum += w;
  }
  if (!(std::fabs(sum - 1) <= 1e-5)) std::abort();
  const Transform2D& t = list.transform;
  for (float v : {t.a, t.b, t.c, t.d, t.tx, t.ty})
    if (!std::isfinite(v)) std::abort();
}

// Two characters' draw lists, one at pose 0's point and one far outside,
// the second placed by a transform beyond float range (the identity then).
void DrawLists(const Rig& rig) {
  const CharacterBuffers buffers = CharacterBuffers::For(rig, 2);
  if (buffers.count != 2) return;  // a rig too large for a crowd of two
  std::vector<double> block(buffers.bytes / sizeof(double) + 1);
  DrawListJob job;
  if (!buffers.Bind(rig, block.data(), block.size() * sizeof(double), &job)) std::abort();
  const double points[4] = {rig.pose_points()[0], rig.pose_points()[1], -1e9, 1e300};
  const Transform2D transforms[2] = {Transform2D::Make(3, -2, 0.5, 2, 2, true), Transform2D::Make(1e300, 0, 0, 1e300)};
  job.points = {points, 4};
  job.transforms = {transforms, 2};
  if (!job.Validate()) std::abort();
  const bool ran = job.Run();
  for (std::size_t i = 0; i < job.positions.size; ++i)
    if (!std::isfinite(job.positions[i])) std::abort();
  for (std::size_t i = 0; i < job.attached_positions.size; ++i)
    if (!std::isfinite(job.attached_positions[i])) std::abort();
  if (!ran) return;
  for (std::size_t k = 0; k < job.output.size; ++k) RequireDrawable(job.output[k]);
  for (std::size_t k = 0; k < job.attached_output.size; ++k) RequireDrawable(job.attached_output[k]);
}

// A rig's state machine (format 1.9): its inputs each set, steps with
// animator updates in between; every channel's weights stay finite and the
// colours its states set (1.10) stay in [0, 1].
void Machine(const Rig& rig) {
  if (rig.machine_layers().empty()) return;
  const std::size_t C = rig.channel_count(), N = rig.pose_count(), A = rig.attached_weight_count();
  std::vector<AnimatorTrack> tracks(C);
  MachineInstance m;
  if (!AnimatorReset(rig, MakeSpan(tracks)) || !MachineReset(rig, &m)) std::abort();
  std::vector<double> raw(N), limited(N), ar(A), al(A);
  for (int step = 0; step < 6; ++step) {
    for (std::uint32_t i = 0; i < rig.machine_inputs().size; ++i) {
      MachineFire(rig, &m, i);
      MachineSetBool(rig, &m, i, (step + i) % 2 == 0);
      MachineSetNumber(rig, &m, i, step * 0.3 - 0.2);
      MachineSetPoint(rig, &m, i, step - 2.0, 0.5);
    }
    MachineStepJob job;
    job.rig = &rig, job.machines = {&m, 1}, job.tracks = MakeSpan(tracks);
    if (!job.Run()) std::abort();
    AnimatorUpdateJob update;
    update.rig = &rig, update.dt = step == 3 ? 1e9 : 0.35;
    update.tracks = MakeSpan(tracks);
    update.weights = MakeSpan(raw), update.limited_weights = MakeSpan(limited);
    update.attached_weights = MakeSpan(ar), update.attached_limited_weights = MakeSpan(al);
    if (!update.Run()) std::abort();
    RequireFinite(raw.data(), raw.size()), RequireFinite(limited.data(), limited.size());
    RequireFinite(ar.data(), ar.size()), RequireFinite(al.data(), al.size());
    // The colours its states set (format 1.10): each in [0, 1].
    Colour colour;
    std::vector<float> parts(rig.part_count() > 1 ? rig.part_count() : 0);
    MachineColourJob colours;
    colours.rig = &rig, colours.dt = update.dt, colours.machines = {&m, 1}, colours.colours = {&colour, 1};
    if (!parts.empty()) colours.part_opacities = MakeSpan(parts);
    if (!colours.Run()) std::abort();
    for (float v : {colour.r, colour.g, colour.b, colour.a})
      if (!(v >= 0 && v <= 1)) std::abort();
    for (float v : parts)
      if (!(v >= 0 && v <= 1)) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<unsigned char> bytes(data, data + size);
  if (bytes.size() >= format::kHeaderSize) {
    const std::uint64_t file_size = bytes.size();
    std::memcpy(bytes.data() + format::kOffFileSize, &file_size, 8);
    const std::uint32_t crc = format::Crc32(bytes.data() + format::kHeaderSize, bytes.size() - format::kHeaderSize);
    std::memcpy(bytes.data() + format::kOffChecksum, &crc, 4);
  }
  Rig rig;
  Error err;
  LoadOptions options;
  options.verify_checksum = false;
  if (!LoadRig(bytes.data(), bytes.size(), &rig, &err, options)) {
    if (err.message[0] == 0) std::abort();  // every refusal says why
    return 0;
  }
  const std::size_t n = rig.pose_count();
  std::vector<double> raw(n), limited(n), texture(n), work(rig.morph_workspace_size()),
      positions(2 * std::size_t(rig.vertex_count()));
  const double far[][2] = {{0, 0}, {0.5, 0.5}, {-3, 2}, {1e6, -1e6}, {1e300, 1e300}};
  for (const auto& p : far) Frame(rig, p[0], p[1], raw, limited, texture, work, positions);
  for (std::uint32_t i = 0; i < n; ++i) {
    const auto point = rig.pose_points();
    Frame(rig, point.data[2 * i], point.data[2 * i + 1], raw, limited, texture, work, positions);
  }
  if (rig.attachment_count() > 0) {
    std::vector<double> w, wl, attach_work(rig.attach_workspace_size()),
        attached(2 * std::size_t(rig.attached_vertex_count()));
    for (const auto& p : far) {
      Frame(rig, p[0], p[1], raw, limited, texture, work, positions);
      w.assign(rig.attached_weight_count(), 0);
      wl.assign(rig.attached_weight_count(), 0);
      for (std::uint32_t c = 1; c < rig.channel_count(); ++c) {
        const Rig& channel = *rig.channel_rig(c);
        const std::size_t nc = channel.pose_count();
        std::vector<double> craw(nc), climited(nc), ctexture(nc), cwork(channel.morph_workspace_size()),
            cpositions(2 * std::size_t(channel.vertex_count()));
        Frame(channel, p[1], p[0], craw, climited, ctexture, cwork, cpositions);
        std::copy(craw.begin(), craw.end(), w.begin() + rig.channel_weight_offset(c));
        std::copy(climited.begin(), climited.end(), wl.begin() + rig.channel_weight_offset(c));
      }
      AttachJob attach;
      attach.rig = &rig;
      attach.body_positions = MakeSpan(positions);
      attach.weights = MakeSpan(w), attach.limited_weights = MakeSpan(wl);
      attach.workspace = MakeSpan(attach_work), attach.positions = MakeSpan(attached);
      if (!attach.Validate()) std::abort();
      const bool placed = attach.Run();
      RequireFinite(attached.data(), attached.size());
      if (placed)
        for (double v : attached)
          if (!(std::fabs(v) <= 4 * kMaxPosition)) std::abort();  // a body position plus a turned offset
    }
  }
  for (std::uint32_t i = 0; i < n; ++i) {  // empty when the rig has none
    const auto uv = rig.uvs(i);
    for (std::size_t k = 0; k < uv.size; ++k)
      if (!std::isfinite(uv.data[k])) std::abort();
  }
  DrawLists(rig);
  Machine(rig);
  return 0;
}
