// SPDX-License-Identifier: MIT
/* posemorph for the web: the runtime's C API compiled to WebAssembly, and
 * this flat surface over it that posemorph.mjs calls. JavaScript passes and
 * gets numbers and pointers only: no struct layout is written twice. Small
 * results (a point, a transform, a part) land in one scratch array that
 * posemorph.mjs reads right after the call; strings in one text buffer.
 *
 * A crowd (pmw_crowd) holds everything one frame of `count` characters
 * needs: the inputs the caller writes (points, channel points, transforms,
 * colours, part opacities), the runtime's buffers, every character's draw
 * steps, and, once asked for, an animator's tracks, weights and events.
 * Nothing here allocates after pmw_crowd_new / pmw_crowd_animator. */
#include "posemorph_web.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

enum { kTextCapacity = 4096, kEventCapacity = 256 };

static pm_error g_error;
static char g_text[kTextCapacity];
static double g_out[9];
static float g_transforms[18]; /* three pm_transforms: two in, one out */

const char* pmw_error(void) { return g_error.message; }
double* pmw_out(void) { return g_out; }
float* pmw_transforms(void) { return g_transforms; }

static void set_error(const char* message) {
  g_error.code = PM_ERROR_INVALID_ARGUMENT;
  strncpy(g_error.message, message, sizeof g_error.message - 1);
  g_error.message[sizeof g_error.message - 1] = '\0';
}

/* A rig from bytes; NULL with pmw_error's message when refused. untrusted:
 * the loader's limits for rigs from other players (pm_load_limits_untrusted). */
pm_rig* pmw_rig_load(const void* bytes, size_t size, int untrusted) {
  pm_rig* rig = NULL;
  memset(&g_error, 0, sizeof g_error);
  int status;
  if (untrusted) {
    pm_load_limits limits;
    pm_load_limits_untrusted(&limits);
    status = pm_rig_load_limited(bytes, size, &limits, &rig, &g_error);
  } else {
    status = pm_rig_load(bytes, size, &rig, &g_error);
  }
  return status == PM_OK ? rig : NULL;
}

/* Counts: 0 vertices, 1 triangles, 2 poses, 3 paths (body), 4 channels,
 * 5 attachments, 6 lists, 7 attached weights, 8 format major, 9 minor. */
uint32_t pmw_rig_count(const pm_rig* rig, int what) {
  pm_rig_info info;
  pm_rig_get_info(rig, &info);
  uint32_t major = 0, minor = 0;
  switch (what) {
    case 0:
      return info.vertex_count;
    case 1:
      return info.triangle_count;
    case 2:
      return info.pose_count;
    case 3:
      return info.path_count;
    case 4:
      return pm_rig_channel_count(rig);
    case 5:
      return pm_rig_attachment_count(rig);
    case 6:
      return pm_character_list_count(rig);
    case 7:
      return pm_rig_attached_weight_count(rig);
    case 8:
      pm_rig_format_version(rig, &major, &minor);
      return major;
    case 9:
      pm_rig_format_version(rig, &major, &minor);
      return minor;
    default:
      return 0;
  }
}

/* Names into the text buffer (NULL when out of range or too long):
 * 0 channel a, 1 channel a's pose b, 2 channel a's path b, 3 list a's part
 * b, 4 list a's part b's drawing in pose c, 5 channel a's event b, 6 the
 * drawing folder, 7 the machine's state a, 8 list a's texture page b. */
