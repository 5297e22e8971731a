// SPDX-License-Identifier: MIT
/* posemorph C API: load a baked rig, evaluate poses. C99, no allocation
 * after pm_rig_load (none at all with pm_rig_load_in_place), nothing thrown.
 * Every function returning int returns PM_OK (0) on success. Every function
 * that writes into a caller's buffer takes its capacity (in elements) and
 * refuses a buffer that is too short (PM_ERROR_BUFFER_TOO_SMALL) or
 * misaligned for its type (PM_ERROR_INVALID_ARGUMENT), writing nothing.
 * Thread-safety: a loaded pm_rig is immutable and may be evaluated from many
 * threads at once, each with its own workspace.
 *
 * Conventions. Positions are in rig units: the units of the rig description
 * (for poses made from drawings, drawing pixels), x to the right and y up,
 * interleaved x0, y0, x1, y1, ... Triangles are counter-clockwise in pose 0.
 * uvs index pose i's own drawing (pm_rig_pose_image): u to the right, v down,
 * both 0..1 over the drawing's canvas. The renderer blends the drawings of
 * the poses with the texture weights in premultiplied alpha:
 * colour = sum_i texture[i] * premultiplied(drawing_i(uv_i)). */
#ifndef POSEMORPH_H
#define POSEMORPH_H

#include <stddef.h>
#include <stdint.h>

#include "posemorph/export.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
  PM_OK = 0,
  PM_ERROR_INVALID_ARGUMENT = 1,
  PM_ERROR_TRUNCATED = 2,
  PM_ERROR_BAD_MAGIC = 3,
  PM_ERROR_BAD_VERSION = 4,
  PM_ERROR_BAD_CHECKSUM = 5,
  PM_ERROR_BAD_LAYOUT = 6,
  PM_ERROR_BAD_VALUE = 7,
  PM_ERROR_TOO_LARGE = 8,
  PM_ERROR_OUT_OF_MEMORY = 9,
  PM_ERROR_UNSUPPORTED_ISA = 10, /* POSEMORPH_ISA names a path this build or CPU cannot run */
  PM_ERROR_BUFFER_TOO_SMALL = 11 /* a caller's buffer is shorter than the rig needs */
};

#define PM_VERSION_MAJOR 0
#define PM_VERSION_MINOR 5
#define PM_VERSION_PATCH 0
/* "MAJOR.MINOR.PATCH" of the library actually linked. */
PM_API const char* pm_version(void);

typedef struct pm_rig pm_rig;

typedef struct pm_error {
  int code;
  char message[256];
} pm_error;

typedef struct pm_rig_info {
  uint32_t vertex_count;
  uint32_t triangle_count;
  uint32_t pose_count;
  uint32_t path_count;
  double default_sigma;
  double size; /* bounding-box diagonal of pose 0 */
} pm_rig_info;

/* Validates the bytes and makes a rig, copying what it needs into one
 * allocation: the caller may free the bytes afterwards. err may be NULL.
 * *out_rig must be NULL on entry (PM_ERROR_INVALID_ARGUMENT otherwise: a
 * rig it held would leak); it is set only on success. */
PM_API int pm_rig_load(const void* bytes, size_t size, pm_rig** out_rig, pm_error* err);
/* Frees a rig from pm_rig_load; for a rig loaded in place it only ends its
 * use (the memory stays the caller's). NULL is allowed. */
PM_API void pm_rig_free(pm_rig* rig);

/* Caller-owned memory (no allocation at all on this path): pm_rig_memory_size
 * gives the bytes a rig needs, pm_rig_load_in_place builds the rig (and its
 * handle) inside `memory`, which must be aligned to PM_RIG_MEMORY_ALIGNMENT
 * and outlive the rig. The bytes may be released after loading. */
#define PM_RIG_MEMORY_ALIGNMENT 16
PM_API int pm_rig_memory_size(const void* bytes, size_t size, size_t* needed, pm_error* err);
PM_API int pm_rig_load_in_place(const void* bytes, size_t size, void* memory, size_t memory_size, pm_rig** out_rig,
                                pm_error* err);
