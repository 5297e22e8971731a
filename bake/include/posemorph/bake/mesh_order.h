// SPDX-License-Identifier: MIT
// The numbering of a drawn mesh, made for the compact encoding. The mapping
// numbers vertices and triangles as it makes them (each split appends), so
// consecutive triangles share nothing and a triangle's vertex indices, coded
// as differences from the previous triangle's (QTRI, runtime/FORMAT.md),
// cost about as much as writing them out: 28-29 bits a triangle on Pip's
// mesh and on a 60 x 80 sprite's. Numbered in the order of a depth-first
// walk over the triangles across shared edges (vertices in the order the
// walk first meets them, each triangle's corners rotated, its orientation
// kept, to lie nearest the triangle before), they cost about half. The
// mesh, its poses and its features are the same; only the numbers change.
#pragma once

#include <cstdint>
#include <vector>

#include "posemorph/bake/triangle_math.h"

namespace posemorph::bake {

// The walk's order: *vertex_order lists the old vertex ids in their new
// order (every vertex of `triangles` first, then any no triangle uses, in
// their old order), *triangles_out the triangles in the new numbering and
// order. `vertex_count`: the vertices' number (every index is below it).
void WalkOrder(const Triangles& triangles, std::size_t vertex_count, std::vector<std::uint32_t>* vertex_order,
               Triangles* triangles_out);

struct MappedDrawings;
// The drawn meshes renumbered in WalkOrder: triangles, each pose's vertices
// and uvs, and the features' vertex ids.
void OrderForCoding(MappedDrawings* drawings);

}  // namespace posemorph::bake