const char* pmw_name(const pm_rig* rig, int what, uint32_t a, uint32_t b, uint32_t c) {
  size_t length = 0;
  int status = PM_ERROR_INVALID_ARGUMENT;
  switch (what) {
    case 0:
      status = pm_rig_channel_name(rig, a, g_text, kTextCapacity, &length);
      break;
    case 1:
      status = pm_channel_pose_name(rig, a, b, g_text, kTextCapacity, &length);
      break;
    case 2:
      status = pm_channel_path_name(rig, a, b, g_text, kTextCapacity, &length);
      break;
    case 3:
      status = pm_character_part_name(rig, a, b, g_text, kTextCapacity, &length);
      break;
    case 4:
      status = pm_character_part_image(rig, a, b, c, g_text, kTextCapacity, &length);
      break;
    case 5:
      status = pm_channel_event_name(rig, a, b, g_text, kTextCapacity, &length);
      break;
    case 6:
      status = pm_rig_drawing_folder(rig, g_text, kTextCapacity, &length);
      break;
    case 7:
      status = pm_machine_state_name(rig, a, g_text, kTextCapacity, &length);
      break;
    case 8:
      status = pm_character_page_name(rig, a, b, g_text, kTextCapacity, &length);
      break;
    default:
      break;
  }
  return status == PM_OK && length < kTextCapacity ? g_text : NULL;
}

/* Channel c's poses (count), and pose p's point into out[0..1]. */
uint32_t pmw_channel_pose_count(const pm_rig* rig, uint32_t channel) {
  uint32_t count = 0;
  return pm_rig_channel_poses(rig, channel, &count, NULL, 0) == PM_OK ? count : 0;
}
int pmw_channel_pose_point(const pm_rig* rig, uint32_t channel, uint32_t pose) {
  uint32_t count = pmw_channel_pose_count(rig, channel);
  if (pose >= count) return PM_ERROR_INVALID_ARGUMENT;
  double* points = (double*)malloc(2 * sizeof(double) * count);
  if (!points) return PM_ERROR_OUT_OF_MEMORY;
  int status = pm_rig_channel_poses(rig, channel, &count, points, 2 * (size_t)count);
  g_out[0] = points[2 * pose];
  g_out[1] = points[2 * pose + 1];
  free(points);
  return status;
}
uint32_t pmw_channel_path_count(const pm_rig* rig, uint32_t channel) { return pm_channel_path_count(rig, channel); }
int pmw_channel_path_find(const pm_rig* rig, uint32_t channel, const char* name) {
  return pm_channel_path_find(rig, channel, name);
}
int pmw_channel_path_sample(const pm_rig* rig, uint32_t channel, uint32_t path, double time) {
  return pm_channel_path_sample(rig, channel, path, time, &g_out[0], &g_out[1]);
}
int pmw_channel_default_sigma(const pm_rig* rig, uint32_t channel) {
  return pm_channel_default_sigma(rig, channel, &g_out[0]);
}
int pmw_channel_pad_range(const pm_rig* rig, uint32_t channel) {
  pm_bounds b;
  int status = pm_channel_pad_range(rig, channel, &b);
  g_out[0] = b.min_x, g_out[1] = b.min_y, g_out[2] = b.max_x, g_out[3] = b.max_y;
  return status;
}
uint32_t pmw_channel_quantize(const pm_rig* rig, uint32_t channel, double x, double y) {
  return pm_channel_quantize_point(rig, channel, x, y);
}
void pmw_channel_dequantize(const pm_rig* rig, uint32_t channel, uint32_t packed) {
  pm_channel_dequantize_point(rig, channel, packed, &g_out[0], &g_out[1]);
}
uint32_t pmw_channel_event_count(const pm_rig* rig, uint32_t channel) { return pm_channel_event_count(rig, channel); }
int pmw_channel_event(const pm_rig* rig, uint32_t channel, uint32_t event) {
  uint32_t path = 0;
  int status = pm_channel_event(rig, channel, event, &path, &g_out[1]);
  g_out[0] = path;
  return status;
}

/* List l (0: the body, a + 1: attachment a): out = vertices, triangles,
 * poses, parts, channel, texture filter (1 nearest). */