/* Bounds for rigs from sources the game does not control (LoadLimits in
 * rig.h): a rig beyond one is refused with PM_ERROR_TOO_LARGE and a message
 * naming it, before its arrays are read. Each 0 keeps the format's limit. */
typedef struct pm_load_limits {
  uint64_t max_bytes;           /* the file */
  uint64_t max_memory;          /* the rig's memory (pm_rig_memory_size, less the handle), attachments included */
  uint32_t max_vertices;        /* the body's and its attachments' together */
  uint32_t max_poses;           /* in any one pose space */
  uint32_t max_attachments;     /* parts of later channels */
  uint64_t max_factor_nonzeros; /* the solve's work per frame, attachments included */
  uint32_t max_fill;            /* factor nonzeros per vertex and bit of V in each pose space (LoadLimits::max_fill) */
} pm_load_limits;
/* The bounds for characters from players (LoadLimits::Untrusted()). */
PM_API void pm_load_limits_untrusted(pm_load_limits* out);
/* pm_rig_load, pm_rig_memory_size and pm_rig_load_in_place within `limits`
 * (NULL: the format's limits, as the functions above). */
PM_API int pm_rig_load_limited(const void* bytes, size_t size, const pm_load_limits* limits, pm_rig** out_rig,
                               pm_error* err);
PM_API int pm_rig_memory_size_limited(const void* bytes, size_t size, const pm_load_limits* limits, size_t* needed,
                                      pm_error* err);
PM_API int pm_rig_load_in_place_limited(const void* bytes, size_t size, const pm_load_limits* limits, void* memory,
                                        size_t memory_size, pm_rig** out_rig, pm_error* err);
PM_API void pm_rig_get_info(const pm_rig* rig, pm_rig_info* info);
/* The rig's own arrays, read-only, valid while the rig is. */
PM_API const uint32_t* pm_rig_triangles(const pm_rig* rig);                   /* 3 x triangle_count */
PM_API const float* pm_rig_uvs(const pm_rig* rig, uint32_t pose);             /* 2 x vertex_count, or NULL */
PM_API const double* pm_rig_pose_positions(const pm_rig* rig, uint32_t pose); /* 2 x vertex_count, or NULL */
PM_API int pm_rig_pose_point(const pm_rig* rig, uint32_t pose, double* x, double* y);

/* A pose's name, its drawing reference (as the bake wrote it; may be empty),
 * a path's name: copied with a terminating NUL into out (capacity bytes).
 * *length (if given) receives the length without the NUL, also when the
 * buffer is too small, so a caller can size it. */
PM_API int pm_rig_pose_name(const pm_rig* rig, uint32_t pose, char* out, size_t capacity, size_t* length);
PM_API int pm_rig_pose_image(const pm_rig* rig, uint32_t pose, char* out, size_t capacity, size_t* length);
PM_API int pm_rig_path_name(const pm_rig* rig, uint32_t path, char* out, size_t capacity, size_t* length);
/* Parts of a layered character (format 1.6): a rig without parts has one,
 * covering every triangle, named "", drawing the poses' images. A part is
 * the triangles first_triangle .. first_triangle + triangle_count - 1 of
 * pm_rig_triangles; lower draw_order draws first (behind). draw_order is
 * pose 0's: a rig may change it with the pose (pm_rig_part_draw_order), and
 * each draw list's parts are then in its dominant drawing's pose's order. */
typedef struct pm_part {
  uint32_t first_triangle, triangle_count;
  int32_t draw_order;
} pm_part;
PM_API uint32_t pm_rig_part_count(const pm_rig* rig); /* 0 for NULL */
PM_API int pm_rig_part(const pm_rig* rig, uint32_t part, pm_part* out);
PM_API int pm_rig_part_name(const pm_rig* rig, uint32_t part, char* out, size_t capacity, size_t* length);
/* A part's draw order in a pose. */
PM_API int pm_rig_part_draw_order(const pm_rig* rig, uint32_t part, uint32_t pose, int32_t* out);
/* The drawing a part shows in a pose (pm_rig_pose_image for a rig without parts). */
PM_API int pm_rig_part_image(const pm_rig* rig, uint32_t part, uint32_t pose, char* out, size_t capacity,
                             size_t* length);
