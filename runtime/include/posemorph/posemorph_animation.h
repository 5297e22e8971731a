/* SPDX-License-Identifier: MIT
 * The C API's animation layer (included by posemorph/posemorph.h, which
 * declares pm_rig and the error codes): the animator's tracks, the state
 * machine and path events, in caller memory. */
#ifndef POSEMORPH_ANIMATION_H
#define POSEMORPH_ANIMATION_H

#include "posemorph/posemorph.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The animator (posemorph/animator.h, docs/animation.md): per character
 * and channel a track that plays paths, queues, mixes, follows a pad and
 * runs behaviours; an update advances `count` characters and writes their
 * weights in pm_morph_batch's (channel 0) and pm_attach's (channels 1 ..
 * C-1) layouts. Tracks live in caller memory: pm_animator_size bytes for
 * `count` characters, aligned to PM_ANIMATOR_ALIGNMENT, initialised by
 * pm_animator_reset. Commands name a character and a channel and take
 * effect at the next update; they return PM_ERROR_INVALID_ARGUMENT for a
 * character, channel or path out of range and PM_ERROR_BUFFER_TOO_SMALL
 * when `capacity` (bytes) does not hold that character's tracks. Nothing
 * allocates; any bytes in the tracks give finite weights. */
#define PM_ANIMATOR_ALIGNMENT 8
PM_API size_t pm_animator_size(const pm_rig* rig, size_t count); /* 0 for NULL */
PM_API int pm_animator_reset(const pm_rig* rig, void* tracks, size_t capacity, size_t count);
typedef struct pm_play_options {
  double speed; /* path seconds per second */
  int loop;     /* -1: as the path says; 0: once; 1: looped */
  double mix;   /* seconds of hand-over; 0 cuts */
  double start; /* seconds after the path's first key */
} pm_play_options;
PM_API void pm_play_options_default(pm_play_options* out); /* 1, -1, 0.2, 0 */
/* options NULL: the defaults. */
PM_API int pm_animator_play(const pm_rig* rig, void* tracks, size_t capacity, size_t character, uint32_t channel,
                            uint32_t path, const pm_play_options* options);
PM_API int pm_animator_queue(const pm_rig* rig, void* tracks, size_t capacity, size_t character, uint32_t channel,
                             uint32_t path, const pm_play_options* options);
PM_API int pm_animator_set_point(const pm_rig* rig, void* tracks, size_t capacity, size_t character, uint32_t channel,
                                 double x, double y, double mix);
PM_API int pm_animator_stop(const pm_rig* rig, void* tracks, size_t capacity, size_t character, uint32_t channel,
                            double mix);
PM_API int pm_animator_set_speed(const pm_rig* rig, void* tracks, size_t capacity, size_t character, uint32_t channel,
                                 double speed);
/* Behaviours (animator.h: BlinkBehaviour ... SpringBehaviour; the ranges
 * there). enabled: 0 or 1. */
typedef struct pm_behaviours {
  int blink_enabled;
  uint32_t blink_pose;
  double blink_interval, blink_jitter, blink_duration, blink_strength;
  uint64_t blink_seed;
  int breath_enabled;
  double breath_period, breath_x, breath_y;
  int look_at_enabled;
  double look_at_x, look_at_y, look_at_smoothing, look_at_strength;
  int spring_enabled;
  double spring_frequency, spring_damping, spring_strength;
} pm_behaviours;
PM_API void pm_behaviours_default(pm_behaviours* out); /* all off, animator.h's defaults */
PM_API int pm_animator_set_behaviours(const pm_rig* rig, void* tracks, size_t capacity, size_t character,
                                      uint32_t channel, const pm_behaviours* behaviours);
PM_API int pm_animator_look_at(const pm_rig* rig, void* tracks, size_t capacity, size_t character, uint32_t channel,
                               double x, double y);
typedef struct pm_animator_event {
  uint32_t character, channel;
  uint32_t event; /* pm_channel_event's index */
  int outgoing;   /* 1: reported by the motion a mix hands over from */
  double time;    /* seconds into the update */
} pm_animator_event;
/* Advances `count` characters by dt seconds (NaN or negative: 0; beyond
 * 1e9: 1e9). weights, limited_weights (required) and texture_weights (may
 * be NULL): count x pose_count each, in weights_capacity doubles; the
 * attached ones (required when the rig has attachments; texture may be
 * NULL): count x pm_rig_attached_weight_count each, in attached_capacity.
 * sigma < 0: each channel's default. events (may be NULL): up to
 * events_capacity crossings, their number in *event_count and the rest
 * counted in *events_missed (both required with events). */
