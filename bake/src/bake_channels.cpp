// SPDX-License-Identifier: MIT
#include "posemorph/bake/bake_channels.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <sstream>

#include "posemorph/bake/error.h"
#include "posemorph/bake/machine_section.h"
#include "posemorph/bake/reproduction_check.h"
#include "posemorph/jobs.h"
#include "posemorph/rig.h"
#include "posemorph/rig_format.h"
#include "rig_message.h"
#include "rig_writer.h"
#include "runtime_oracle.h"

namespace posemorph::bake {
namespace {

namespace fmt = format;

// A point of a pose-0 drawing in the rig's units (y up, origin at the
// canvas's pivot); a rig given as vertices has no canvas and takes it as is.
Eigen::Vector2d ToRig(const Rig& rig, const Eigen::Vector2d& p) {
  const DrawingCanvas c = rig.pose_canvas(0);
  if (!(c.width > 0)) return p;
  return {p.x() - c.pivot_x, c.pivot_y - p.y()};
}

struct Located {
  std::uint32_t triangle = 0;
  double weights[3] = {0, 0, 0};
  double inside = -HUGE_VAL;  // the smallest barycentric weight: >= 0 inside
};

// The triangle of [first, first + count) holding p in pose 0, the most
// inside one where p lies on an edge.
Located Locate(const Rig& rig, std::uint32_t first, std::uint32_t count, const Eigen::Vector2d& p) {
  const double* x = rig.pose_positions(0).data;
  const std::uint32_t* tri = rig.triangles().data;
  Located best;
  for (std::uint32_t t = first; t < first + count; ++t) {
    const std::uint32_t* v = tri + 3 * std::size_t(t);
    const Eigen::Vector2d a(x[2 * v[0]], x[2 * v[0] + 1]), b(x[2 * v[1]], x[2 * v[1] + 1]),
        c(x[2 * v[2]], x[2 * v[2] + 1]);
    const double det = (a.x() - c.x()) * (b.y() - c.y()) - (b.x() - c.x()) * (a.y() - c.y());
    if (!(std::fabs(det) > 0)) continue;
    const double l0 = ((b.y() - c.y()) * (p.x() - c.x()) - (b.x() - c.x()) * (p.y() - c.y())) / det;
    const double l1 = ((c.y() - a.y()) * (p.x() - c.x()) + (a.x() - c.x()) * (p.y() - c.y())) / det;
    const double l2 = 1 - l0 - l1;
    const double inside = std::min({l0, l1, l2});
    if (inside > best.inside) {
      best.triangle = t;
      best.weights[0] = l0, best.weights[1] = l1, best.weights[2] = l2;
      best.inside = inside;
    }
  }
  // Clamp the rounding of a point on an edge or a vertex into [0, 1].
  double sum = 0;
  for (double& w : best.weights) sum += (w = std::clamp(w, 0.0, 1.0));
  for (double& w : best.weights) w /= sum;
  return best;
}

// Where the barycentric point lies in pose `pose`.
Eigen::Vector2d At(const Rig& rig, std::uint32_t pose, std::uint32_t triangle, const double* w) {
  const double* x = rig.pose_positions(pose).data;
  const std::uint32_t* v = rig.triangles().data + 3 * std::size_t(triangle);
  Eigen::Vector2d p(0, 0);
  for (int k = 0; k < 3; ++k) p += w[k] * Eigen::Vector2d(x[2 * v[k]], x[2 * v[k] + 1]);
  return p;
}

void Align(std::vector<unsigned char>& out) {
  while (out.size() % fmt::kSectionAlignment) out.push_back(0);
}

struct Attachment {
  std::uint32_t channel = 0;
  Located parent, joint;
  std::vector<unsigned char> bytes;
};

// The body's sections with a CHAN section added (runtime/FORMAT.md).
RigSections Compose(RigSections body, const std::vector<std::string>& names,
                    const std::vector<Attachment>& attachments) {
  std::vector<unsigned char> chan;
  fmt::ChannelsHeader header{};
  header.channel_count = std::uint32_t(names.size());
  header.attachment_count = std::uint32_t(attachments.size());
  AppendRecord(chan, header);
  const std::size_t entries = chan.size();
  chan.resize(chan.size() + attachments.size() * fmt::kAttachmentEntrySize, 0);  // filled below
  for (const std::string& name : names) AppendString(chan, name);
  for (std::size_t a = 0; a < attachments.size(); ++a) {
    const Attachment& at = attachments[a];
    Align(chan);
    fmt::AttachmentEntry entry{};
    entry.channel = at.channel;
    entry.parent_triangle = at.parent.triangle;
    entry.joint_triangle = at.joint.triangle;
    for (int k = 0; k < 3; ++k)
      entry.parent_weights[k] = at.parent.weights[k], entry.joint_weights[k] = at.joint.weights[k];
    entry.offset = chan.size();
    entry.size = at.bytes.size();
    fmt::EncodeRecord(entry, chan.data() + entries + a * fmt::kAttachmentEntrySize);
    chan.insert(chan.end(), at.bytes.begin(), at.bytes.end());
  }
  body.Add(fmt::kChannels, std::move(chan));
  return body;
}

// Each attachment in each pose of its channel, the body at pose 0 and the
// other channels at theirs: the largest distance from its drawn shape moved
// so that its joint lies on the body's.
std::vector<double> PlacedErrors(const Rig& rig) {
  std::vector<double> errors(rig.attachment_count(), 0.0);
  const std::size_t N0 = rig.pose_count(), NW = rig.attached_weight_count();
  std::vector<double> raw(N0), limited(N0), work(rig.morph_workspace_size()), body(2 * std::size_t(rig.vertex_count()));
  std::vector<double> w(NW), wl(NW), attach_work(rig.attach_workspace_size()),
      placed(2 * std::size_t(rig.attached_vertex_count()));
  WeightsJob weights;
  weights.rig = &rig;
  weights.x = rig.pose_points()[0], weights.y = rig.pose_points()[1];
  weights.raw = {raw.data(), N0};
  weights.limited = {limited.data(), N0};
  weights.Run();
  MorphJob morph;
  morph.rig = &rig;
  morph.weights = {raw.data(), N0};
  morph.limited_weights = {limited.data(), N0};
  morph.workspace = {work.data(), work.size()};
  morph.positions = {body.data(), body.size()};
  morph.Run();
  for (std::uint32_t c = 1; c < rig.channel_count(); ++c) {
    const Rig& channel = *rig.channel_rig(c);
    for (std::uint32_t i = 0; i < channel.pose_count(); ++i) {
      for (std::uint32_t k = 1; k < rig.channel_count(); ++k) {
        const Rig& other = *rig.channel_rig(k);
        const std::uint32_t pose = k == c ? i : 0;
        WeightsJob job;
        job.rig = &other;
        job.x = other.pose_points()[2 * pose], job.y = other.pose_points()[2 * pose + 1];
        job.raw = {w.data() + rig.channel_weight_offset(k), other.pose_count()};
        job.limited = {wl.data() + rig.channel_weight_offset(k), other.pose_count()};
        job.Run();
      }
      AttachJob attach;
      attach.rig = &rig;
      attach.body_positions = {body.data(), body.size()};
      attach.weights = {w.data(), NW};
      attach.limited_weights = {wl.data(), NW};
      attach.workspace = {attach_work.data(), attach_work.size()};
      attach.positions = {placed.data(), placed.size()};
      attach.Run();
      std::size_t at = 0;
      for (std::uint32_t a = 0; a < rig.attachment_count(); ++a) {
        const AttachmentView view = rig.attachment(a);
        const Rig& part = *view.rig;
        if (view.channel == c) {
          const Eigen::Vector2d shift = At(rig, 0, view.parent_triangle, view.parent_weights) -
                                        At(part, i, view.joint_triangle, view.joint_weights);
          const double* drawn = part.pose_positions(i).data;
          for (std::uint32_t v = 0; v < part.vertex_count(); ++v) {
            const Eigen::Vector2d expected = Eigen::Vector2d(drawn[2 * v], drawn[2 * v + 1]) + shift;
            const Eigen::Vector2d got(placed[at + 2 * v], placed[at + 2 * v + 1]);
            errors[a] = std::max(errors[a], (got - expected).norm());
          }
        }
        at += 2 * std::size_t(part.vertex_count());
      }
    }
  }
  return errors;
}

}  // namespace

RigDescription ChannelBodyDescription(const RigDescription& description) {
  RigDescription body = description;
  body.channels.clear();
  body.state_machine = {};  // the whole character's, written once with the file (BakeCharacter)
  body.parts.clear();
  body.glue.clear();
  std::vector<std::size_t> index(description.parts.size(), SIZE_MAX);
  for (std::size_t p = 0; p < description.parts.size(); ++p)
    if (description.parts[p].channel == 0) {
      index[p] = body.parts.size();
      body.parts.push_back(description.parts[p]);
    }
  for (const GlueDescription& g : description.glue)
    if (index[g.part_index] != SIZE_MAX && index[g.to_index] != SIZE_MAX) {
      GlueDescription e = g;
      e.part_index = index[g.part_index];
      e.to_index = index[g.to_index];
      body.glue.push_back(std::move(e));
    }
  return body;
}

RigDescription AttachmentDescription(const RigDescription& description, std::size_t part) {
  const PartDescription& p = description.parts.at(part);
  const ChannelDescription& channel = description.channels.at(p.channel);
  RigDescription sub = description;
  sub.file = description.file + ": part '" + p.name + "'";
  sub.channels.clear();
  sub.state_machine = {};                      // an attachment's rig has none of its own
  sub.anchor_given = sub.facing_left = false;  // the character's placement is the body's
  sub.glue.clear();
  sub.warnings.clear();
  sub.poses = channel.poses;
  sub.paths = channel.paths;
  sub.parts = {p};
  sub.parts[0].channel = 0;
  const bool drawn = !p.poses.empty() && p.poses[0].drawn;
  for (const GlueDescription& g : description.glue) {
    if (g.part_index != part || !drawn) continue;
    if (g.at.size() != p.poses.size())
      throw BakeError(description.file, "part '" + p.name + "' is drawn: give its joint to '" + g.to +
                                            "' in each of its channel's poses (one [x, y] per pose)");
    for (std::size_t i = 0; i < p.poses.size(); ++i) sub.parts[0].poses[i].features.push_back(g.at[i]);
  }
  return sub;
}

CharacterPlan PlanCharacter(const RigDescription& d) {
  CharacterPlan plan;
  plan.body = ChannelBodyDescription(d);
  for (std::size_t p = 0; p < d.parts.size(); ++p) {
    if (d.parts[p].channel == 0) continue;
    const GlueDescription* glue = nullptr;
    for (const GlueDescription& g : d.glue)
      if (g.part_index == p) glue = &g;
    if (!glue) throw BakeError(d.file, "part '" + d.parts[p].name + "' is glued to nothing");
    plan.attachments.push_back({p, AttachmentDescription(d, p), *glue});
  }
  for (const ChannelDescription& c : d.channels) plan.channels.push_back(c.name);
  return plan;
}

std::vector<unsigned char> BakeCharacter(const RigDescription& d, BakeReport* report) {
  const auto start = std::chrono::steady_clock::now();
  const CharacterPlan plan = PlanCharacter(d);
  BakeReport r;
  // Each pose space baked on its own, its rig as its verification loaded it.
  BakedRig body_baked = BakeOne(plan.body, &r);
  const Rig& body = body_baked.rig;
  std::vector<Attachment> attachments;
  struct Poses {
    PoseMeshes meshes;
    double tolerance;
  };
  std::vector<Poses> attached;  // each attachment's poses, for the verification
  for (const AttachmentPlan& planned : plan.attachments) {
    const PartDescription& part = d.parts[planned.part];
    const GlueDescription* glue = &planned.glue;
    BakeReport sub;
    Attachment a;
    a.channel = std::uint32_t(part.channel);
    BakedRig baked = BakeOne(planned.description, &sub);
    a.bytes = std::move(baked.bytes);
    const Rig& rig = baked.rig;
    std::uint32_t parent = 0;
    while (parent < body.part_count() &&
           std::string(body.part(parent).name.data, body.part(parent).name.size) != glue->to)
      ++parent;
    const PartView pv = body.part(parent);
    const std::string where = "glue of part '" + part.name + "' to '" + glue->to + "'";
    // 1e-9 of the rig's size: on an edge or a vertex, not outside.
    const double tolerance = -1e-9;
    a.parent = Locate(body, pv.first_triangle, pv.triangle_count, ToRig(body, glue->at[0]));
    if (!(a.parent.inside >= tolerance))
      throw BakeError(d.file,
                      where + ": the joint " + PointText(glue->at[0]) + " lies off part '" + glue->to + "' in " +
                          PoseLabel(body.pose_name(0).data ? std::string(body.pose_name(0).data, body.pose_name(0).size)
                                                           : std::string(),
                                    0) +
                          ": a joint lies on both parts");
    a.joint = Locate(rig, 0, rig.triangle_count(), ToRig(rig, glue->at[0]));
    if (!(a.joint.inside >= tolerance))
      throw BakeError(d.file, where + ": the joint " + PointText(glue->at[0]) + " lies off part '" + part.name +
                                  "' in its channel's first pose: a joint lies on both parts");
    AttachmentReport ar;
    ar.part = part.name;
    ar.channel = d.channels[part.channel].name;
    ar.parent = glue->to;
    ar.vertices = sub.vertices, ar.triangles = sub.triangles, ar.poses = sub.poses;
    ar.parent_triangle = a.parent.triangle;
    ar.bytes = a.bytes.size(), ar.exact_bytes = sub.exact_bytes;
    r.attachments.push_back(ar);
    for (const std::string& w : sub.warnings) r.warnings.push_back(w);
    attachments.push_back(std::move(a));
    attached.push_back({std::move(baked.meshes), baked.reproduction_tolerance});
  }
  const std::vector<std::string>& names = plan.channels;
  // The file, written once, and its verification from one load by the
  // runtime: every pose space of the file (the body, each attachment) gives
  // its poses back, and each attachment sits at its joint in every pose of
  // its channel. (Each pose space's bake loaded its own bytes before, to
  // check its in-betweens for folds; what is reported is measured here.)
  RigSections whole_sections = Compose(std::move(body_baked.sections), names, attachments);
  if (!d.state_machine.layers.empty()) whole_sections.Add(fmt::kMachine, MachineSection(d.state_machine));
  std::vector<unsigned char> bytes = WriteRig(whole_sections);
  const Rig whole = LoadWithRuntime(bytes, d.file, "the rig written does not load in the runtime");
  r.drawings = ReadRigDrawings(whole);
  if (whole.attachment_count() != attached.size())
    throw BakeError(d.file, "internal error: the rig written holds " + std::to_string(whole.attachment_count()) +
                                " attachments, not " + std::to_string(attached.size()));
  r.max_reproduction_error =
      MeasureReproduction(whole, body_baked.meshes, body_baked.reproduction_tolerance, d.file, "body");
  const std::vector<double> placed = PlacedErrors(whole);
  std::uint64_t exact = r.exact_bytes;
  for (std::size_t a = 0; a < r.attachments.size(); ++a) {
    r.attachments[a].max_reproduction_error =
        MeasureReproduction(*whole.attachment(std::uint32_t(a)).rig, attached[a].meshes, attached[a].tolerance, d.file,
                            "part '" + r.attachments[a].part + "'");
    r.attachments[a].placed_error = placed[a];
    exact += r.attachments[a].exact_bytes;
  }
  r.channels = names;
  r.bytes = bytes.size();
  r.exact_bytes = exact;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (report) *report = std::move(r);
  return bytes;
}

}  // namespace posemorph::bake
