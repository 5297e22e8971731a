// SPDX-License-Identifier: MIT
// The C API's whole character (posemorph/posemorph_character.h): every
// list of a character (the body, each attachment) answered alike, every
// channel's names, and draw lists with the attachments merged back to front.
#include <cstddef>
#include <cstdint>
#include <initializer_list>

#include "c_api_draw.h"
#include "c_api_internal.h"
#include "draw_list_internal.h"
#include "posemorph/draw_list.h"
#include "posemorph/posemorph.h"

using namespace posemorph::c_api;  // NOLINT(google-build-using-namespace): the C API's own helpers
using posemorph::Span;

namespace {

// List `list` of a character: the rig itself (0) or attachment list - 1's rig.
const posemorph::Rig* ListRig(const pm_rig* rig, uint32_t list) {
  if (!rig || !rig->rig.loaded()) return nullptr;
  if (list == 0) return &rig->rig;
  return list - 1 < rig->rig.attachment_count() ? rig->rig.attachment(list - 1).rig : nullptr;
}

const posemorph::Rig* ChannelRig(const pm_rig* rig, uint32_t channel) {
  return rig ? rig->rig.channel_rig(channel) : nullptr;
}

}  // namespace

extern "C" {

uint32_t pm_character_list_count(const pm_rig* rig) {
  return rig && rig->rig.loaded() ? 1 + rig->rig.attachment_count() : 0;
}

int pm_character_list(const pm_rig* rig, uint32_t list, pm_list_info* out) {
  const posemorph::Rig* r = ListRig(rig, list);
  if (!r || !out) return PM_ERROR_INVALID_ARGUMENT;
  *out = pm_list_info{r->vertex_count(), r->triangle_count(), r->pose_count(), r->part_count(),
                      list == 0 ? 0u : rig->rig.attachment(list - 1).channel};
  return PM_OK;
}

int pm_character_part(const pm_rig* rig, uint32_t list, uint32_t part, pm_part* out) {
  const posemorph::Rig* r = ListRig(rig, list);
  if (!r || !out || part >= r->part_count()) return PM_ERROR_INVALID_ARGUMENT;
  const posemorph::PartView view = r->part(part);
  *out = pm_part{view.first_triangle, view.triangle_count, view.draw_order};
  return PM_OK;
}

int pm_character_part_name(const pm_rig* rig, uint32_t list, uint32_t part, char* out, size_t capacity,
                           size_t* length) {
  const posemorph::Rig* r = ListRig(rig, list);
  const bool valid = r && part < r->part_count();
  return CopyString(valid ? r->part(part).name : posemorph::StringView{}, valid, out, capacity, length);
}

int pm_character_part_image(const pm_rig* rig, uint32_t list, uint32_t part, uint32_t pose, char* out, size_t capacity,
                            size_t* length) {
  const posemorph::Rig* r = ListRig(rig, list);
  const bool valid = r && part < r->part_count() && pose < r->pose_count();
  return CopyString(valid ? r->part_image(part, pose) : posemorph::StringView{}, valid, out, capacity, length);
}

int pm_character_canvas(const pm_rig* rig, uint32_t list, uint32_t pose, pm_canvas* out) {
  const posemorph::Rig* r = ListRig(rig, list);
  if (!r || !out || pose >= r->pose_count()) return PM_ERROR_INVALID_ARGUMENT;
  const posemorph::DrawingCanvas c = r->pose_canvas(pose);
  *out = pm_canvas{c.width, c.height, c.pivot_x, c.pivot_y};
  return PM_OK;
}

int pm_character_texture_filter(const pm_rig* rig, uint32_t list) {
  const posemorph::Rig* r = ListRig(rig, list);
  return r && r->texture_filter() == posemorph::TextureFilter::kNearest ? PM_FILTER_NEAREST : PM_FILTER_LINEAR;
}

// Texture pages (format 1.12): Rig::page and Rig::part_region per list.
int pm_rig_has_atlas(const pm_rig* rig) { return rig && rig->rig.has_atlas() ? 1 : 0; }

uint32_t pm_character_page_count(const pm_rig* rig, uint32_t list) {
  const posemorph::Rig* r = ListRig(rig, list);
  return r ? r->page_count() : 0;
}

int pm_character_page(const pm_rig* rig, uint32_t list, uint32_t page, pm_page* out) {
  const posemorph::Rig* r = ListRig(rig, list);
  if (!r || !out || page >= r->page_count()) return PM_ERROR_INVALID_ARGUMENT;
  const posemorph::TexturePage p = r->page(page);
  *out = pm_page{p.width, p.height, p.atlas ? 1 : 0, p.premultiplied ? 1 : 0};
  return PM_OK;
}

int pm_character_page_name(const pm_rig* rig, uint32_t list, uint32_t page, char* out, size_t capacity,
                           size_t* length) {
  const posemorph::Rig* r = ListRig(rig, list);
  return CopyString(r ? r->page(page).name : posemorph::StringView{}, r && page < r->page_count(), out, capacity,
                    length);
}

int pm_character_part_region(const pm_rig* rig, uint32_t list, uint32_t part, uint32_t pose, pm_region* out) {
  const posemorph::Rig* r = ListRig(rig, list);
  if (!r || !out || part >= r->part_count() || pose >= r->pose_count()) return PM_ERROR_INVALID_ARGUMENT;
  const posemorph::TextureRegion g = r->part_region(part, pose);
  *out = pm_region{g.page, g.scale_u, g.offset_u, g.scale_v, g.offset_v, g.x, g.y, g.width, g.height};
  return PM_OK;
}

int pm_channel_pose_name(const pm_rig* rig, uint32_t channel, uint32_t pose, char* out, size_t capacity,
                         size_t* length) {
  const posemorph::Rig* c = ChannelRig(rig, channel);
  const bool valid = c && pose < c->pose_count();
  return CopyString(valid ? c->pose_name(pose) : posemorph::StringView{}, valid, out, capacity, length);
}

uint32_t pm_channel_path_count(const pm_rig* rig, uint32_t channel) {
  const posemorph::Rig* c = ChannelRig(rig, channel);
  return c ? c->path_count() : 0;
}

int pm_channel_path_name(const pm_rig* rig, uint32_t channel, uint32_t path, char* out, size_t capacity,
                         size_t* length) {
  const posemorph::Rig* c = ChannelRig(rig, channel);
  const bool valid = c && path < c->path_count();
  return CopyString(valid ? c->path(path).name : posemorph::StringView{}, valid, out, capacity, length);
}

int pm_channel_default_sigma(const pm_rig* rig, uint32_t channel, double* out) {
  const posemorph::Rig* c = ChannelRig(rig, channel);
  if (!c || !out) return PM_ERROR_INVALID_ARGUMENT;
  *out = c->default_sigma();
  return PM_OK;
}

int pm_rig_placement(const pm_rig* rig, double* anchor_x, double* anchor_y, int* facing_left) {
  if (!rig || !rig->rig.loaded() || !anchor_x || !anchor_y || !facing_left) return PM_ERROR_INVALID_ARGUMENT;
  *anchor_x = rig->rig.anchor_x(), *anchor_y = rig->rig.anchor_y(), *facing_left = rig->rig.facing_left() ? 1 : 0;
  return PM_OK;
}

void pm_transform_place(const pm_rig* rig, double x, double y, double radians, double scale, int face_left,
                        pm_transform* out) {
  if (!out) return;
  posemorph::Transform2D t;
  if (rig && rig->rig.loaded()) t = posemorph::Transform2D::Place(rig->rig, x, y, radians, scale, face_left != 0);
  *out = {t.a, t.b, t.c, t.d, t.tx, t.ty};
}

int pm_channel_pad_range(const pm_rig* rig, uint32_t channel, pm_bounds* out) {
  const posemorph::Rig* c = ChannelRig(rig, channel);
  if (!c || !out) return PM_ERROR_INVALID_ARGUMENT;
  const posemorph::PadRange r = c->pad_range();
  *out = pm_bounds{r.min_x, r.min_y, r.max_x, r.max_y};
  return PM_OK;
}

void pm_transform_compose(const pm_transform* outer, const pm_transform* inner, pm_transform* out) {
  if (!outer || !inner || !out) return;
  const posemorph::Transform2D t = posemorph::Compose(TransformFromC(*outer), TransformFromC(*inner));
  *out = {t.a, t.b, t.c, t.d, t.tx, t.ty};
}

int pm_character_buffers(const pm_rig* rig, size_t count, pm_character_buffer_sizes* out) {
  if (!rig || !out || count == 0 || count > posemorph::MaxDrawListCount(rig->rig)) return PM_ERROR_INVALID_ARGUMENT;
  const posemorph::CharacterBuffers b = posemorph::CharacterBuffers::For(rig->rig, count);
  *out = pm_character_buffer_sizes{b.workspace, b.positions, b.attached_positions, b.attached_lists};
  return PM_OK;
}

int pm_character_draw_lists(const pm_rig* rig, const pm_draw_options* options, size_t count,
                            const pm_character_inputs* inputs, double* workspace, size_t workspace_capacity,
                            float* positions, size_t positions_capacity, float* attached_positions,
                            size_t attached_positions_capacity, pm_draw_list* out, size_t out_capacity,
                            pm_draw_list* attached_out, size_t attached_out_capacity) {
  if (!rig || !inputs || !workspace || !positions || !out || count == 0 || !Aligned(workspace) || !Aligned(positions) ||
      !Aligned(attached_positions) || !Aligned(out) || !Aligned(attached_out))
    return PM_ERROR_INVALID_ARGUMENT;
  const pm_character_inputs& in = *inputs;
  for (const double* p : {in.points, in.channel_points, in.weights, in.limited_weights, in.texture_weights,
                          in.attached_weights, in.attached_limited_weights, in.attached_texture_weights})
    if (!Aligned(p)) return PM_ERROR_INVALID_ARGUMENT;
  if (!Aligned(in.transforms)) return PM_ERROR_INVALID_ARGUMENT;
  pm_draw_options o;
  pm_draw_options_default(&o);
  if (options) o = *options;
  if (!Aligned(o.colours) || !Aligned(o.part_opacities)) return PM_ERROR_INVALID_ARGUMENT;
  const posemorph::Rig& r = rig->rig;
  pm_character_buffer_sizes need{};
  if (pm_character_buffers(rig, count, &need) != PM_OK) return PM_ERROR_INVALID_ARGUMENT;
  const std::size_t A = r.attachment_count();
  if (workspace_capacity < need.workspace_doubles || positions_capacity < need.position_floats ||
      out_capacity < count ||
      (A && (!attached_positions || !attached_out || attached_positions_capacity < need.attached_position_floats ||
             attached_out_capacity < need.attached_lists)))
    return PM_ERROR_BUFFER_TOO_SMALL;
  const std::size_t n = r.pose_count(), nw = r.attached_weight_count();
  const std::size_t channel_values = 2 * std::size_t(r.channel_count() - 1);
  posemorph::DrawListJob job;
  job.rig = &r;
  job.count = count;
  if (in.points) job.points = {in.points, 2 * count};
  if (in.weights) {
    job.weights = {in.weights, count * n};
    job.limited_weights = {in.limited_weights, in.limited_weights ? count * n : 0};
    job.texture_weights = {in.texture_weights, in.texture_weights ? count * n : 0};
  }
  if (in.channel_points && channel_values) job.channel_points = {in.channel_points, count * channel_values};
  if (A && in.attached_weights) {
    job.attached_weights = {in.attached_weights, count * nw};
    job.attached_limited_weights = {in.attached_limited_weights, in.attached_limited_weights ? count * nw : 0};
    job.attached_texture_weights = {in.attached_texture_weights, in.attached_texture_weights ? count * nw : 0};
  }
  SetDrawOptions(o, count, r, &job);
  job.workspace = {workspace, need.workspace_doubles};
  job.positions = {positions, need.position_floats};
  // The attachments' lists are written as C structs (checked above).
  if (A) job.attached_positions = {attached_positions, need.attached_position_floats};
  if (!posemorph::detail::ValidDrawListInputs(job, A != 0)) return PM_ERROR_INVALID_ARGUMENT;
  double* body = A ? workspace + posemorph::detail::DrawListBodyWorkspace(r, count) : nullptr;
  const auto transform_at = [&in](std::size_t k) {
    return in.transforms ? TransformFromC(in.transforms[k]) : posemorph::Transform2D();
  };
  const bool ok = posemorph::detail::RunDrawLists(
      job, transform_at,
      [&](std::size_t k, const posemorph::DrawList& list) { DrawListToC(list, r.vertex_count(), &out[k]); }, body);
  if (!ok) return PM_ERROR_BAD_VALUE;
  if (!A) return PM_OK;
  const bool attached_ok = posemorph::detail::RunAttachedLists(
      job, body, workspace + need.workspace_doubles,
      [&](std::size_t k) {
        const pm_draw_list& b = out[k];
        return posemorph::detail::ListPlacement{TransformFromC(b.transform), b.mirrored != 0,
                                                posemorph::Colour{b.colour.r, b.colour.g, b.colour.b, b.colour.a}};
      },
      [&](std::size_t k, std::uint32_t a, const posemorph::DrawList& list) {
        DrawListToC(list, r.attachment(a).rig->vertex_count(), &attached_out[k * A + a]);
      });
  return attached_ok ? PM_OK : PM_ERROR_BAD_VALUE;
}

uint32_t pm_character_draw_steps(const pm_rig* rig, const pm_draw_list* body, const pm_draw_list* attached,
                                 pm_draw_step* out, uint32_t capacity) {
  if (!rig || !rig->rig.loaded() || !body || !Aligned(body) || !Aligned(attached) || !Aligned(out)) return 0;
  const posemorph::Rig& r = rig->rig;
  const std::uint32_t lists = 1 + (attached ? r.attachment_count() : 0);
  auto list_of = [&](std::uint32_t i) -> const pm_draw_list& { return i == 0 ? *body : attached[i - 1]; };
  // The lists are the caller's: every part and pose must be its list's.
  for (std::uint32_t i = 0; i < lists; ++i) {
    const pm_draw_list& l = list_of(i);
    const posemorph::Rig& lr = *ListRig(rig, i);
    if (l.part_count > lr.part_count() || (l.part_count && !l.parts) || !Aligned(l.parts)) return 0;
    if (l.drawing_count > PM_MAX_BLEND_DRAWINGS || (l.drawing_count && l.drawings[0].pose >= lr.pose_count())) return 0;
    for (std::uint32_t p = 0; p < l.part_count; ++p)
      if (l.parts[p] >= lr.part_count()) return 0;
  }
  return posemorph::detail::MergeDrawSteps(
      lists,
      [&](std::uint32_t i) {
        return Span<const std::uint32_t>{list_of(i).parts, list_of(i).part_count};
      },
      [&](std::uint32_t i, std::uint32_t part) {
        const pm_draw_list& l = list_of(i);
        return ListRig(rig, i)->part_draw_order(part, l.drawing_count ? l.drawings[0].pose : 0);
      },
      [&](std::uint32_t k, std::uint32_t list, std::uint32_t part) {
        if (out && k < capacity) out[k] = pm_draw_step{list, part};
      });
}

}  // extern "C"
