// SPDX-License-Identifier: MIT
/* posemorph C API: load a baked rig, evaluate poses. C99, no allocation
 * after pm_rig_load, nothing thrown. Every function returning int returns
 * PM_OK (0) on success. Thread-safety: a loaded pm_rig is immutable and may
 * be evaluated from many threads at once, each with its own workspace. */
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
  PM_ERROR_UNSUPPORTED_ISA = 10 /* POSEMORPH_ISA names a path this build or CPU cannot run */
};

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
PM_API void pm_rig_get_info(const pm_rig* rig, pm_rig_info* info);
PM_API const uint32_t* pm_rig_triangles(const pm_rig* rig);            /* 3 x triangle_count */
PM_API const float* pm_rig_uvs(const pm_rig* rig, uint32_t pose);     /* 2 x vertex_count, or NULL */
PM_API const double* pm_rig_pose_positions(const pm_rig* rig, uint32_t pose); /* 2 x vertex_count, or NULL */
PM_API int pm_rig_pose_point(const pm_rig* rig, uint32_t pose, double* x, double* y);

/* Weights at a pose-space point. raw is required (pose_count doubles);
 * shear and texture may be NULL. sigma in [0,1] sharpens the texture blend. */
PM_API int pm_weights(const pm_rig* rig, double x, double y, double sigma, int shear_limit,
               double* raw, double* shear, double* texture);

/* Doubles of workspace pm_morph needs. */
PM_API size_t pm_morph_workspace_size(const pm_rig* rig);

/* Vertex positions (2 x vertex_count, interleaved) for raw and shear weights.
 * positions_f32 may be NULL. linear != 0 blends vertex positions linearly. */
PM_API int pm_morph(const pm_rig* rig, const double* weights, const double* shear_weights, int linear,
             double* workspace, double* positions, float* positions_f32);

/* Many characters sharing one rig: `count` sets of pose_count weights (raw,
 * and shear-limited) in, `count` position arrays out (either may be NULL,
 * not both). Equal to pm_morph per character, bit for bit. To use several
 * threads, call it per thread on disjoint ranges, each with its own
 * workspace of pm_batch_workspace_size() doubles. */
PM_API size_t pm_batch_workspace_size(const pm_rig* rig);
PM_API int pm_morph_batch(const pm_rig* rig, size_t count, const double* weights, const double* shear_weights,
                   double* workspace, double* positions, float* positions_f32);

/* Index of the named path or -1; point on a path at a time in seconds. */
PM_API int pm_path_find(const pm_rig* rig, const char* name);
PM_API int pm_path_sample(const pm_rig* rig, uint32_t path, double time, double* x, double* y);

/* A pose-space point in 4 bytes (x in the low 16 bits, y in the high 16). */
PM_API uint32_t pm_quantize_point(const pm_rig* rig, double x, double y);
PM_API void pm_dequantize_point(const pm_rig* rig, uint32_t packed, double* x, double* y);

#ifdef __cplusplus
}
#endif

#endif /* POSEMORPH_H */
