// SPDX-License-Identifier: MIT
#include "posemorph/bake/join_parts.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

#include "posemorph/bake/deform_poses.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/orient_triangles.h"
#include "posemorph/bake/validate_rig.h"
#include "rig_message.h"

namespace posemorph::bake {
namespace {

// How far apart two points may be and still be one joint, times the rig's size.
constexpr double kJointTolerance = 1e-9;
// Drawn parts: the mapping works on an integer grid per part (scaled to the
// part's extent), so one joint point lands on each part's grid, up to half
// a cell apart (3e-5 drawing units on a 256-pixel canvas). Copies this close
// are one joint; the joined vertex is the first part's copy.
constexpr double kDrawnJointTolerance = 1e-3;
// How far a joint given to a mesh may lie off its vertex, times the part's size.
constexpr double kVertexTolerance = 1e-6;

std::string GlueLabel(const RigDescription& d, std::size_t g) {
  return "glue[" + std::to_string(g) + "] ('" + d.glue[g].part + "' to '" + d.glue[g].to + "')";
}

bool Involves(const GlueDescription& g, std::size_t part) { return g.part_index == part || g.to_index == part; }

double Size(const Points& vertices) {
  Eigen::AlignedBox2d box;
  for (const Eigen::Vector2d& v : vertices) box.extend(v);
  return box.diagonal().norm();
}

// One part mapped or read alone, validated as a rig of its own.
struct MappedPart {
  PoseMeshes meshes;
  MappingReport report;
  std::vector<std::uint32_t> joint_vertex;  // per glue entry that involves the part, its vertex
};

MappedPart MapPart(const RigDescription& description, std::size_t p) {
  const RigDescription sub = PartRigDescription(description, p);
  MappedPart out;
  const MappedDrawings drawings = MapDrawings(sub);
  out.meshes = DeformPoses(sub, drawings);
  out.meshes.triangles = OrientTriangles(out.meshes);
  if (const std::optional<std::string> problem = ValidateRig(out.meshes, {})) throw BakeError(sub.file, *problem);
  out.report = drawings.report;
  const std::size_t V = out.meshes.poses[0].vertices.size(), N = sub.poses.size();
  const bool drawn = drawings.report.mapped;
  // Drawn: the joints are the features appended last, in glue order.
  std::size_t feature = drawings.feature_vertices.size();
  for (const GlueDescription& g : description.glue) feature -= Involves(g, p) && drawn ? 1 : 0;
  const double tolerance = kVertexTolerance * std::max(1.0, Size(out.meshes.poses[0].vertices));
  for (std::size_t g = 0; g < description.glue.size(); ++g) {
    const GlueDescription& glue = description.glue[g];
    if (!Involves(glue, p)) {
      out.joint_vertex.push_back(0);
      continue;
    }
    if (drawn) {
      out.joint_vertex.push_back(drawings.feature_vertices[feature++]);
      continue;
    }
    // A mesh: the vertex at the joint in pose 0 (and at it in every pose given).
    std::uint32_t best = 0;
    double best_distance = HUGE_VAL;
    for (std::size_t v = 0; v < V; ++v) {
      const double d = (out.meshes.poses[0].vertices[v] - glue.at[0]).norm();
      if (d < best_distance) best = std::uint32_t(v), best_distance = d;
    }
    if (!(best_distance <= tolerance))
      throw BakeError(sub.file, GlueLabel(description, g) + ": no vertex of part '" + description.parts[p].name +
                                    "' lies at the joint " + PointText(glue.at[0]) + " in " +
                                    PoseLabel(sub.poses[0].name, 0) + " (the nearest is " +
                                    std::to_string(best_distance) +
                                    " away): a joint of parts given as vertices is a vertex of both");
    for (std::size_t i = 1; i < glue.at.size() && i < N; ++i)
      if (!((out.meshes.poses[i].vertices[best] - glue.at[i]).norm() <= tolerance))
        throw BakeError(sub.file,
                        GlueLabel(description, g) + ": in " + PoseLabel(sub.poses[i].name, i) + " the joint's vertex " +
                            std::to_string(best) + " of part '" + description.parts[p].name + "' is at " +
                            PointText(out.meshes.poses[i].vertices[best]) + ", not at " + PointText(glue.at[i]));
    out.joint_vertex.push_back(best);
  }
  return out;
}

// Union-find over every part's vertices, numbered part after part.
struct Classes {
  std::vector<std::size_t> parent;
  std::size_t Find(std::size_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  }
};

void AddReport(const MappingReport& part, MappingReport* all) {
  if (!part.mapped) return;
  const bool first = !all->mapped;
  all->mapped = true;
  all->matched_vertices += part.matched_vertices;
  all->boundary_vertices += part.boundary_vertices;
  all->steiner_points += part.steiner_points;
  all->features += part.features;
  all->min_angle_degrees = first ? part.min_angle_degrees : std::min(all->min_angle_degrees, part.min_angle_degrees);
  all->min_angle_before_alignment = first ? part.min_angle_before_alignment
                                          : std::min(all->min_angle_before_alignment, part.min_angle_before_alignment);
  all->simplification_error = std::max(all->simplification_error, part.simplification_error);
  all->seconds += part.seconds;
  all->aligned = first ? part.aligned : all->aligned && part.aligned;
  if (all->alignment_skipped.empty()) all->alignment_skipped = part.alignment_skipped;
  all->alignment_max_move = std::max(all->alignment_max_move, part.alignment_max_move);
  all->alignment_seconds += part.alignment_seconds;
  all->warnings.insert(all->warnings.end(), part.warnings.begin(), part.warnings.end());
}

// A pose's parts are layers of one canvas: the same size and origin.
void CheckCanvases(const RigDescription& d, const std::vector<MappedPart>& parts) {
  for (std::size_t i = 0; i < d.poses.size(); ++i) {
    const PoseMesh* first = nullptr;
    std::size_t first_part = 0;
    for (std::size_t p = 0; p < parts.size(); ++p) {
      const PoseMesh& m = parts[p].meshes.poses[i];
      if (m.canvas_size.x() <= 0) continue;
      if (!first) {
        first = &m, first_part = p;
      } else if (m.canvas_size != first->canvas_size || m.canvas_pivot != first->canvas_pivot) {
        throw BakeError(d.file, "part '" + d.parts[p].name + "', " + PoseLabel(d.poses[i].name, i) +
                                    ": its drawing's canvas (" + PointText(m.canvas_size) + ", origin at " +
                                    PointText(m.canvas_pivot) + ") differs from part '" + d.parts[first_part].name +
                                    "''s (" + PointText(first->canvas_size) + ", origin at " +
                                    PointText(first->canvas_pivot) + "): a pose's parts are layers of one canvas");
      }
    }
  }
  for (std::size_t p = 1; p < parts.size(); ++p)
    if (parts[p].meshes.poses[0].uvs.empty() != parts[0].meshes.poses[0].uvs.empty())
      throw BakeError(d.file, "part '" + d.parts[p].name + "' " +
                                  (parts[p].meshes.poses[0].uvs.empty() ? "has no uvs" : "has uvs") + ", part '" +
                                  d.parts[0].name + "' " + (parts[0].meshes.poses[0].uvs.empty() ? "none" : "has") +
                                  ": draw every part, or give every part uvs");
}

}  // namespace

RigDescription PartRigDescription(const RigDescription& description, std::size_t p) {
  const PartDescription& part = description.parts.at(p);
  RigDescription sub = description;
  // Messages name the part once: an attachment's description (a rig of one
  // part, bake_channels.cpp) already names it in its file.
  const std::string label = ": part '" + part.name + "'";
  const bool named = description.file.size() >= label.size() &&
                     description.file.compare(description.file.size() - label.size(), label.size(), label) == 0;
  sub.file = named ? description.file : description.file + label;
  sub.parts.clear();
  sub.glue.clear();
  sub.paths.clear();
  sub.warnings.clear();
  sub.triangles = part.triangles;
  sub.poses = part.poses;
  const bool drawn = !part.poses.empty() && part.poses[0].drawn;
  for (std::size_t g = 0; g < description.glue.size(); ++g) {
    const GlueDescription& glue = description.glue[g];
    if (!drawn || !Involves(glue, p)) continue;
    if (glue.at.size() != sub.poses.size())
      throw BakeError(description.file, GlueLabel(description, g) + ": part '" + part.name +
                                            "' is drawn: give the joint's point in every pose's drawing (one [x, y] "
                                            "per pose)");
    for (std::size_t i = 0; i < sub.poses.size(); ++i) sub.poses[i].features.push_back(glue.at[i]);
  }
  return sub;
}

JoinedParts JoinParts(const RigDescription& d) {
  std::vector<MappedPart> parts;
  for (std::size_t p = 0; p < d.parts.size(); ++p) parts.push_back(MapPart(d, p));
  CheckCanvases(d, parts);
  const std::size_t N = d.poses.size();

  // Every part's vertices, numbered part after part; joints join classes.
  std::vector<std::size_t> offset(parts.size() + 1, 0);
  for (std::size_t p = 0; p < parts.size(); ++p) offset[p + 1] = offset[p] + parts[p].meshes.poses[0].vertices.size();
  Classes classes;
  classes.parent.resize(offset.back());
  for (std::size_t v = 0; v < classes.parent.size(); ++v) classes.parent[v] = v;
  for (std::size_t g = 0; g < d.glue.size(); ++g) {
    const GlueDescription& glue = d.glue[g];
    const std::size_t a = offset[glue.part_index] + parts[glue.part_index].joint_vertex[g];
    const std::size_t b = offset[glue.to_index] + parts[glue.to_index].joint_vertex[g];
    classes.parent[classes.Find(a)] = classes.Find(b);
  }
  JoinedParts out;
  std::vector<std::size_t> id(offset.back(), SIZE_MAX), first_member;
  for (std::size_t v = 0; v < offset.back(); ++v) {
    const std::size_t root = classes.Find(v);
    if (id[root] == SIZE_MAX) id[root] = first_member.size(), first_member.push_back(v);
    id[v] = id[root];
  }
  auto part_of = [&](std::size_t v) {
    return std::size_t(std::upper_bound(offset.begin(), offset.end(), v) - offset.begin() - 1);
  };
  // The joined poses: each vertex where its first member is, uvs likewise;
  // every other member must be there too.
  PoseMeshes& meshes = out.meshes;
  double rig_size = 0;
  for (const MappedPart& part : parts) rig_size = std::max(rig_size, Size(part.meshes.poses[0].vertices));
  const double tolerance = kJointTolerance * std::max(1.0, rig_size);
  for (std::size_t i = 0; i < N; ++i) {
    PoseMesh pose;
    pose.name = d.poses[i].name;
    pose.point = d.poses[i].point;
    for (const MappedPart& part : parts)
      if (part.meshes.poses[i].canvas_size.x() > 0) {
        pose.canvas_size = part.meshes.poses[i].canvas_size;
        pose.canvas_pivot = part.meshes.poses[i].canvas_pivot;
      }
    const bool uvs = !parts[0].meshes.poses[i].uvs.empty();
    for (std::size_t v : first_member) {
      const std::size_t p = part_of(v);
      pose.vertices.push_back(parts[p].meshes.poses[i].vertices[v - offset[p]]);
      if (uvs) pose.uvs.push_back(parts[p].meshes.poses[i].uvs[v - offset[p]]);
    }
    meshes.poses.push_back(std::move(pose));
  }
  for (std::size_t g = 0; g < d.glue.size(); ++g) {
    const GlueDescription& glue = d.glue[g];
    const std::uint32_t a = parts[glue.part_index].joint_vertex[g], b = parts[glue.to_index].joint_vertex[g];
    for (std::size_t i = 0; i < N; ++i) {
      const Eigen::Vector2d& pa = parts[glue.part_index].meshes.poses[i].vertices[a];
      const Eigen::Vector2d& pb = parts[glue.to_index].meshes.poses[i].vertices[b];
      const bool drawn = d.parts[glue.part_index].poses[i].drawn || d.parts[glue.to_index].poses[i].drawn;
      if (!((pa - pb).norm() <= (drawn ? std::max(tolerance, kDrawnJointTolerance) : tolerance)))
        throw BakeError(d.file, GlueLabel(d, g) + ": in " + PoseLabel(d.poses[i].name, i) + " the joint is at " +
                                    PointText(pa) + " on part '" + glue.part + "' but at " + PointText(pb) +
                                    " on part '" + glue.to + "': a joint is one point in every pose");
    }
    out.joints.push_back(std::uint32_t(id[offset[glue.part_index] + a]));
  }
  for (std::size_t p = 0; p < parts.size(); ++p) {
    MeshPart part;
    part.name = d.parts[p].name;
    part.order = d.parts[p].order;
    part.pose_orders = d.parts[p].pose_orders;
    part.first_triangle = std::uint32_t(meshes.triangles.size());
    for (const auto& t : parts[p].meshes.triangles)
      meshes.triangles.push_back({std::uint32_t(id[offset[p] + t[0]]), std::uint32_t(id[offset[p] + t[1]]),
                                  std::uint32_t(id[offset[p] + t[2]])});
    part.triangle_count = std::uint32_t(meshes.triangles.size()) - part.first_triangle;
    for (std::size_t i = 0; i < N; ++i) part.images.push_back(parts[p].meshes.poses[i].image);
    meshes.parts.push_back(std::move(part));
    AddReport(parts[p].report, &out.report);
  }
  out.report.vertices = meshes.poses[0].vertices.size();
  out.report.triangles = meshes.triangles.size();
  out.report.registered = d.mapping.registration;
  out.report.stretch_cost = d.mapping.stretch_cost;
  return out;
}

}  // namespace posemorph::bake
