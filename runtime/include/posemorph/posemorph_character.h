/* SPDX-License-Identifier: MIT
 * The C API's whole character (included by posemorph/posemorph.h, which
 * declares pm_rig, pm_draw_list and the error codes): draw lists for every
 * channel, the attachments' lists merged with the body's back to front,
 * and what a renderer needs to know of each list's drawings. What C++'s
 * DrawListJob (with attached_output) and CharacterDrawSteps do, so a
 * binding re-implements nothing.
 *
 * A character's lists: list 0 is the body (the first channel's pose space,
 * the rig itself), list a + 1 is attachment a (pm_rig_attachment: a part of
 * a later channel, pinned to the body at its joint). Each list has its own
 * vertices, triangles, parts, drawings and uvs; pm_character_part,
 * pm_character_part_image, pm_character_canvas and
 * pm_character_texture_filter answer for any list, so a renderer treats the
 * body and the attachments alike. */
#ifndef POSEMORPH_CHARACTER_H
#define POSEMORPH_CHARACTER_H

#include "posemorph/posemorph.h"

#ifdef __cplusplus
extern "C" {
#endif

/* 1 + pm_rig_attachment_count: the lists of one character (0 for NULL). */
PM_API uint32_t pm_character_list_count(const pm_rig* rig);
/* The vertices, triangles, poses and parts of list `list`. */
typedef struct pm_list_info {
  uint32_t vertex_count, triangle_count, pose_count, part_count;
  uint32_t channel; /* the channel whose pose space drives it: 0 for the body */
} pm_list_info;
PM_API int pm_character_list(const pm_rig* rig, uint32_t list, pm_list_info* out);
/* Part `part` of list `list` (pm_rig_part for the body), its name, its
 * drawing in pose `pose` of that list (pm_rig_part_image for the body,
 * pm_rig_attachment_image for an attachment's one part), and that pose's
 * canvas (pm_rig_pose_canvas). */
PM_API int pm_character_part(const pm_rig* rig, uint32_t list, uint32_t part, pm_part* out);
PM_API int pm_character_part_name(const pm_rig* rig, uint32_t list, uint32_t part, char* out, size_t capacity,
                                  size_t* length);
PM_API int pm_character_part_image(const pm_rig* rig, uint32_t list, uint32_t part, uint32_t pose, char* out,
                                   size_t capacity, size_t* length);
PM_API int pm_character_canvas(const pm_rig* rig, uint32_t list, uint32_t pose, pm_canvas* out);
/* PM_FILTER_LINEAR or PM_FILTER_NEAREST for list `list`'s drawings (linear for NULL or a list out of range). */
PM_API int pm_character_texture_filter(const pm_rig* rig, uint32_t list);

/* Texture pages (Rig::page, format 1.12): what a renderer uploads. `list`
 * 0 is the rig, 1 + a its attachment a (each has its own list). With an
 * atlas (pm_rig_has_atlas), the pages the bake packed the drawings into:
 * PNG files beside the rig file, premultiplied RGBA, one size per list, the
 * same files for every list of a character. Without one, a page per part
 * and pose: page p x N + i is pm_character_part_image(list, p, i), straight alpha, in
 * the drawing folder. Part p in pose i samples page region.page at
 * (u scale_u + offset_u, v scale_v + offset_v) for its uvs (u, v), inside
 * the rectangle x, y, width, height of that page's pixels. */
typedef struct pm_page {
  uint32_t width, height; /* pixels; 0 when unknown (a drawing of a rig without canvases) */
  int atlas;              /* 1: an atlas page beside the rig; 0: a drawing in the drawing folder */
  int premultiplied;      /* 1: premultiplied RGBA (atlas pages) */
} pm_page;
typedef struct pm_region {
  uint32_t page;
  float scale_u, offset_u, scale_v, offset_v;
  uint32_t x, y, width, height;
} pm_region;
PM_API int pm_rig_has_atlas(const pm_rig* rig);                            /* 1 with an atlas, 0 without (or NULL) */
PM_API uint32_t pm_character_page_count(const pm_rig* rig, uint32_t list); /* 0 beyond the lists */
PM_API int pm_character_page(const pm_rig* rig, uint32_t list, uint32_t page, pm_page* out);
PM_API int pm_character_page_name(const pm_rig* rig, uint32_t list, uint32_t page, char* out, size_t capacity,
                                  size_t* length);
PM_API int pm_character_part_region(const pm_rig* rig, uint32_t list, uint32_t part, uint32_t pose, pm_region* out);

/* A channel's poses and paths by name, and its default texture sharpening
 * (channel 0: pm_rig_pose_name, pm_rig_path_name, pm_rig_info's). */
PM_API int pm_channel_pose_name(const pm_rig* rig, uint32_t channel, uint32_t pose, char* out, size_t capacity,
                                size_t* length);
PM_API uint32_t pm_channel_path_count(const pm_rig* rig, uint32_t channel); /* 0 for a channel out of range */
PM_API int pm_channel_path_name(const pm_rig* rig, uint32_t channel, uint32_t path, char* out, size_t capacity,
                                size_t* length);
PM_API int pm_channel_default_sigma(const pm_rig* rig, uint32_t channel, double* out);

/* Where the character stands: its anchor in rig units (y up; the
 * description's "anchor", by default the bottom centre of pose 0's bounds)
 * and whether its drawings face left (the description's "facing"). */
PM_API int pm_rig_placement(const pm_rig* rig, double* anchor_x, double* anchor_y, int* facing_left);
/* A character standing at world (x, y): the anchor goes there, scaled,
 * turned counter-clockwise by `radians` about it, facing left when
 * face_left (mirrored about the anchor when its drawings face the other
 * way). C++: Transform2D::Place. The identity for non-finite inputs. */
PM_API void pm_transform_place(const pm_rig* rig, double x, double y, double radians, double scale, int face_left,
                               pm_transform* out);
/* Channel `channel`'s useful pad range: its pose points' bounds widened by a
 * tenth of their larger extent (at least one weight-grid cell) on each
 * side, within its weight grid. C++: Rig::pad_range. */
PM_API int pm_channel_pad_range(const pm_rig* rig, uint32_t channel, pm_bounds* out);

/* outer after inner (a camera after a character's place); the identity when
 * a field of the product would not fit a float. out may be outer or inner. */
PM_API void pm_transform_compose(const pm_transform* outer, const pm_transform* inner, pm_transform* out);

/* The buffers pm_character_draw_lists needs for `count` characters: the
 * workspace (doubles), the body's positions (floats, count x 2 x
 * vertex_count), the attachments' positions (floats, count x 2 x
 * pm_rig_attached_vertex_count) and their lists (count x
 * pm_rig_attachment_count). */
typedef struct pm_character_buffer_sizes {
  size_t workspace_doubles, position_floats, attached_position_floats, attached_lists;
} pm_character_buffer_sizes;
PM_API int pm_character_buffers(const pm_rig* rig, size_t count, pm_character_buffer_sizes* out);

/* What drives `count` characters this frame: either pose-space points or an
 * animator's weights (pm_animator_update's layouts), not both.
 *   points: 2 x count (the body's channel); channel_points: per character
 *     channels 1 .. C-1's (x, y) in turn, or NULL: each later channel at
 *     its first pose's point.
 *   weights, limited_weights, texture_weights: count x pose_count each;
 *     attached_weights, attached_limited_weights, attached_texture_weights:
 *     count x pm_rig_attached_weight_count each (required with weights when
 *     the rig has attachments).
 *   transforms: count, or NULL for the identity. */
typedef struct pm_character_inputs {
  const double* points;
  const double* channel_points;
  const double *weights, *limited_weights, *texture_weights;
  const double *attached_weights, *attached_limited_weights, *attached_texture_weights;
  const pm_transform* transforms;
} pm_character_inputs;

/* Every list of `count` characters: out[k] is character k's body (as
 * pm_draw_lists gives it), attached_out[k x A + a] its attachment a's list
 * (A = pm_rig_attachment_count; its positions in attached_positions, its
 * drawings' poses and uvs the attachment's own, the character's transform
 * and colour, part opacities 1). A rig without attachments needs no
 * attached buffers (NULL, 0). Options as pm_draw_lists (NULL: the
 * defaults). The same bits as DrawListJob with attached_output (and
 * pm_morph_batch + pm_attach). Capacities in elements; PM_ERROR_BAD_VALUE
 * when a solve goes beyond 1e30 (posemorph/jobs.h, kMaxPosition). */
PM_API int pm_character_draw_lists(const pm_rig* rig, const pm_draw_options* options, size_t count,
                                   const pm_character_inputs* inputs, double* workspace, size_t workspace_capacity,
                                   float* positions, size_t positions_capacity, float* attached_positions,
                                   size_t attached_positions_capacity, pm_draw_list* out, size_t out_capacity,
                                   pm_draw_list* attached_out, size_t attached_out_capacity);

/* One step of drawing a character: part `part` of list `list` (0: the body,
 * a + 1: attachment a). */
typedef struct pm_draw_step {
  uint32_t list, part;
} pm_draw_step;
/* The order to draw one character: every part of its body's list and of its
 * attachments' lists (attached: pm_rig_attachment_count lists from
 * pm_character_draw_lists, NULL when there are none), back to front by
 * their draw orders in each list's dominant drawing's pose (ties: the
 * body's parts in its order, then the attachments' in attachment order),
 * as posemorph-view draws them. Writes min(steps, capacity) steps to out
 * and returns how many steps there are; 0 for lists that are not this
 * rig's (a part or pose out of range). A step draws list `list`'s
 * triangles of that part (pm_character_part) with the list's drawings,
 * each part's own image (pm_character_part_image), the list's weights and
 * uvs, at colour.a x part_opacity[part]. */
PM_API uint32_t pm_character_draw_steps(const pm_rig* rig, const pm_draw_list* body, const pm_draw_list* attached,
                                        pm_draw_step* out, uint32_t capacity);

#ifdef __cplusplus
}
#endif

#endif /* POSEMORPH_CHARACTER_H */
