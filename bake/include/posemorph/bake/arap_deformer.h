// SPDX-License-Identifier: MIT
// As-rigid-as-possible shape manipulation (Igarashi, Moscovich, Hughes 2005):
// drag handle vertices of a triangle mesh and get the other vertices back,
// in two least-squares steps whose matrices depend only on the mesh and on
// which vertices are handles, so they are factored once per handle set and
// every drag is back-substitution.
//   1. similarity: each vertex should stay where its triangle's other two
//      vertices, rotated and uniformly scaled, put it;
//   2. scale adjustment: fit each original triangle rigidly to the step-1
//      result, then find positions whose edges best match the fitted ones.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "posemorph/bake/triangle_math.h"

namespace posemorph::bake {

class ArapDeformer {
 public:
  // `rest` must be a valid mesh (every triangle positive); `handles` are >= 2
  // distinct vertex indices. Throws BakeError (with `file`) otherwise.
  ArapDeformer(Points rest, Triangles triangles, std::vector<std::uint32_t> handles, const std::string& file = "");
  ~ArapDeformer();
  ArapDeformer(ArapDeformer&&) noexcept;
  ArapDeformer& operator=(ArapDeformer&&) noexcept;

  // Positions for the handles at `targets` (one per handle, in order).
  // `similarity`, if given, receives the step-1 result alone.
  void Deform(const std::vector<Eigen::Vector2d>& targets, Points* out, Points* similarity = nullptr) const;

  const std::vector<std::uint32_t>& handles() const { return handles_; }

 private:
  struct Factors;
  Points rest_;
  Triangles triangles_;
  std::vector<std::uint32_t> handles_;
  std::unique_ptr<Factors> factors_;
};

// The vertex a handle placed at `point` grabs: the nearest vertex of the
// triangle containing the point (or of the nearest triangle, if the point is
// within `tolerance` of the mesh). Returns false if the point is farther away.
bool HandleVertex(const Points& mesh, const Triangles& triangles, const Eigen::Vector2d& point, double tolerance,
                  std::uint32_t* vertex);

}  // namespace posemorph::bake
