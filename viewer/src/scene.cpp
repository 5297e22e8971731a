// SPDX-License-Identifier: MIT
#include "scene.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "posemorph/draw_list.h"
#include "posemorph/jobs.h"
#include "posemorph/path.h"
#include "machine_driver.h"

namespace posemorph::viewer {

View CharacterBounds(const Rig& rig) {
  View v{1e300, 1e300, -1e300, -1e300};
  for (std::uint32_t i = 0; i < rig.pose_count(); ++i) {
    const Span<const double> p = rig.pose_positions(i);
    for (std::size_t k = 0; k < p.size; k += 2) {
      v.x0 = std::min(v.x0, p.data[k]), v.x1 = std::max(v.x1, p.data[k]);
      v.y0 = std::min(v.y0, p.data[k + 1]), v.y1 = std::max(v.y1, p.data[k + 1]);
    }
  }
  const double margin = 0.06 * std::max(v.x1 - v.x0, v.y1 - v.y0);
  return {v.x0 - margin, v.y0 - margin, v.x1 + margin, v.y1 + margin};
}

View TransformBounds(const Transform2D& t, const View& r) {
  View out{1e300, 1e300, -1e300, -1e300};
  const double corners[4][2] = {{r.x0, r.y0}, {r.x1, r.y0}, {r.x0, r.y1}, {r.x1, r.y1}};
  for (const auto& c : corners) {
    double x = 0, y = 0;
    t.Apply(c[0], c[1], &x, &y);
    out.x0 = std::min(out.x0, x), out.x1 = std::max(out.x1, x);
    out.y0 = std::min(out.y0, y), out.y1 = std::max(out.y1, y);
  }
  return out;
}

TextureFilter SceneFilter(const Rig& rig, const Scene& scene) {
  if (scene.filter < 0) return rig.texture_filter();
  return scene.filter == 1 ? TextureFilter::kNearest : TextureFilter::kLinear;
}

std::uint32_t SceneCharacters(const Rig& rig, const Scene& scene) {
  if (scene.show_bases) return rig.pose_count();
  if (scene.compare_linear) return 2;
  return std::max<std::uint32_t>(scene.crowd, 1);
}

namespace {

// SplitMix64: a few lines, the same sequence everywhere (std::
// distributions are not specified bit for bit across standard libraries).
struct Random {
  std::uint64_t state;
  double Next() {  // uniform in [0, 1)
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return double((z ^ (z >> 31)) >> 11) * (1.0 / 9007199254740992.0);
  }
};

// A character with control channels: each later channel's point per
// character (its path at the character's phase, else the scene's point,
// else its first pose's), for DrawListJob's channel_points.
bool ChannelPoints(const Rig& rig, const Scene& scene, SceneScratch& scratch, std::uint32_t K, std::string* error) {
  const std::uint32_t C = rig.channel_count();
  scratch.channel_points.assign(std::size_t(K) * 2 * (C - 1), 0.0);
  for (std::uint32_t c = 1; c < C; ++c) {
    const Rig& channel = *rig.channel_rig(c);
    const ChannelInput* in = c - 1 < scene.channels.size() ? &scene.channels[c - 1] : nullptr;
    int path = -1;
    if (in && !in->path.empty()) {
      path = channel.FindPath(in->path.c_str());
      if (path < 0) {
        const StringView name = rig.channel_name(c);
        *error = "channel '" + std::string(name.data, name.size) + "' has no path \"" + in->path + "\"";
        return false;
      }
    }
    for (std::uint32_t k = 0; k < K; ++k) {
      double x = in ? in->x : channel.pose_points()[0], y = in ? in->y : channel.pose_points()[1];
      if (path >= 0) {
        const PathView p = channel.path(std::uint32_t(path));
        SamplePath(p, scene.time + (p.end_time() - p.start_time()) * scratch.phases[k], &x, &y);
      }
      scratch.channel_points[(std::size_t(k) * (C - 1) + (c - 1)) * 2] = x;
      scratch.channel_points[(std::size_t(k) * (C - 1) + (c - 1)) * 2 + 1] = y;
    }
  }
  return true;
}

}  // namespace

void CrowdLayout(const Rig& rig, std::uint32_t count, std::uint32_t seed, Transform2D* transforms, double* phases) {
  const View one = CharacterBounds(rig);
  const double cw = one.x1 - one.x0, ch = one.y1 - one.y0;
  struct Member {
    double depth, x;
    bool flip;
    std::uint32_t index;
  };
  std::vector<Member> members(count);
  Random random{seed};
  const double ground = cw * std::max(2.0, 1.2 * std::sqrt(double(count)));
  for (std::uint32_t k = 0; k < count; ++k) {
    members[k].depth = random.Next();
    members[k].x = (random.Next() - 0.5) * ground;
    members[k].flip = random.Next() < 0.5;
    members[k].index = k;
  }
  std::stable_sort(members.begin(), members.end(),
                   [](const Member& a, const Member& b) { return a.depth > b.depth; });  // far first
  // Each character's feet (the bottom middle of its bounds) stand on the ground line.
  Transform2D feet;
  feet.tx = float(-(one.x0 + one.x1) / 2), feet.ty = float(-one.y0);
  for (std::uint32_t i = 0; i < count; ++i) {
    const Member& m = members[i];
    const double scale = 1 - 0.55 * m.depth;
    const Transform2D place = Transform2D::Make(m.x, m.depth * 0.8 * ch, 0, scale, scale, m.flip);
    transforms[i] = Compose(place, feet);
    phases[i] = double(m.index) / count;
  }
}

bool PrepareScene(const Rig& rig, const Scene& scene, RigRenderer& renderer, SceneScratch& scratch, SceneBounds* bounds,
                  std::uint32_t* count, std::string* error) {
  const std::uint32_t V = rig.vertex_count(), K = SceneCharacters(rig, scene);
  if (K > renderer.max_instances()) {
    *error = "a scene of " + std::to_string(K) + " characters is more than the renderer holds (" +
             std::to_string(renderer.max_instances()) + ")";
    return false;
  }
  if (scene.machine && (scene.machine->count() != K || scene.show_bases || scene.compare_linear)) {
    *error = "the state machine drives " + std::to_string(scene.machine->count()) +
             " character(s): not the base poses, the rigid | linear comparison or another crowd";
    return false;
  }
  int path = -1;
  if (!scene.path.empty() && !scene.machine) {
    path = rig.FindPath(scene.path.c_str());
    if (path < 0) {
      *error = "the rig has no path \"" + scene.path + "\"";
      return false;
    }
  }
  const View one = CharacterBounds(rig);
  const double cw = one.x1 - one.x0;

  // Where each character stands, in draw order, and its pose-space point.
  scratch.points.resize(2 * std::size_t(K));
  scratch.transforms.resize(K);
  scratch.phases.assign(K, 0.0);
  if (K > 1 && !scene.show_bases && !scene.compare_linear) {
    CrowdLayout(rig, K, scene.seed, scratch.transforms.data(), scratch.phases.data());
  } else if (K == 1) {
    scratch.transforms[0] = scene.transform;
  } else {
    for (std::uint32_t k = 0; k < K; ++k) scratch.transforms[k] = Transform2D::Make(cw * k, 0);  // in a row
  }
  for (std::uint32_t k = 0; k < K; ++k) {
    double x = scene.x, y = scene.y;
    if (scene.show_bases) {
      x = rig.pose_points().data[2 * k], y = rig.pose_points().data[2 * k + 1];
    } else if (path >= 0) {
      const PathView p = rig.path(std::uint32_t(path));
      const double t0 = p.start_time(), t1 = p.end_time();
      SamplePath(p, scene.time + (t1 - t0) * scratch.phases[k], &x, &y);
    }
    scratch.points[2 * k] = x, scratch.points[2 * k + 1] = y;
  }

  // The runtime: one draw-list job (two for the rigid | linear comparison),
  // positions straight into the renderer's buffer; a character with
  // channels gets its attachments' lists too.
  const std::uint32_t A = rig.attachment_count();
  if (A > 0 && !scene.machine && !ChannelPoints(rig, scene, scratch, K, error)) return false;
  scratch.workspace.resize(DrawListWorkspaceSize(rig, K));
  scratch.lists.resize(K);
  scratch.attached_positions.resize(std::size_t(K) * 2 * rig.attached_vertex_count());
  scratch.attachment_lists.resize(std::size_t(K) * A);
  scratch.colours.assign(K, scene.colour);
  const std::size_t P = rig.part_count();
  const bool machine_parts = scene.machine && scene.machine->part_count() == P;
  const bool opacities = scene.part_opacities.size() == P || machine_parts;
  scratch.part_opacities.assign(opacities ? K * P : 0, 1.0f);
  for (std::uint32_t k = 0; opacities && k < K; ++k) {
    float* to = scratch.part_opacities.data() + k * P;
    if (scene.part_opacities.size() == P) std::copy(scene.part_opacities.begin(), scene.part_opacities.end(), to);
    for (std::size_t p = 0; machine_parts && p < P; ++p) to[p] *= scene.machine->part_opacities(k)[p];
  }
  for (std::uint32_t k = 0; scene.machine && k < K; ++k) {  // the states' colour times the scene's own
    const Colour& c = scene.machine->colour(k);
    Colour& to = scratch.colours[k];
    to.r *= c.r, to.g *= c.g, to.b *= c.b, to.a *= c.a;
  }
  const auto run = [&](std::uint32_t first, std::uint32_t n, Interpolation interpolation) {
    DrawListJob job;
    job.rig = &rig;
    job.count = n;
    job.points = {scratch.points.data() + 2 * std::size_t(first), 2 * std::size_t(n)};
    job.transforms = {scratch.transforms.data() + first, n};
    job.colours = {scratch.colours.data() + first, n};
    if (opacities) job.part_opacities = {scratch.part_opacities.data() + first * P, n * P};
    job.sigma = scene.sigma;
    job.limit_weights = scene.limit_weights;
    job.interpolation = interpolation;
    job.max_drawings = std::clamp<std::uint32_t>(scene.max_drawings, 1, kDrawingsPerCharacter);
    job.workspace = {scratch.workspace.data(), scratch.workspace.size()};
    job.positions = {renderer.positions() + std::size_t(first) * 2 * V, std::size_t(n) * 2 * V};
    job.output = {scratch.lists.data() + first, n};
    if (A > 0) {
      const std::size_t c2 = 2 * std::size_t(rig.channel_count() - 1),
                        a2 = 2 * std::size_t(rig.attached_vertex_count());
      job.channel_points = {scratch.channel_points.data() + first * c2, n * c2};
      job.attached_positions = {scratch.attached_positions.data() + first * a2, n * a2};
      job.attached_output = {scratch.attachment_lists.data() + std::size_t(first) * A, std::size_t(n) * A};
    }
    if (scene.machine) scene.machine->Bind(&job);  // all K characters (checked above)
    return job.Run();
  };
  const bool ok = scene.compare_linear ? run(0, 1, Interpolation::kRigid) && run(1, 1, Interpolation::kLinear)
                                       : run(0, K, scene.linear ? Interpolation::kLinear : Interpolation::kRigid);
  if (!ok) {
    *error = "the draw-list job refused the scene";
    return false;
  }
  // The attachments' positions into their renderers' buffers: a job's
  // floats are attachment after attachment, character after character.
  const auto place_attachments = [&](std::uint32_t first, std::uint32_t n) {
    std::size_t offset = 0;
    for (std::uint32_t a = 0; a < A; ++a) {
      const std::size_t p2 = 2 * std::size_t(rig.attachment(a).rig->vertex_count());
      RigRenderer* r = renderer.attachment(a);
      const float* from = scratch.attached_positions.data() + std::size_t(first) * 2 * rig.attached_vertex_count();
      std::copy(from + offset * n, from + offset * n + std::size_t(n) * p2, r->positions() + std::size_t(first) * p2);
      for (std::uint32_t k = first; k < first + n; ++k)
        r->SetCharacter(k, scratch.attachment_lists[std::size_t(k) * A + a]);
      offset += p2;
    }
  };
  if (A > 0) {
    if (scene.compare_linear)
      place_attachments(0, 1), place_attachments(1, 1);
    else
      place_attachments(0, K);
  }
  View all{1e300, 1e300, -1e300, -1e300};
  for (std::uint32_t k = 0; k < K; ++k) {
    renderer.SetCharacter(k, scratch.lists[k]);
    const View b = TransformBounds(scratch.transforms[k], one);
    all = {std::min(all.x0, b.x0), std::min(all.y0, b.y0), std::max(all.x1, b.x1), std::max(all.y1, b.y1)};
  }
  renderer.SetHiddenParts(scene.hidden_parts);
  bounds->all = all;
  bounds->first = TransformBounds(scratch.transforms[0], one);
  *count = K;
  return true;
}

}  // namespace posemorph::viewer