/* Where the bake found the drawings, relative to the rig file's folder
 * ('/'-separated, may contain ".."; empty before format 1.5 or when the bake
 * did not know): where tools on the baking machine look for the drawings.
 * Copied as above. */
PM_API int pm_rig_drawing_folder(const pm_rig* rig, char* out, size_t capacity, size_t* length);

/* The pose-space grid the weights are baked on: a UI maps its pad to
 * [min_x, max_x] x [min_y, max_y]; points beyond are clamped to it. */
typedef struct pm_grid_info {
  double min_x, min_y, max_x, max_y;
  double cell; /* square cell edge */
  uint32_t cells_x, cells_y;
} pm_grid_info;
PM_API int pm_rig_grid(const pm_rig* rig, pm_grid_info* out);

/* Control channels (format 1.7): a character whose parts move on several
 * pose spaces (a face apart from the body). The rig itself is channel 0:
 * every function above is about it. A part of a later channel is an
 * attachment: a rig of its own over its channel's poses, solved with its
 * joint pinned and placed on the body by pm_attach (posemorph/jobs.h,
 * AttachJob). A rig with one channel has no attachments. */
PM_API uint32_t pm_rig_channel_count(const pm_rig* rig); /* 1 for one channel; 0 for NULL */
PM_API int pm_rig_channel_name(const pm_rig* rig, uint32_t channel, char* out, size_t capacity, size_t* length);
PM_API int pm_rig_find_channel(const pm_rig* rig, const char* name); /* its index, or -1 */
/* Channel `channel`'s pose count, its pose points (2 per pose, in `points`
 * of `capacity` doubles; may be NULL to ask the count) and its grid. */
PM_API int pm_rig_channel_poses(const pm_rig* rig, uint32_t channel, uint32_t* pose_count, double* points,
                                size_t capacity);
PM_API int pm_rig_channel_grid(const pm_rig* rig, uint32_t channel, pm_grid_info* out);
/* pm_weights in channel `channel`'s pose space (channel 0: pm_weights). */
PM_API int pm_channel_weights(const pm_rig* rig, uint32_t channel, double x, double y, double sigma, int limit_weights,
                              double* raw, double* limited, double* texture, size_t capacity);
/* A channel's path at a time (pm_path_sample in its own pose space), and its paths' names. */
PM_API int pm_channel_path_find(const pm_rig* rig, uint32_t channel, const char* name);
PM_API int pm_channel_path_sample(const pm_rig* rig, uint32_t channel, uint32_t path, double time, double* x,
                                  double* y);
typedef struct pm_attachment {
  uint32_t channel; /* 1 .. channel_count - 1 */
  uint32_t vertex_count, triangle_count, pose_count;
  int32_t draw_order;       /* its part's, in its pose 0 (pm_rig_attachment_draw_order per pose) */
  uint32_t parent_triangle; /* the body triangle its joint lies in */
  double parent_weights[3]; /* the joint there (barycentric, pose 0) */
  uint32_t joint_triangle;  /* the joint in the attachment's own triangles */
  double joint_weights[3];
} pm_attachment;
PM_API uint32_t pm_rig_attachment_count(const pm_rig* rig); /* 0 for NULL or one channel */
PM_API int pm_rig_attachment(const pm_rig* rig, uint32_t attachment, pm_attachment* out);
PM_API int pm_rig_attachment_name(const pm_rig* rig, uint32_t attachment, char* out, size_t capacity, size_t* length);
PM_API int pm_rig_attachment_draw_order(const pm_rig* rig, uint32_t attachment, uint32_t pose, int32_t* out);
/* Its triangles (3 x triangle_count), its uvs in one of its poses (2 x
 * vertex_count, or NULL) and its drawing in that pose. NULL beyond the counts. */