int pmw_list(const pm_rig* rig, uint32_t list) {
  pm_list_info info;
  int status = pm_character_list(rig, list, &info);
  if (status != PM_OK) return status;
  g_out[0] = info.vertex_count, g_out[1] = info.triangle_count, g_out[2] = info.pose_count;
  g_out[3] = info.part_count, g_out[4] = info.channel, g_out[5] = pm_character_texture_filter(rig, list);
  g_out[6] = pm_character_page_count(rig, list), g_out[7] = pm_rig_has_atlas(rig);
  return PM_OK;
}
/* out = texture page `page` of list `list`: width, height, atlas, premultiplied. */
int pmw_list_page(const pm_rig* rig, uint32_t list, uint32_t page) {
  pm_page p;
  int status = pm_character_page(rig, list, page, &p);
  if (status != PM_OK) return status;
  g_out[0] = p.width, g_out[1] = p.height, g_out[2] = p.atlas, g_out[3] = p.premultiplied;
  return PM_OK;
}
/* out = part `part`'s region in pose `pose`: page, scale u, offset u, scale v, offset v, x, y, width, height. */
int pmw_list_region(const pm_rig* rig, uint32_t list, uint32_t part, uint32_t pose) {
  pm_region r;
  int status = pm_character_part_region(rig, list, part, pose, &r);
  if (status != PM_OK) return status;
  g_out[0] = r.page, g_out[1] = r.scale_u, g_out[2] = r.offset_u, g_out[3] = r.scale_v, g_out[4] = r.offset_v;
  g_out[5] = r.x, g_out[6] = r.y, g_out[7] = r.width, g_out[8] = r.height;
  return PM_OK;
}
const uint32_t* pmw_list_triangles(const pm_rig* rig, uint32_t list) {
  return list == 0 ? pm_rig_triangles(rig) : pm_rig_attachment_triangles(rig, list - 1);
}
/* out = first triangle, triangle count, draw order. */
int pmw_list_part(const pm_rig* rig, uint32_t list, uint32_t part) {
  pm_part p;
  int status = pm_character_part(rig, list, part, &p);
  g_out[0] = p.first_triangle, g_out[1] = p.triangle_count, g_out[2] = p.draw_order;
  return status;
}
/* out = width, height, pivot x, pivot y of list l's drawing in pose `pose`. */
int pmw_list_canvas(const pm_rig* rig, uint32_t list, uint32_t pose) {
  pm_canvas c;
  int status = pm_character_canvas(rig, list, pose, &c);
  g_out[0] = c.width, g_out[1] = c.height, g_out[2] = c.pivot_x, g_out[3] = c.pivot_y;
  return status;
}
/* Pose p's vertex positions of the body (rig units, y up): 2 x vertices. */
const double* pmw_pose_positions(const pm_rig* rig, uint32_t pose) { return pm_rig_pose_positions(rig, pose); }
/* out = anchor x, anchor y, facing left. */
int pmw_placement(const pm_rig* rig) {
  double x = 0, y = 0;
  int left = 0;
  int status = pm_rig_placement(rig, &x, &y, &left);
  g_out[0] = x, g_out[1] = y, g_out[2] = left;
  return status;
}

/* Transforms in g_transforms: make / place write [12..17]; compose reads
 * outer [0..5] and inner [6..11]. */
void pmw_transform_make(double x, double y, double radians, double sx, double sy, int flip) {
  pm_transform_make(x, y, radians, sx, sy, flip, (pm_transform*)&g_transforms[12]);
}
void pmw_transform_place(const pm_rig* rig, double x, double y, double radians, double scale, int face_left) {
  pm_transform_place(rig, x, y, radians, scale, face_left, (pm_transform*)&g_transforms[12]);
}
void pmw_transform_compose(void) {
  pm_transform_compose((const pm_transform*)&g_transforms[0], (const pm_transform*)&g_transforms[6],
                       (pm_transform*)&g_transforms[12]);
}

