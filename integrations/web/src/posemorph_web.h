// SPDX-License-Identifier: MIT
/* The flat surface posemorph.mjs calls (posemorph_web.c says how it works).
 * Compiled to WebAssembly for the npm package, and natively for the
 * benchmark page's twin (bench/frame_native.c). */
#ifndef POSEMORPH_WEB_H
#define POSEMORPH_WEB_H
#include <stddef.h>
#include <stdint.h>

#include "posemorph/posemorph.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pmw_crowd pmw_crowd;

const char* pmw_error(void);
double* pmw_out(void);
float* pmw_transforms(void);
pm_rig* pmw_rig_load(const void* bytes, size_t size, int untrusted);
uint32_t pmw_rig_count(const pm_rig* rig, int what);
const char* pmw_name(const pm_rig* rig, int what, uint32_t a, uint32_t b, uint32_t c);
uint32_t pmw_channel_pose_count(const pm_rig* rig, uint32_t channel);
int pmw_channel_pose_point(const pm_rig* rig, uint32_t channel, uint32_t pose);
uint32_t pmw_channel_path_count(const pm_rig* rig, uint32_t channel);
int pmw_channel_path_find(const pm_rig* rig, uint32_t channel, const char* name);
int pmw_channel_path_sample(const pm_rig* rig, uint32_t channel, uint32_t path, double time);
int pmw_channel_default_sigma(const pm_rig* rig, uint32_t channel);
int pmw_channel_pad_range(const pm_rig* rig, uint32_t channel);
uint32_t pmw_channel_quantize(const pm_rig* rig, uint32_t channel, double x, double y);
void pmw_channel_dequantize(const pm_rig* rig, uint32_t channel, uint32_t packed);
uint32_t pmw_channel_event_count(const pm_rig* rig, uint32_t channel);
int pmw_channel_event(const pm_rig* rig, uint32_t channel, uint32_t event);
int pmw_list(const pm_rig* rig, uint32_t list);
const uint32_t* pmw_list_triangles(const pm_rig* rig, uint32_t list);
int pmw_list_part(const pm_rig* rig, uint32_t list, uint32_t part);
int pmw_list_canvas(const pm_rig* rig, uint32_t list, uint32_t pose);
int pmw_list_page(const pm_rig* rig, uint32_t list, uint32_t page);
int pmw_list_region(const pm_rig* rig, uint32_t list, uint32_t part, uint32_t pose);
const double* pmw_pose_positions(const pm_rig* rig, uint32_t pose);
int pmw_placement(const pm_rig* rig);
void pmw_transform_make(double x, double y, double radians, double sx, double sy, int flip);
void pmw_transform_place(const pm_rig* rig, double x, double y, double radians, double scale, int face_left);
void pmw_transform_compose(void);
void pmw_crowd_free(pmw_crowd* c);
pmw_crowd* pmw_crowd_new(const pm_rig* rig, size_t count);
double* pmw_crowd_points(pmw_crowd* c);
double* pmw_crowd_channel_points(pmw_crowd* c);
float* pmw_crowd_transforms(pmw_crowd* c);
float* pmw_crowd_colours(pmw_crowd* c);
float* pmw_crowd_part_opacities(pmw_crowd* c);
uint32_t pmw_crowd_part_stride(const pmw_crowd* c);
int pmw_crowd_evaluate(pmw_crowd* c, int from_animator, int use, double sigma, uint32_t max_drawings, int limit_weights,
                       int linear);
const float* pmw_crowd_positions(const pmw_crowd* c, int attached);
size_t pmw_crowd_position_count(const pmw_crowd* c, int attached);
const float* pmw_list_positions(const pmw_crowd* c, size_t k, uint32_t l);
uint32_t pmw_list_drawing_count(const pmw_crowd* c, size_t k, uint32_t l);
const float* pmw_list_drawing(const pmw_crowd* c, size_t k, uint32_t l, uint32_t i);
const float* pmw_list_transform(const pmw_crowd* c, size_t k, uint32_t l);
const float* pmw_list_colour(const pmw_crowd* c, size_t k, uint32_t l);
const float* pmw_list_part_opacity(const pmw_crowd* c, size_t k, uint32_t l);
int pmw_list_mirrored(const pmw_crowd* c, size_t k, uint32_t l);
const uint32_t* pmw_crowd_steps(const pmw_crowd* c, size_t k);
uint32_t pmw_crowd_step_count(const pmw_crowd* c, size_t k);
int pmw_crowd_animator(pmw_crowd* c);
int pmw_animator_play(pmw_crowd* c, size_t k, uint32_t channel, uint32_t path, double speed, int loop, double mix,
                      double start, int queue);
int pmw_animator_set_point(pmw_crowd* c, size_t k, uint32_t channel, double x, double y, double mix);
int pmw_animator_stop(pmw_crowd* c, size_t k, uint32_t channel, double mix);
int pmw_animator_set_speed(pmw_crowd* c, size_t k, uint32_t channel, double speed);
int pmw_animator_look_at(pmw_crowd* c, size_t k, uint32_t channel, double x, double y);
int pmw_animator_update(pmw_crowd* c, double dt);
size_t pmw_animator_event_count(const pmw_crowd* c);
int pmw_animator_event(const pmw_crowd* c, size_t i);
int pmw_crowd_machine(pmw_crowd* c);
int pmw_machine_find_input(const pm_rig* rig, const char* name);
int pmw_machine_find_state(const pm_rig* rig, const char* name);
int pmw_machine_set_bool(pmw_crowd* c, size_t k, uint32_t input, int value);
int pmw_machine_set_number(pmw_crowd* c, size_t k, uint32_t input, double value);
int pmw_machine_set_point(pmw_crowd* c, size_t k, uint32_t input, double x, double y);
int pmw_machine_fire(pmw_crowd* c, size_t k, uint32_t input);
int pmw_machine_state(const pmw_crowd* c, size_t k, uint32_t layer);

#ifdef __cplusplus
}
#endif
#endif