PM_API const uint32_t* pm_rig_attachment_triangles(const pm_rig* rig, uint32_t attachment);
PM_API const float* pm_rig_attachment_uvs(const pm_rig* rig, uint32_t attachment, uint32_t pose);
PM_API int pm_rig_attachment_image(const pm_rig* rig, uint32_t attachment, uint32_t pose, char* out, size_t capacity,
                                   size_t* length);
/* The layouts pm_attach reads and writes: all attachments' vertices; all
 * later channels' weights side by side, channel c's starting at
 * pm_rig_channel_weight_offset (c >= 1). */
PM_API uint32_t pm_rig_attached_vertex_count(const pm_rig* rig);
PM_API uint32_t pm_rig_attached_weight_count(const pm_rig* rig);
PM_API uint32_t pm_rig_channel_weight_offset(const pm_rig* rig, uint32_t channel);
PM_API size_t pm_attach_workspace_size(const pm_rig* rig);
/* The attachments of `count` characters (AttachJob): body_positions are
 * pm_morph's (or pm_morph_batch's) doubles, count x 2 x vertex_count (in
 * body_capacity doubles); weights and limited_weights, channel by channel
 * (1 .. C-1), count x that channel's pose count each (in weights_capacity
 * doubles each: for one character pm_rig_attached_weight_count); positions
 * (required) and positions_f32 (may be NULL), attachment by attachment,
 * count x 2 x its vertex count (in positions_capacity elements each: for one
 * character 2 x pm_rig_attached_vertex_count). The same bits for a
 * character whatever `count`. */
PM_API int pm_attach(const pm_rig* rig, size_t count, const double* body_positions, size_t body_capacity,
                     const double* weights, const double* limited_weights, size_t weights_capacity, int linear,
                     double* workspace, size_t workspace_capacity, double* positions, float* positions_f32,
                     size_t positions_capacity);

/* Axis-aligned bounds in rig units. */
typedef struct pm_bounds {
  double min_x, min_y, max_x, max_y;
} pm_bounds;
/* The bounds of one base pose. */
PM_API int pm_rig_pose_bounds(const pm_rig* rig, uint32_t pose, pm_bounds* out);
/* The bounds of the frames over the pose hull (the convex hull of the pose
 * points): the base poses and frames at samples^2 points spread over the
 * hull (samples in 2..256; in-betweens between samples may reach a little
 * further: add a margin). Evaluates frames: workspace holds
 * pm_hull_bounds_workspace_size() doubles. */
PM_API size_t pm_hull_bounds_workspace_size(const pm_rig* rig);
PM_API int pm_rig_hull_bounds(const pm_rig* rig, uint32_t samples, double* workspace, size_t workspace_capacity,
                              pm_bounds* out);

/* Pose i's drawing: canvas size and where the rig origin sits on it (x
 * right, y down), in drawing units (PNG pixels); all zero when the pose has
 * no drawing or the rig predates format 1.1. One rig unit is one drawing
 * unit, y up. */
typedef struct pm_canvas {
  double width, height, pivot_x, pivot_y;
} pm_canvas;
PM_API int pm_rig_pose_canvas(const pm_rig* rig, uint32_t pose, pm_canvas* out);

/* How the rig's drawings want to be sampled (format 1.4; earlier rigs:
 * linear): PM_FILTER_NEAREST for pixel art. A hint for the renderer. */
#define PM_FILTER_LINEAR 0
#define PM_FILTER_NEAREST 1
PM_API int pm_rig_texture_filter(const pm_rig* rig);

/* The CRC-32 of the file and its format version: network peers compare
 * them (after a handshake) to know they hold the same rig. */
PM_API int pm_rig_checksum(const pm_rig* rig, uint32_t* crc);
PM_API int pm_rig_format_version(const pm_rig* rig, uint32_t* major, uint32_t* minor);

/* Weights at a pose-space point. raw is required; limited (the limited
 * weights: phi(w) renormalised, or raw when limit_weights is 0) and texture may be
 * NULL; each given array holds `capacity` doubles, at least pose_count.
 * sigma in [0,1] sharpens the texture blend. */