PM_API int pm_animator_update(const pm_rig* rig, void* tracks, size_t capacity, size_t count, double dt, double sigma,
                              int limit_weights, double* weights, double* limited_weights, double* texture_weights,
                              size_t weights_capacity, double* attached_weights, double* attached_limited_weights,
                              double* attached_texture_weights, size_t attached_capacity, pm_animator_event* events,
                              size_t events_capacity, size_t* event_count, uint64_t* events_missed);
/* One character's animator as bytes for a late-joining peer (animator.h:
 * AnimatorSave, AnimatorLoad): the size, the bytes (out_capacity bytes;
 * *written their length), and back (PM_ERROR_BAD_VALUE, changing nothing,
 * for bytes that are not such a state for this rig). */
PM_API size_t pm_animator_state_size(const pm_rig* rig, const void* tracks, size_t capacity, size_t character);
PM_API int pm_animator_save(const pm_rig* rig, const void* tracks, size_t capacity, size_t character,
                            unsigned char* out, size_t out_capacity, size_t* written);
PM_API int pm_animator_load(const pm_rig* rig, const unsigned char* bytes, size_t size, void* tracks, size_t capacity,
                            size_t character);
/* The rig's state machine (format 1.9; posemorph/state_machine.h): per
 * character a machine of pm_machine_size bytes (aligned to
 * PM_ANIMATOR_ALIGNMENT) in caller memory. Set inputs by index
 * (pm_machine_find_input), then pm_machine_step before each
 * pm_animator_update: it issues the commands that enter new states into the
 * tracks. PM_ERROR_INVALID_ARGUMENT for a rig without a machine, an input
 * of another type, or an index out of range. */
PM_API size_t pm_machine_size(const pm_rig* rig, size_t count); /* 0 without a machine */
PM_API int pm_machine_reset(const pm_rig* rig, void* machines, size_t capacity, size_t count);
PM_API int pm_machine_find_input(const pm_rig* rig, const char* name); /* its index, or -1 */
PM_API int pm_machine_find_state(const pm_rig* rig, const char* name);
PM_API int pm_machine_state_name(const pm_rig* rig, uint32_t state, char* out, size_t capacity, size_t* length);
PM_API int pm_machine_set_bool(const pm_rig* rig, void* machines, size_t capacity, size_t character, uint32_t input,
                               int value);
PM_API int pm_machine_set_number(const pm_rig* rig, void* machines, size_t capacity, size_t character, uint32_t input,
                                 double value);
PM_API int pm_machine_set_point(const pm_rig* rig, void* machines, size_t capacity, size_t character, uint32_t input,
                                double x, double y);
PM_API int pm_machine_fire(const pm_rig* rig, void* machines, size_t capacity, size_t character, uint32_t input);
/* The state layer `layer` of a character is in (-1 before its first step). */
PM_API int pm_machine_state(const pm_rig* rig, const void* machines, size_t capacity, size_t character, uint32_t layer);
/* Steps `count` characters' machines into their tracks (pm_animator_*'s
 * memory for the same count). */
PM_API int pm_machine_step(const pm_rig* rig, void* machines, size_t capacity, size_t count, void* tracks,
                           size_t tracks_capacity);
/* The colour the characters' states set (format 1.10; MachineColourJob):
 * after pm_machine_step, with the update's dt, advances each character's
 * fade and writes `count` colours (NULL: none written) and, for a rig with
 * parts, count x pm_rig_part_count body part opacities (NULL: none), as
 * pm_draw_options' colours and part_opacities take them. */
PM_API int pm_machine_colours(const pm_rig* rig, void* machines, size_t capacity, size_t count, double dt,
                              pm_colour* colours, float* part_opacities, size_t part_opacities_capacity);
/* A channel's path events (format 1.8): their number, the path and time of
 * one, its name. */
PM_API uint32_t pm_channel_event_count(const pm_rig* rig, uint32_t channel); /* 0 for NULL */
PM_API int pm_channel_event(const pm_rig* rig, uint32_t channel, uint32_t event, uint32_t* path, double* time);
PM_API int pm_channel_event_name(const pm_rig* rig, uint32_t channel, uint32_t event, char* out, size_t capacity,
                                 size_t* length);

#ifdef __cplusplus
}
#endif

#endif /* POSEMORPH_ANIMATION_H */