struct pmw_crowd {
  const pm_rig* rig;
  size_t count;
  uint32_t channels, attachments, poses, parts, attached_weights, max_steps;
  pm_character_buffer_sizes sizes;
  double* work;
  float *positions, *attached_positions;
  pm_draw_list *lists, *attached;
  double *points, *channel_points;
  pm_transform* transforms;
  pm_colour* colours;
  float* part_opacities;
  pm_draw_step* steps;
  uint32_t* step_counts;
  /* The animator (pmw_crowd_animator) and the state machine (pmw_crowd_machine). */
  void* tracks;
  size_t tracks_size;
  double *w, *wl, *wt, *aw, *awl, *awt;
  pm_animator_event events[kEventCapacity];
  size_t event_count;
  uint64_t events_missed;
  void* machines;
  size_t machines_size;
};

/* malloc aligns for any type (8 bytes or more on every target), which the
 * animator's and the machine's memory need (PM_ANIMATOR_ALIGNMENT). */
typedef char animator_alignment_check[PM_ANIMATOR_ALIGNMENT <= 8 ? 1 : -1];

static void* zeroed(size_t count, size_t size) { return calloc(count ? count : 1, size); }

void pmw_crowd_free(pmw_crowd* c) {
  if (!c) return;
  void* blocks[] = {c->work,
                    c->positions,
                    c->attached_positions,
                    c->lists,
                    c->attached,
                    c->points,
                    c->channel_points,
                    c->transforms,
                    c->colours,
                    c->part_opacities,
                    c->steps,
                    c->step_counts,
                    c->tracks,
                    c->w,
                    c->wl,
                    c->wt,
                    c->aw,
                    c->awl,
                    c->awt,
                    c->machines};
  for (size_t i = 0; i < sizeof blocks / sizeof blocks[0]; ++i) free(blocks[i]);
  free(c);
}

/* A crowd of `count` characters of `rig`; NULL with pmw_error's message. */
pmw_crowd* pmw_crowd_new(const pm_rig* rig, size_t count) {
  memset(&g_error, 0, sizeof g_error);
  pmw_crowd* c = (pmw_crowd*)zeroed(1, sizeof(pmw_crowd));
  if (!c) return set_error("out of memory"), NULL;
  c->rig = rig, c->count = count;
  c->channels = pm_rig_channel_count(rig), c->attachments = pm_rig_attachment_count(rig);
  c->attached_weights = pm_rig_attached_weight_count(rig);
  pm_rig_info info;
  pm_rig_get_info(rig, &info);
  c->poses = info.pose_count;
  c->parts = pm_rig_part_count(rig) ? pm_rig_part_count(rig) : 1;
  uint32_t lists = pm_character_list_count(rig);
  for (uint32_t l = 0; l < lists; ++l) {
    pm_list_info li;
    if (pm_character_list(rig, l, &li) == PM_OK) c->max_steps += li.part_count;
  }
  if (count == 0 || pm_character_buffers(rig, count, &c->sizes) != PM_OK) {
    pmw_crowd_free(c);
    return set_error("no buffers for that many characters"), NULL;
  }
  c->work = (double*)zeroed(c->sizes.workspace_doubles, sizeof(double));
  c->positions = (float*)zeroed(c->sizes.position_floats, sizeof(float));
  c->attached_positions = (float*)zeroed(c->sizes.attached_position_floats, sizeof(float));
  c->lists = (pm_draw_list*)zeroed(count, sizeof(pm_draw_list));
  c->attached = (pm_draw_list*)zeroed(c->sizes.attached_lists, sizeof(pm_draw_list));
  c->points = (double*)zeroed(2 * count, sizeof(double));
  c->channel_points = (double*)zeroed(2 * count * (c->channels > 1 ? c->channels - 1 : 1), sizeof(double));
  c->transforms = (pm_transform*)zeroed(count, sizeof(pm_transform));
  c->colours = (pm_colour*)zeroed(count, sizeof(pm_colour));
  c->part_opacities = (float*)zeroed((size_t)c->parts * count, sizeof(float));
  c->steps = (pm_draw_step*)zeroed((size_t)c->max_steps * count, sizeof(pm_draw_step));
  c->step_counts = (uint32_t*)zeroed(count, sizeof(uint32_t));
  if (!c->work || !c->positions || !c->attached_positions || !c->lists || !c->attached || !c->points ||
      !c->channel_points || !c->transforms || !c->colours || !c->part_opacities || !c->steps || !c->step_counts) {
    pmw_crowd_free(c);
    return set_error("out of memory"), NULL;
  }
  for (size_t k = 0; k < count; ++k) {
    pm_transform_make(0, 0, 0, 1, 1, 0, &c->transforms[k]);
    c->colours[k].r = c->colours[k].g = c->colours[k].b = c->colours[k].a = 1;
    for (uint32_t p = 0; p < c->parts; ++p) c->part_opacities[c->parts * k + p] = 1;
  }
  return c;
}