PM_API int pm_weights(const pm_rig* rig, double x, double y, double sigma, int limit_weights, double* raw,
                      double* limited, double* texture, size_t capacity);

/* Doubles of workspace pm_morph needs. */
PM_API size_t pm_morph_workspace_size(const pm_rig* rig);

/* Vertex positions (2 x vertex_count, interleaved) for raw and limited weights
 * (pose_count each). workspace: workspace_capacity doubles, at least
 * pm_morph_workspace_size. positions (required) and positions_f32 (may be
 * NULL) hold positions_capacity elements each, at least 2 x vertex_count.
 * linear != 0 blends vertex positions linearly. PM_ERROR_BAD_VALUE (zeros
 * written) when the solve gives a position beyond 1e30 or not finite, which
 * only a rig whose factor amplifies its solve can (posemorph/jobs.h,
 * kMaxPosition). */
PM_API int pm_morph(const pm_rig* rig, const double* weights, const double* limited_weights, int linear,
                    double* workspace, size_t workspace_capacity, double* positions, float* positions_f32,
                    size_t positions_capacity);

/* Many characters sharing one rig: `count` sets of pose_count weights (raw,
 * and limited) in, `count` position arrays out (either may be NULL,
 * not both). Equal to pm_morph per character, bit for bit. To use several
 * threads, call it per thread on disjoint ranges, each with its own
 * workspace (workspace_capacity doubles, at least pm_batch_workspace_size).
 * Each given position array holds positions_capacity elements, at least
 * count x 2 x vertex_count. PM_ERROR_BAD_VALUE as pm_morph: zeros for the
 * characters whose solve goes beyond 1e30, the others evaluated. */
PM_API size_t pm_batch_workspace_size(const pm_rig* rig);
PM_API int pm_morph_batch(const pm_rig* rig, size_t count, const double* weights, const double* limited_weights,
                          double* workspace, size_t workspace_capacity, double* positions, float* positions_f32,
                          size_t positions_capacity);

/* Draw lists: everything a renderer needs for `count` characters of one
 * rig at their pose-space points (posemorph/draw_list.h has the C++ form
 * and how to draw one). A transform places a character in the world:
 *   x' = a x + c y + tx,  y' = b x + d y + ty   (rig units -> world)
 * The renderer applies it; positions stay in rig units. */
typedef struct pm_transform {
  float a, b, c, d, tx, ty;
} pm_transform;
/* Scale (sx, sy), flip horizontally if flip_x, rotate counter-clockwise by
 * `radians`, move to (x, y). Non-finite inputs give the identity. */
PM_API void pm_transform_make(double x, double y, double radians, double scale_x, double scale_y, int flip_x,
                              pm_transform* out);
#define PM_MAX_BLEND_DRAWINGS 8
typedef struct pm_blended_drawing {
  uint32_t pose;    /* whose drawing (pm_rig_pose_image) */
  float weight;     /* the picked drawings' weights sum to 1 */
  const float* uvs; /* that pose's uvs (2 x vertex_count), or NULL */
} pm_blended_drawing;
#define PM_MAX_PARTS 64
/* A character's tint (r, g, b multiply the drawing's colour) and opacity
 * (a), each in 0..1: a renderer multiplies each premultiplied sample by
 * (r, g, b, 1) x a (posemorph/draw_list.h, "Drawing a DrawList"). */
