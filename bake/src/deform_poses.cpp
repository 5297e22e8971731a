// SPDX-License-Identifier: MIT
// Poses made by dragging handles on another pose's mesh: they share its
// connectivity by construction, and its drawing and uvs.
#include <cmath>
#include <sstream>

#include "posemorph/bake/arap_deformer.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/deform_poses.h"

namespace posemorph::bake {

namespace {

// Pose i of the rig: its source pose `from` with the handles dragged (ARAP),
// checked: handles on distinct vertices of the mesh, no triangle flipped.
void DeformPose(const RigDescription& rig, std::size_t i, const PoseMesh& from, const Triangles& triangles,
                PoseMesh& pose) {
  auto fail = [&](const std::string& problem) {
    throw BakeError(rig.file, PoseLabel(rig.poses[i].name, i) + ": " + problem);
  };
  const DeformDescription& deform = rig.poses[i].deform;
  const Points& mesh = from.vertices;
  const std::size_t V = mesh.size();
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (std::uint32_t v : triangles[t])
      if (v >= V)
        fail("its source '" + from.name + "' has " + std::to_string(V) + " vertices, triangle " + std::to_string(t) +
             " uses vertex " + std::to_string(v));
  Eigen::AlignedBox2d box;
  for (const auto& p : mesh) box.extend(p);
  const double size = box.diagonal().norm();

  std::vector<std::uint32_t> handles;
  std::vector<Eigen::Vector2d> targets;
  for (std::size_t h = 0; h < deform.handles.size(); ++h) {
    const HandleDescription& hd = deform.handles[h];
    std::uint32_t v = hd.vertex;
    if (hd.by_vertex) {
      if (v >= V)
        fail("handle " + std::to_string(h) + " names vertex " + std::to_string(v) + ", but '" + from.name + "' has " +
             std::to_string(V));
    } else if (!HandleVertex(mesh, triangles, hd.at, 1e-3 * size, &v)) {
      std::ostringstream s;
      s << "handle " << h << " at (" << hd.at.x() << ", " << hd.at.y() << ") lies outside the mesh of '" << from.name
        << "'";
      fail(s.str());
    }
    for (std::size_t k = 0; k < handles.size(); ++k)
      if (handles[k] == v)
        fail("handles " + std::to_string(k) + " and " + std::to_string(h) + " coincide (both grab vertex " +
             std::to_string(v) + ")");
    handles.push_back(v);
    targets.push_back(hd.to);
  }
  if (handles.size() < 2)
    fail("a deformation needs at least 2 handles, this one has " + std::to_string(handles.size()));

  try {
    ArapDeformer(mesh, triangles, handles).Deform(targets, &pose.vertices);
  } catch (const BakeError& e) {
    fail(e.what());
  }
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const double before = SignedArea(mesh, triangles[t]), after = SignedArea(pose.vertices, triangles[t]);
    if (before > 0 && !(after > 1e-10 * size * size)) {
      std::ostringstream s;
      s << "the deformation flips triangle " << t << " (signed area " << after << " from " << before
        << "); drag its handles less far or add handles";
      fail(s.str());
    }
  }
  pose.image = from.image;
  pose.uvs = from.uvs;
  pose.canvas_size = from.canvas_size;
  pose.canvas_pivot = from.canvas_pivot;
}

}  // namespace

PoseMeshes DeformPoses(const RigDescription& rig, const MappedDrawings& drawings) {
  PoseMeshes meshes = GivenPoseMeshes(rig);
  if (drawings.report.mapped) {
    meshes.triangles = drawings.triangles;
    for (std::size_t k = 0; k < drawings.poses.size(); ++k) meshes.poses[drawings.poses[k]] = drawings.meshes[k];
  }
  const std::size_t N = rig.poses.size();
  auto fail = [&](std::size_t i, const std::string& problem) {
    throw BakeError(rig.file, PoseLabel(rig.poses[i].name, i) + ": " + problem);
  };

  std::vector<char> done(N, 0);
  std::size_t remaining = 0;
  for (std::size_t i = 0; i < N; ++i) {
    done[i] = !rig.poses[i].deformed;
    remaining += rig.poses[i].deformed;
  }
  if (remaining == N && N > 0)
    throw BakeError(rig.file, "every pose is made by deformation; at least one needs vertices");
  if (remaining == 0) return meshes;

  std::vector<std::size_t> source(N, 0);
  for (std::size_t i = 0; i < N; ++i) {
    if (!rig.poses[i].deformed) continue;
    bool found = false;
    for (std::size_t j = 0; j < N && !found; ++j)
      if (rig.poses[j].name == rig.poses[i].deform.from) source[i] = j, found = true;
    if (!found) fail(i, "deforms pose '" + rig.poses[i].deform.from + "', which the rig does not have");
    if (source[i] == i) fail(i, "deforms itself");
  }

  // Each pass resolves the poses whose source is ready; a pass that resolves
  // nothing means the rest form a cycle.
  while (remaining > 0) {
    bool progress = false;
    for (std::size_t i = 0; i < N; ++i) {
      if (done[i] || !done[source[i]]) continue;
      DeformPose(rig, i, meshes.poses[source[i]], meshes.triangles, meshes.poses[i]);
      done[i] = 1;
      --remaining;
      progress = true;
    }
    if (!progress)
      for (std::size_t i = 0; i < N; ++i)
        if (!done[i])
          fail(i, "deformation sources form a cycle ('" + rig.poses[i].name + "' <- '" + rig.poses[i].deform.from +
                      "' <- ...)");
  }
  return meshes;
}

PoseMeshes ResolvePoseMeshes(const RigDescription& description) {
  return DeformPoses(description, MapDrawings(description));
}

}  // namespace posemorph::bake
