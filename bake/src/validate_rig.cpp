// SPDX-License-Identifier: MIT
// Everything the math needs from the input, checked before any of it runs.
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <sstream>

#include "posemorph/bake/error.h"
#include "posemorph/bake/validate_rig.h"
#include "posemorph/bake/triangle_math.h"
#include "posemorph/rig_format.h"

namespace posemorph::bake {
namespace {

std::uint32_t FindRoot(std::vector<std::uint32_t>& parent, std::uint32_t v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

std::string CheckCounts(const PoseMeshes& rig) {
  const std::size_t N = rig.poses.size();
  if (N < 2) return "a rig needs at least 2 poses, this one has " + std::to_string(N);
  if (N > format::kMaxPoses)
    return "at most " + std::to_string(format::kMaxPoses) + " poses are supported, got " + std::to_string(N);
  const std::size_t V = rig.poses[0].vertices.size();
  if (V < 3)
    return PoseLabel(rig.poses[0].name, 0) + " has " + std::to_string(V) + " vertices; a mesh needs at least 3";
  if (V > format::kMaxVertices) return "too many vertices: " + std::to_string(V);
  if (std::uint64_t(V) * N > kMaxBakeVertexPoses)
    return std::to_string(V) + " vertices in " + std::to_string(N) + " poses (" + std::to_string(std::uint64_t(V) * N) +
           " vertex-poses), above the bake's bound of " + std::to_string(kMaxBakeVertexPoses) +
           ": a bake that size would run for minutes and take gigabytes (90,000 vertices in 3 poses take about "
           "10 s and 800 MB)";
  if (rig.triangles.empty()) return "the triangle list is empty";
  if (rig.triangles.size() > format::kMaxTriangles)
    return "too many triangles: " + std::to_string(rig.triangles.size());
  for (std::size_t i = 0; i < N; ++i) {
    const PoseMesh& p = rig.poses[i];
    if (p.vertices.size() != V)
      return PoseLabel(rig.poses[i].name, i) + " has " + std::to_string(p.vertices.size()) + " vertices, pose 0 has " +
             std::to_string(V);
    if (!p.uvs.empty() && p.uvs.size() != V)
      return PoseLabel(rig.poses[i].name, i) + " has " + std::to_string(p.uvs.size()) + " uvs for " +
             std::to_string(V) + " vertices";
    for (std::size_t j = 0; j < i; ++j)
      if (rig.poses[j].name == p.name)
        return PoseLabel(rig.poses[i].name, i) + ": the name is used by pose " + std::to_string(j) + " too";
  }
  const bool any_uvs =
      std::any_of(rig.poses.begin(), rig.poses.end(), [](const PoseMesh& p) { return !p.uvs.empty(); });
  if (any_uvs)
    for (std::size_t i = 0; i < N; ++i)
      if (rig.poses[i].uvs.empty())
        return PoseLabel(rig.poses[i].name, i) + " has no uvs, but other poses do; give all or none";
  return {};
}

std::string CheckIndices(const PoseMeshes& rig) {
  const std::size_t V = rig.poses[0].vertices.size();
  // Indices.
  std::set<std::array<std::uint32_t, 3>> seen;
  for (std::size_t t = 0; t < rig.triangles.size(); ++t) {
    const auto& tri = rig.triangles[t];
    for (std::uint32_t v : tri)
      if (v >= V)
        return "triangle " + std::to_string(t) + " uses vertex " + std::to_string(v) + ", but there are only " +
               std::to_string(V);
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
      return "triangle " + std::to_string(t) + " repeats a vertex (" + std::to_string(tri[0]) + ", " +
             std::to_string(tri[1]) + ", " + std::to_string(tri[2]) + ")";
    std::array<std::uint32_t, 3> key = tri;
    std::sort(key.begin(), key.end());
    if (!seen.insert(key).second) return "triangle " + std::to_string(t) + " appears twice in the triangle list";
  }
  return {};
}

std::string CheckManifold(const PoseMeshes& rig) {
  // Manifold: an edge borders at most two triangles (a third would overlap
  // one of them, and the ARAP energy would count that area twice).
  {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::size_t>> edge_triangles;
    for (std::size_t t = 0; t < rig.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        std::uint32_t a = rig.triangles[t][k], b = rig.triangles[t][(k + 1) % 3];
        if (a > b) std::swap(a, b);
        std::vector<std::size_t>& list = edge_triangles[{a, b}];
        list.push_back(t);
        if (list.size() > 2)
          return "the mesh is not manifold: edge (" + std::to_string(a) + ", " + std::to_string(b) +
                 ") borders triangles " + std::to_string(list[0]) + ", " + std::to_string(list[1]) + " and " +
                 std::to_string(list[2]) + " (an edge borders at most two)";
      }
  }
  return {};
}

std::string CheckConnected(const PoseMeshes& rig) {
  const std::size_t V = rig.poses[0].vertices.size();
  // Every vertex in a triangle, all triangles in one vertex-connected part:
  // otherwise K (one pinned vertex) is singular.
  std::vector<std::uint32_t> parent(V);
  std::iota(parent.begin(), parent.end(), 0u);
  std::vector<char> used(V, 0);
  for (const auto& tri : rig.triangles)
    for (int k = 0; k < 3; ++k) {
      used[tri[k]] = 1;
      parent[FindRoot(parent, tri[k])] = FindRoot(parent, tri[(k + 1) % 3]);
    }
  for (std::size_t v = 0; v < V; ++v) {
    if (!used[v]) return "vertex " + std::to_string(v) + " is used by no triangle";
    if (FindRoot(parent, std::uint32_t(v)) != FindRoot(parent, 0))
      return "the mesh falls apart: vertex " + std::to_string(v) +
             " is not connected to vertex 0 (a rig is one connected mesh)";
  }
  return {};
}

std::string CheckFinite(const PoseMeshes& rig) {
  const std::size_t N = rig.poses.size();
  const std::size_t V = rig.poses[0].vertices.size();
  // Finite numbers (the reader checks JSON numbers; this also covers rigs built in code).
  for (std::size_t i = 0; i < N; ++i) {
    const PoseMesh& p = rig.poses[i];
    if (!p.point.allFinite()) return PoseLabel(rig.poses[i].name, i) + ": pose-space point is not finite";
    for (std::size_t v = 0; v < V; ++v)
      if (!p.vertices[v].allFinite())
        return PoseLabel(rig.poses[i].name, i) + ": vertex " + std::to_string(v) + " is not finite";
    for (std::size_t v = 0; v < p.uvs.size(); ++v)
      if (!p.uvs[v].allFinite())
        return PoseLabel(rig.poses[i].name, i) + ": uv " + std::to_string(v) + " is not finite";
  }
  return {};
}

std::string CheckAreas(const PoseMeshes& rig) {
  const std::size_t N = rig.poses.size();
  // Orientation (OrientTriangles made pose 0 counter-clockwise): every
  // triangle must keep a clearly positive area in every pose.
  for (std::size_t i = 0; i < N; ++i) {
    const Points& q = rig.poses[i].vertices;
    Eigen::AlignedBox2d box;
    for (const auto& v : q) box.extend(v);
    const double diag = box.diagonal().norm();
    if (!(diag > 0)) return PoseLabel(rig.poses[i].name, i) + ": all vertices coincide";
    const double min_area = 1e-10 * diag * diag;
    for (std::size_t t = 0; t < rig.triangles.size(); ++t) {
      const double a = SignedArea(q, rig.triangles[t]);
      if (std::abs(a) <= min_area) {
        std::ostringstream s;
        s << PoseLabel(rig.poses[i].name, i) << ": triangle " << t << " is degenerate (area " << a << ")";
        return s.str();
      }
      if (a < 0) {
        std::ostringstream s;
        s << PoseLabel(rig.poses[i].name, i) << ": triangle " << t << " is flipped (signed area " << a
          << ", pose 0 is counter-clockwise)";
        return s.str();
      }
    }
  }
  return {};
}

std::string CheckPosePoints(const PoseMeshes& rig) {
  const std::size_t N = rig.poses.size();
  // Pose points: representable (the pose-space grid is built from their
  // spread: 1e308 apart overflows it, 5e-324 apart underflows it), and distinct
  // (the grid check later also needs them in distinct cells).
  Eigen::AlignedBox2d point_box;
  for (std::size_t i = 0; i < N; ++i) {
    const Eigen::Vector2d& p = rig.poses[i].point;
    if (!(std::fabs(p.x()) <= format::kMaxPathValue) || !(std::fabs(p.y()) <= format::kMaxPathValue)) {
      std::ostringstream s;
      s << PoseLabel(rig.poses[i].name, i) << ": pose-space point (" << p.x() << ", " << p.y()
        << ") lies beyond +-1e12";
      return s.str();
    }
    point_box.extend(p);
  }
  for (std::size_t i = 0; i < N; ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (rig.poses[i].point == rig.poses[j].point)
        return PoseLabel(rig.poses[i].name, i) + " and " + PoseLabel(rig.poses[j].name, j) +
               " share the pose-space point (" + std::to_string(rig.poses[i].point.x()) + ", " +
               std::to_string(rig.poses[i].point.y()) + ")";
  if (!(point_box.sizes().maxCoeff() >= 1e-6)) {
    std::ostringstream s;
    s << "the pose-space points span only " << point_box.sizes().maxCoeff()
      << "; they must span at least 1e-6 (pose-space units are yours: 1 is a good scale)";
    return s.str();
  }
  return {};
}

std::string CheckFormatLimits(const PoseMeshes& rig, const std::vector<PathDescription>& paths) {
  const std::size_t N = rig.poses.size();
  // The rig format's own limits (runtime/include/posemorph/rig_format.h),
  // checked here so a description beyond them is refused by name instead of
  // baking a rig the runtime would not load.
  if (paths.size() > format::kMaxPaths)
    return "paths: " + std::to_string(paths.size()) + " paths, more than the rig format's limit of " +
           std::to_string(format::kMaxPaths);
  std::size_t keys = 0;
  for (const PathDescription& path : paths) keys += path.keys.size();
  if (keys > format::kMaxPathKeys)
    return "paths: " + std::to_string(keys) + " keys in all, more than the rig format's limit of " +
           std::to_string(format::kMaxPathKeys);
  std::size_t events = 0;
  for (const PathDescription& path : paths) events += path.events.size();
  if (events > format::kMaxEvents)
    return "paths: " + std::to_string(events) + " events in all, more than the rig format's limit of " +
           std::to_string(format::kMaxEvents);
  std::size_t string_bytes = 0, longest = 0;
  std::string longest_name;
  auto count = [&](const std::string& text, const std::string& what) {
    string_bytes += 4 + text.size();
    if (text.size() > longest) longest = text.size(), longest_name = what;
  };
  for (std::size_t i = 0; i < N; ++i) {
    count(rig.poses[i].name, PoseLabel(rig.poses[i].name, i) + "'s name");
    count(rig.poses[i].image, PoseLabel(rig.poses[i].name, i) + "'s image reference");
  }
  for (std::size_t k = 0; k < paths.size(); ++k) count(paths[k].name, "paths[" + std::to_string(k) + "].name");
  for (std::size_t k = 0; k < paths.size(); ++k)
    for (const auto& event : paths[k].events)
      count(event.second, "paths[" + std::to_string(k) + "]'s event '" + event.second.substr(0, 32) + "'");
  for (const MeshPart& part : rig.parts) {
    count(part.name, "part '" + part.name + "''s name");
    for (std::size_t i = 0; i < part.images.size(); ++i)
      count(part.images[i], "part '" + part.name + "''s image reference in " + PoseLabel(rig.poses[i].name, i));
  }
  if (string_bytes > format::kMaxStringBytes)
    return "pose names, image references and path names take " + std::to_string(string_bytes) +
           " bytes, more than the rig format's limit of " + std::to_string(format::kMaxStringBytes) +
           " (the longest, " + longest_name + ", has " + std::to_string(longest) + ")";
  return {};
}

}  // namespace

std::optional<std::string> ValidateRig(const PoseMeshes& rig, const std::vector<PathDescription>& paths) {
  // In this order: each check may assume the ones before it passed.
  for (std::string (*check)(const PoseMeshes&) :
       {CheckCounts, CheckIndices, CheckManifold, CheckConnected, CheckFinite, CheckAreas, CheckPosePoints}) {
    std::string problem = check(rig);
    if (!problem.empty()) return problem;
  }
  std::string problem = CheckFormatLimits(rig, paths);
  if (!problem.empty()) return problem;
  return std::nullopt;
}

}  // namespace posemorph::bake