typedef struct pm_colour {
  float r, g, b, a;
} pm_colour;
typedef struct pm_draw_list {
  const float* positions;  /* 2 x vertex_count floats, rig units: a slice of the caller's positions */
  const uint32_t* indices; /* 3 x triangle_count (counter-clockwise in pose 0) */
  uint32_t vertex_count, index_count;
  uint32_t drawing_count; /* 1..max_drawings */
  pm_blended_drawing drawings[PM_MAX_BLEND_DRAWINGS];
  pm_transform transform;
  int mirrored; /* the transform mirrors: triangles are clockwise in the world */
  /* The parts back to front (pm_rig_part): draw each part's triangles in
   * this order with its own drawings (pm_rig_part_image) and the same
   * weights and uvs. One part, every triangle, for a rig without parts. */
  const uint32_t* parts;
  uint32_t part_count;
  pm_colour colour; /* the character's tint and opacity (pm_draw_options.colours) */
  /* Each part's opacity by part index (1 beyond the rig's parts): part p
   * draws at colour.a x part_opacity[p]. */
  float part_opacity[PM_MAX_PARTS];
} pm_draw_list;
typedef struct pm_draw_options {
  double sigma; /* texture sharpening in [0, 1]; < 0: the rig's default */
  /* 1 (default): the stretches blend with the limited weights (the paper's
   * limit on shear and scale). `shear_limit`, its name before 0.3, is a
   * deprecated alias where the compiler has anonymous unions (C11, C++). */
#if defined(__cplusplus) || (defined(__STDC_VERSION__) && __STDC_VERSION__ >= 201112L)
  union {
    int limit_weights;
    int shear_limit;
  };
#else
  int limit_weights;
#endif
  int linear;            /* 1: linear vertex blending (for comparison) */
  uint32_t max_drawings; /* K in 1..8: drawings the renderer blends per character */
  /* count colours, or NULL: as drawn; count x part_count opacities (part
   * index order), or NULL: every part opaque. Clamped to 0..1, NaN as 1. */
  const pm_colour* colours;
  const float* part_opacities;
} pm_draw_options;
/* sigma -1, limit_weights 1, linear 0, max_drawings 8, no colours. Start from these
 * and set fields by name (a positional initialiser needs braces around
 * limit_weights where the alias union is there). */
PM_API void pm_draw_options_default(pm_draw_options* out);
/* The buffers pm_draw_lists needs for `count` characters: workspace
 * (doubles) and positions (floats). */
PM_API int pm_draw_list_buffers(const pm_rig* rig, size_t count, size_t* workspace_doubles, size_t* position_floats);
/* points: 2 x count doubles; transforms: count, or NULL for the identity;
 * options NULL: the defaults; out: count lists. Rigid characters equal
 * pm_morph_batch (one character: pm_morph) bit for bit. */
PM_API int pm_draw_lists(const pm_rig* rig, const pm_draw_options* options, size_t count, const double* points,
                         const pm_transform* transforms, double* workspace, size_t workspace_capacity, float* positions,
                         size_t positions_capacity, pm_draw_list* out, size_t out_capacity);
/* The max_drawings (1..8) largest of pose_count texture weights, largest
 * first, renormalised (as pm_draw_lists picks them; uvs NULL). Returns the
 * number written to out (capacity entries). */
PM_API uint32_t pm_pick_drawings(const double* texture_weights, uint32_t pose_count, uint32_t max_drawings,
                                 pm_blended_drawing* out, uint32_t capacity);
/* Index of the named path or -1; point on a path at a time in seconds. */
PM_API int pm_path_find(const pm_rig* rig, const char* name);
PM_API int pm_path_sample(const pm_rig* rig, uint32_t path, double time, double* x, double* y);

/* A pose-space point in 4 bytes (x in the low 16 bits, y in the high 16). */
PM_API uint32_t pm_quantize_point(const pm_rig* rig, double x, double y);
PM_API void pm_dequantize_point(const pm_rig* rig, uint32_t packed, double* x, double* y);
/* The same in channel `channel`'s pose space (channel 0: the above): a
 * frame of a character with channels is 4 bytes per channel. 0 (and x, y
 * left alone) for a channel the rig does not have. */
PM_API uint32_t pm_channel_quantize_point(const pm_rig* rig, uint32_t channel, double x, double y);
PM_API void pm_channel_dequantize_point(const pm_rig* rig, uint32_t channel, uint32_t packed, double* x, double* y);

#ifdef __cplusplus
}
#endif

/* The animation layer's functions: the animator, the state machine, events. */
#include "posemorph/posemorph_animation.h"
/* The whole character: every channel's draw lists, attachments merged back to front. */
#include "posemorph/posemorph_character.h"

#endif /* POSEMORPH_H */