/* The inputs the caller writes before pmw_crowd_evaluate. */
double* pmw_crowd_points(pmw_crowd* c) { return c->points; }
double* pmw_crowd_channel_points(pmw_crowd* c) { return c->channel_points; }
float* pmw_crowd_transforms(pmw_crowd* c) { return &c->transforms[0].a; }
float* pmw_crowd_colours(pmw_crowd* c) { return &c->colours[0].r; }
float* pmw_crowd_part_opacities(pmw_crowd* c) { return c->part_opacities; }
uint32_t pmw_crowd_part_stride(const pmw_crowd* c) { return c->parts; }

/* One frame: from the points (from_animator 0) or the animator's last
 * update (1); the optional inputs as flags (1 channel points, 2 transforms,
 * 4 colours, 8 part opacities); then every character's draw steps. */
int pmw_crowd_evaluate(pmw_crowd* c, int from_animator, int use, double sigma, uint32_t max_drawings, int limit_weights,
                       int linear) {
  pm_draw_options options;
  pm_draw_options_default(&options);
  options.sigma = sigma, options.max_drawings = max_drawings, options.limit_weights = limit_weights;
  options.linear = linear;
  options.colours = (use & 4) ? c->colours : NULL;
  options.part_opacities = (use & 8) ? c->part_opacities : NULL;
  pm_character_inputs in;
  memset(&in, 0, sizeof in);
  if (from_animator) {
    if (!c->tracks) return PM_ERROR_INVALID_ARGUMENT;
    in.weights = c->w, in.limited_weights = c->wl, in.texture_weights = c->wt;
    if (c->attachments)
      in.attached_weights = c->aw, in.attached_limited_weights = c->awl, in.attached_texture_weights = c->awt;
  } else {
    in.points = c->points;
    in.channel_points = (use & 1) && c->channels > 1 ? c->channel_points : NULL;
  }
  in.transforms = (use & 2) ? c->transforms : NULL;
  const pm_character_buffer_sizes* s = &c->sizes;
  int status = pm_character_draw_lists(c->rig, &options, c->count, &in, c->work, s->workspace_doubles, c->positions,
                                       s->position_floats, c->attachments ? c->attached_positions : NULL,
                                       s->attached_position_floats, c->lists, c->count,
                                       c->attachments ? c->attached : NULL, s->attached_lists);
  if (status != PM_OK) return status;
  for (size_t k = 0; k < c->count; ++k) {
    c->step_counts[k] =
        pm_character_draw_steps(c->rig, &c->lists[k], c->attachments ? &c->attached[k * c->attachments] : NULL,
                                &c->steps[k * c->max_steps], c->max_steps);
  }
  return PM_OK;
}

