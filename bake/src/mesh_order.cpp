// SPDX-License-Identifier: MIT
// A drawn mesh numbered for the compact encoding (mesh_order.h): a
// depth-first walk over the triangles across shared edges.
#include "posemorph/bake/mesh_order.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <limits>

#include "posemorph/bake/map_drawings.h"

namespace posemorph::bake {
namespace {

constexpr std::uint32_t kUnseen = std::numeric_limits<std::uint32_t>::max();

}  // namespace

void WalkOrder(const Triangles& triangles, std::size_t vertex_count, std::vector<std::uint32_t>* vertex_order,
               Triangles* triangles_out) {
  const std::vector<std::vector<std::uint32_t>> neighbours = EdgeNeighbours(triangles);
  // Depth first from triangle 0 (then from the first triangle not reached),
  // each triangle's neighbours in EdgeNeighbours' order.
  std::vector<std::uint32_t> order;
  order.reserve(triangles.size());
  std::vector<char> visited(triangles.size(), 0);
  std::vector<std::uint32_t> stack;
  for (std::uint32_t root = 0; root < triangles.size(); ++root) {
    if (visited[root]) continue;
    stack.push_back(root);
    while (!stack.empty()) {
      const std::uint32_t t = stack.back();
      stack.pop_back();
      if (visited[t]) continue;
      visited[t] = 1;
      order.push_back(t);
      for (auto u = neighbours[t].rbegin(); u != neighbours[t].rend(); ++u)
        if (!visited[*u]) stack.push_back(*u);
    }
  }
  std::vector<std::uint32_t> number(vertex_count, kUnseen);
  vertex_order->clear();
  triangles_out->clear();
  std::array<std::uint32_t, 3> previous{0, 0, 0};
  for (std::uint32_t t : order) {
    std::array<std::uint32_t, 3> renumbered{};
    for (std::size_t c = 0; c < 3; ++c) {
      std::uint32_t& n = number[triangles[t][c]];
      if (n == kUnseen) n = std::uint32_t(vertex_order->size()), vertex_order->push_back(triangles[t][c]);
      renumbered[c] = n;
    }
    // The rotation nearest the triangle before (the first of a tie).
    std::array<std::uint32_t, 3> best{};
    std::int64_t best_distance = std::numeric_limits<std::int64_t>::max();
    for (std::size_t r = 0; r < 3; ++r) {
      const std::array<std::uint32_t, 3> turned{renumbered[r], renumbered[(r + 1) % 3], renumbered[(r + 2) % 3]};
      std::int64_t distance = 0;
      for (std::size_t c = 0; c < 3; ++c) distance += std::llabs(std::int64_t(turned[c]) - std::int64_t(previous[c]));
      if (distance < best_distance) best = turned, best_distance = distance;
    }
    triangles_out->push_back(best);
    previous = best;
  }
  for (std::uint32_t v = 0; v < vertex_count; ++v)
    if (number[v] == kUnseen) vertex_order->push_back(v);
}

void OrderForCoding(MappedDrawings* drawings) {
  if (drawings->triangles.empty() || drawings->meshes.empty()) return;
  const std::size_t V = drawings->meshes[0].vertices.size();
  std::vector<std::uint32_t> vertex_order;
  Triangles triangles;
  WalkOrder(drawings->triangles, V, &vertex_order, &triangles);
  std::vector<std::uint32_t> number(V);
  for (std::uint32_t n = 0; n < V; ++n) number[vertex_order[n]] = n;
  drawings->triangles = std::move(triangles);
  for (PoseMesh& mesh : drawings->meshes) {
    Points vertices(V);
    for (std::size_t n = 0; n < V; ++n) vertices[n] = mesh.vertices[vertex_order[n]];
    mesh.vertices = std::move(vertices);
    if (mesh.uvs.size() == V) {
      std::vector<Eigen::Vector2f> uvs(V);
      for (std::size_t n = 0; n < V; ++n) uvs[n] = mesh.uvs[vertex_order[n]];
      mesh.uvs = std::move(uvs);
    }
  }
  for (std::uint32_t& f : drawings->feature_vertices) f = number[f];
}

}  // namespace posemorph::bake
