// SPDX-License-Identifier: MIT
// What the C API's draw-list calls share (pm_draw_lists in c_api_frames.cpp,
// pm_character_draw_lists in c_api_character.cpp): the options onto the
// job, a DrawList as the C struct, a pm_transform as the C++ one.
#pragma once
#include <cstddef>
#include <cstdint>

#include "posemorph/draw_list.h"
#include "posemorph/posemorph.h"

namespace posemorph::c_api {

inline void SetDrawOptions(const pm_draw_options& o, std::size_t count, const Rig& rig, DrawListJob* job) {
  job->sigma = o.sigma;
  job->limit_weights = o.limit_weights != 0;
  job->interpolation = o.linear ? Interpolation::kLinear : Interpolation::kRigid;
  job->max_drawings = o.max_drawings;
  if (o.colours) job->colours = {reinterpret_cast<const Colour*>(o.colours), count};
  if (o.part_opacities) job->part_opacities = {o.part_opacities, count * rig.part_count()};
}

inline Transform2D TransformFromC(const pm_transform& c) {
  Transform2D t;
  t.a = c.a, t.b = c.b, t.c = c.c, t.d = c.d, t.tx = c.tx, t.ty = c.ty;
  return t;
}

// A DrawList as the C struct; vertex_count from the list's own rig.
inline void DrawListToC(const DrawList& list, std::uint32_t vertex_count, pm_draw_list* d) {
  d->positions = list.positions.data;
  d->indices = list.indices.data;
  d->vertex_count = vertex_count;
  d->index_count = std::uint32_t(list.indices.size);
  d->drawing_count = list.drawing_count;
  for (std::uint32_t i = 0; i < PM_MAX_BLEND_DRAWINGS; ++i)
    d->drawings[i] = {list.drawings[i].pose, list.drawings[i].weight, list.drawings[i].uvs};
  const Transform2D& t = list.transform;
  d->transform = {t.a, t.b, t.c, t.d, t.tx, t.ty};
  d->mirrored = list.mirrored ? 1 : 0;
  d->parts = list.parts.data;
  d->part_count = std::uint32_t(list.parts.size);
  d->colour = {list.colour.r, list.colour.g, list.colour.b, list.colour.a};
  for (std::uint32_t p = 0; p < PM_MAX_PARTS; ++p) d->part_opacity[p] = list.part_opacity[p];
}

}  // namespace posemorph::c_api