static const pm_draw_list* list_of(const pmw_crowd* c, size_t k, uint32_t l) {
  if (k >= c->count || l > c->attachments) return NULL;
  return l == 0 ? &c->lists[k] : &c->attached[k * c->attachments + l - 1];
}
/* The last frame, read by posemorph.mjs (which copies it out). */
const float* pmw_crowd_positions(const pmw_crowd* c, int attached) {
  return attached ? c->attached_positions : c->positions;
}
size_t pmw_crowd_position_count(const pmw_crowd* c, int attached) {
  return attached ? c->sizes.attached_position_floats : c->sizes.position_floats;
}
const float* pmw_list_positions(const pmw_crowd* c, size_t k, uint32_t l) {
  const pm_draw_list* d = list_of(c, k, l);
  return d ? d->positions : NULL;
}
uint32_t pmw_list_drawing_count(const pmw_crowd* c, size_t k, uint32_t l) {
  const pm_draw_list* d = list_of(c, k, l);
  return d ? d->drawing_count : 0;
}
/* Drawing i: out = pose, weight (the float, exactly); returns its uvs. */
const float* pmw_list_drawing(const pmw_crowd* c, size_t k, uint32_t l, uint32_t i) {
  const pm_draw_list* d = list_of(c, k, l);
  if (!d || i >= d->drawing_count) return NULL;
  g_out[0] = d->drawings[i].pose, g_out[1] = d->drawings[i].weight;
  return d->drawings[i].uvs;
}
/* The list's transform (6 floats: a b c d tx ty), colour (4 floats),
 * part opacities (64 floats) and whether it is mirrored. */
const float* pmw_list_transform(const pmw_crowd* c, size_t k, uint32_t l) {
  const pm_draw_list* d = list_of(c, k, l);
  return d ? &d->transform.a : NULL;
}
const float* pmw_list_colour(const pmw_crowd* c, size_t k, uint32_t l) {
  const pm_draw_list* d = list_of(c, k, l);
  return d ? &d->colour.r : NULL;
}
const float* pmw_list_part_opacity(const pmw_crowd* c, size_t k, uint32_t l) {
  const pm_draw_list* d = list_of(c, k, l);
  return d ? d->part_opacity : NULL;
}
int pmw_list_mirrored(const pmw_crowd* c, size_t k, uint32_t l) {
  const pm_draw_list* d = list_of(c, k, l);
  return d ? d->mirrored : 0;
}
/* Character k's draw steps back to front: (list, part) pairs. */
const uint32_t* pmw_crowd_steps(const pmw_crowd* c, size_t k) { return &c->steps[k * c->max_steps].list; }
uint32_t pmw_crowd_step_count(const pmw_crowd* c, size_t k) { return k < c->count ? c->step_counts[k] : 0; }

/* The animator: tracks and weights for every character (once). */
int pmw_crowd_animator(pmw_crowd* c) {
  if (c->tracks) return PM_OK;
  size_t size = pm_animator_size(c->rig, c->count);
  if (size == 0) return PM_ERROR_INVALID_ARGUMENT;
  size_t n = c->count * c->poses, na = c->count * (c->attached_weights ? c->attached_weights : 1);
  c->tracks = malloc(size);
  c->w = (double*)zeroed(n, sizeof(double)), c->wl = (double*)zeroed(n, sizeof(double));
  c->wt = (double*)zeroed(n, sizeof(double)), c->aw = (double*)zeroed(na, sizeof(double));
  c->awl = (double*)zeroed(na, sizeof(double)), c->awt = (double*)zeroed(na, sizeof(double));
  if (!c->tracks || !c->w || !c->wl || !c->wt || !c->aw || !c->awl || !c->awt) return PM_ERROR_OUT_OF_MEMORY;
  c->tracks_size = size;
  return pm_animator_reset(c->rig, c->tracks, size, c->count);
}
int pmw_animator_play(pmw_crowd* c, size_t k, uint32_t channel, uint32_t path, double speed, int loop, double mix,
                      double start, int queue) {
  pm_play_options o;
  pm_play_options_default(&o);
  o.speed = speed, o.loop = loop, o.mix = mix, o.start = start;
  return queue ? pm_animator_queue(c->rig, c->tracks, c->tracks_size, k, channel, path, &o)
               : pm_animator_play(c->rig, c->tracks, c->tracks_size, k, channel, path, &o);
}
int pmw_animator_set_point(pmw_crowd* c, size_t k, uint32_t channel, double x, double y, double mix) {
  return pm_animator_set_point(c->rig, c->tracks, c->tracks_size, k, channel, x, y, mix);
}
int pmw_animator_stop(pmw_crowd* c, size_t k, uint32_t channel, double mix) {
  return pm_animator_stop(c->rig, c->tracks, c->tracks_size, k, channel, mix);
}
int pmw_animator_set_speed(pmw_crowd* c, size_t k, uint32_t channel, double speed) {
  return pm_animator_set_speed(c->rig, c->tracks, c->tracks_size, k, channel, speed);
}
int pmw_animator_look_at(pmw_crowd* c, size_t k, uint32_t channel, double x, double y) {
  return pm_animator_look_at(c->rig, c->tracks, c->tracks_size, k, channel, x, y);
}
/* Advances every character by dt seconds (weights for pmw_crowd_evaluate
 * from_animator), the machine first when there is one. */
int pmw_animator_update(pmw_crowd* c, double dt) {
  if (!c->tracks) return PM_ERROR_INVALID_ARGUMENT;
  if (c->machines) {
    int status = pm_machine_step(c->rig, c->machines, c->machines_size, c->count, c->tracks, c->tracks_size);
    if (status != PM_OK) return status;
    status = pm_machine_colours(c->rig, c->machines, c->machines_size, c->count, dt, c->colours, c->part_opacities,
                                (size_t)c->parts * c->count);
    if (status != PM_OK) return status;
  }
  size_t n = c->count * c->poses, na = c->count * c->attached_weights;
  int attached = c->attachments > 0;
  return pm_animator_update(c->rig, c->tracks, c->tracks_size, c->count, dt, -1, 1, c->w, c->wl, c->wt, n,
                            attached ? c->aw : NULL, attached ? c->awl : NULL, attached ? c->awt : NULL, na, c->events,
                            kEventCapacity, &c->event_count, &c->events_missed);
}
size_t pmw_animator_event_count(const pmw_crowd* c) { return c->event_count; }
/* Event i of the last update: out = character, channel, event, outgoing, time. */
int pmw_animator_event(const pmw_crowd* c, size_t i) {
  if (i >= c->event_count) return PM_ERROR_INVALID_ARGUMENT;
  const pm_animator_event* e = &c->events[i];
  g_out[0] = e->character, g_out[1] = e->channel, g_out[2] = e->event, g_out[3] = e->outgoing, g_out[4] = e->time;
  return PM_OK;
}

/* The rig's state machine for every character (after pmw_crowd_animator). */
int pmw_crowd_machine(pmw_crowd* c) {
  if (c->machines) return PM_OK;
  size_t size = pm_machine_size(c->rig, c->count);
  if (size == 0 || !c->tracks) return PM_ERROR_INVALID_ARGUMENT;
  c->machines = malloc(size);
  if (!c->machines) return PM_ERROR_OUT_OF_MEMORY;
  c->machines_size = size;
  return pm_machine_reset(c->rig, c->machines, size, c->count);
}
int pmw_machine_find_input(const pm_rig* rig, const char* name) { return pm_machine_find_input(rig, name); }
int pmw_machine_find_state(const pm_rig* rig, const char* name) { return pm_machine_find_state(rig, name); }
int pmw_machine_set_bool(pmw_crowd* c, size_t k, uint32_t input, int value) {
  return pm_machine_set_bool(c->rig, c->machines, c->machines_size, k, input, value);
}
int pmw_machine_set_number(pmw_crowd* c, size_t k, uint32_t input, double value) {
  return pm_machine_set_number(c->rig, c->machines, c->machines_size, k, input, value);
}
int pmw_machine_set_point(pmw_crowd* c, size_t k, uint32_t input, double x, double y) {
  return pm_machine_set_point(c->rig, c->machines, c->machines_size, k, input, x, y);
}
int pmw_machine_fire(pmw_crowd* c, size_t k, uint32_t input) {
  return pm_machine_fire(c->rig, c->machines, c->machines_size, k, input);
}
int pmw_machine_state(const pmw_crowd* c, size_t k, uint32_t layer) {
  return pm_machine_state(c->rig, c->machines, c->machines_size, k, layer);
}
