// SPDX-License-Identifier: MIT
/* The animator and the state machine from C99, on Pell with a face: tracks
 * and machines in memory the test owns, commands, updates, events, a late
 * joiner's state, and the sample's state machine driven by its inputs.
 * Usage: c_api_animator_test PELL_FACE.pmrig */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "c_test_support.h"
#include "posemorph/posemorph.h"

/* The animator from C: two characters' tracks in memory the test owns;
 * character 0 plays the body's path with no mix, so its weights are the
 * path's at the same time; character 1 blinks and looks; events name
 * themselves; bad characters, channels and buffers are refused. */
static void Animator(const pm_rig* rig) {
  enum { kCount = 2 };
  pm_rig_info info;
  pm_rig_get_info(rig, &info);
  const size_t N = info.pose_count, NW = pm_rig_attached_weight_count(rig);
  const size_t size = pm_animator_size(rig, kCount);
  EXPECT(size > 0 && size % PM_ANIMATOR_ALIGNMENT == 0 && pm_animator_size(NULL, 1) == 0);
  void* tracks = malloc(size + 8);
  EXPECT(pm_animator_reset(rig, tracks, size - 1, kCount) == PM_ERROR_BUFFER_TOO_SMALL);
  EXPECT(pm_animator_reset(rig, (char*)tracks + 4, size, kCount) == PM_ERROR_INVALID_ARGUMENT);
  EXPECT(pm_animator_reset(rig, tracks, size, kCount) == PM_OK);
  pm_play_options once;
  pm_play_options_default(&once);
  EXPECT(once.speed == 1 && once.loop == -1 && once.mix > 0);
  once.mix = 0;
  EXPECT(pm_animator_play(rig, tracks, size, 0, 0, 0, &once) == PM_OK);
  EXPECT(pm_animator_play(rig, tracks, size, 1, 0, 0, NULL) == PM_OK);
  EXPECT(pm_animator_play(rig, tracks, size, 0, 2, 0, &once) == PM_ERROR_INVALID_ARGUMENT); /* no channel 2 */
  EXPECT(pm_animator_play(rig, tracks, size, 0, 0, 9, &once) == PM_ERROR_INVALID_ARGUMENT); /* no path 9 */
  EXPECT(pm_animator_play(rig, tracks, size, kCount, 0, 0, &once) == PM_ERROR_BUFFER_TOO_SMALL);
  pm_behaviours b;
  pm_behaviours_default(&b);
  EXPECT(!b.blink_enabled && b.blink_interval > 0 && b.spring_frequency > 0);
  b.blink_enabled = 1, b.blink_pose = 3, b.blink_interval = 0.3;
  b.look_at_enabled = 1;
  EXPECT(pm_animator_set_behaviours(rig, tracks, size, 1, 1, &b) == PM_OK);
  EXPECT(pm_animator_look_at(rig, tracks, size, 1, 1, 1.0, 0.0) == PM_OK);
  EXPECT(pm_animator_set_behaviours(rig, tracks, size, 1, 1, NULL) == PM_ERROR_INVALID_ARGUMENT);
  double* raw = calloc(kCount * N, sizeof(double));
  double* limited = calloc(kCount * N, sizeof(double));
  double* w = calloc(kCount * NW, sizeof(double));
  double* wl = calloc(kCount * NW, sizeof(double));
  double* path_raw = calloc(N, sizeof(double));
  double* path_limited = calloc(N, sizeof(double));
  pm_animator_event events[16];
  size_t written = 0, seen = 0, named = 0;
  uint64_t missed = 0;
  double worst = 0, worst_sum = 0;
  for (int f = 1; f <= 90; ++f) {
    EXPECT(pm_animator_update(rig, tracks, size, kCount, 1.0 / 60, -1, 1, raw, limited, NULL, kCount * N, w, wl, NULL,
                              kCount * NW, events, 16, &written, &missed) == PM_OK);
    double x = 0, y = 0;
    EXPECT(pm_path_sample(rig, 0, f / 60.0, &x, &y) == PM_OK);
    EXPECT(pm_weights(rig, x, y, -1, 1, path_raw, path_limited, NULL, N) == PM_OK);
    for (size_t i = 0; i < N; ++i) worst = fmax(worst, fabs(raw[i] - path_raw[i]));
    for (size_t k = 0; k < kCount; ++k) {
      double s = 0;
      for (size_t i = 0; i < NW; ++i) s += w[k * NW + i];
      worst_sum = fmax(worst_sum, fabs(s - 1));
    }
    for (size_t e = 0; e < written; ++e) {
      char name[32];
      size_t length = 0;
      uint32_t path = 9;
      double time = -1;
      EXPECT(events[e].character < kCount && events[e].channel < 2 && (events[e].outgoing & ~1) == 0);
      EXPECT(events[e].time >= 0 && events[e].time <= 1.0 / 60);
      EXPECT(pm_channel_event(rig, events[e].channel, events[e].event, &path, &time) == PM_OK && path == 0);
      if (pm_channel_event_name(rig, events[e].channel, events[e].event, name, sizeof name, &length) == PM_OK &&
          strcmp(name, "wave-peak") == 0)
        ++named;
      ++seen;
    }
  }
  EXPECT(worst <= 1e-12);     /* no mix, no behaviours on the body: the path's own weights */
  EXPECT(worst_sum <= 1e-12); /* blinks keep a partition of unity */
  EXPECT(named == kCount);    /* "greet" reaches its wave at 0.8 s: once per character */
  EXPECT(seen >= named && missed == 0);
  EXPECT(pm_channel_event_count(rig, 0) == 4 && pm_channel_event_count(rig, 2) == 0);
  EXPECT(pm_animator_update(rig, tracks, size, kCount, 1.0 / 60, -1, 1, raw, limited, NULL, kCount * N - 1, w, wl, NULL,
                            kCount * NW, NULL, 0, NULL, NULL) == PM_ERROR_BUFFER_TOO_SMALL);
  EXPECT(pm_animator_update(rig, tracks, size, kCount, 1.0 / 60, -1, 1, raw, limited, NULL, kCount * N, NULL, wl, NULL,
                            kCount * NW, NULL, 0, NULL, NULL) == PM_ERROR_INVALID_ARGUMENT);
  EXPECT(pm_animator_update(rig, tracks, size, kCount, NAN, -1, 1, raw, limited, NULL, kCount * N, w, wl, NULL,
                            kCount * NW, events, 16, NULL, &missed) == PM_ERROR_INVALID_ARGUMENT);
  /* A late joiner: character 1's state loaded into character 0; both then give the same weights. */
  {
    unsigned char state[4096];
    size_t n = 0;
    EXPECT(pm_animator_state_size(rig, tracks, size, 1) > 5);
    EXPECT(pm_animator_save(rig, tracks, size, 1, state, 4, &n) == PM_ERROR_BUFFER_TOO_SMALL);
    EXPECT(pm_animator_save(rig, tracks, size, 1, state, sizeof state, &n) == PM_OK);
    EXPECT(n == pm_animator_state_size(rig, tracks, size, 1));
    EXPECT(pm_animator_load(rig, state, n - 1, tracks, size, 0) == PM_ERROR_BAD_VALUE);
    EXPECT(pm_animator_load(rig, state, n, tracks, size, 0) == PM_OK);
    EXPECT(pm_animator_update(rig, tracks, size, kCount, 0.25, -1, 1, raw, limited, NULL, kCount * N, w, wl, NULL,
                              kCount * NW, NULL, 0, NULL, NULL) == PM_OK);
    EXPECT(memcmp(raw, raw + N, N * sizeof(double)) == 0 && memcmp(w, w + NW, NW * sizeof(double)) == 0);
  }
  printf("c_api_animator_test: animator: %zu events over 1.5 s for %d characters, weights within %g of the path's\n",
         seen, kCount, worst);
  free(raw), free(limited), free(w), free(wl), free(path_raw), free(path_limited), free(tracks);
}

/* The sample's machine: idle until "wave" fires, then waving; the face
 * chats while "talking". */
static void Machine(const pm_rig* rig) {
  enum { kCount = 2 };
  pm_rig_info info;
  pm_rig_get_info(rig, &info);
  const size_t N = info.pose_count, NW = pm_rig_attached_weight_count(rig);
  const size_t size = pm_animator_size(rig, kCount), msize = pm_machine_size(rig, kCount);
  EXPECT(msize > 0);
  void* tracks = malloc(size);
  void* machines = malloc(msize);
  EXPECT(pm_animator_reset(rig, tracks, size, kCount) == PM_OK);
  EXPECT(pm_machine_reset(rig, machines, msize - 1, kCount) == PM_ERROR_BUFFER_TOO_SMALL);
  EXPECT(pm_machine_reset(rig, machines, msize, kCount) == PM_OK);
  EXPECT(pm_machine_state(rig, machines, msize, 0, 0) == -1); /* before the first step */
  const int wave = pm_machine_find_input(rig, "wave"), talking = pm_machine_find_input(rig, "talking");
  EXPECT(wave >= 0 && talking >= 0 && pm_machine_find_input(rig, "fly") == -1);
  EXPECT(pm_machine_set_number(rig, machines, msize, 0, (uint32_t)wave, 1) == PM_ERROR_INVALID_ARGUMENT);
  double* raw = calloc(kCount * N, sizeof(double));
  double* limited = calloc(kCount * N, sizeof(double));
  double* w = calloc(kCount * NW, sizeof(double));
  double* wl = calloc(kCount * NW, sizeof(double));
  for (int f = 0; f < 40; ++f) {
    if (f == 10) {
      EXPECT(pm_machine_fire(rig, machines, msize, 1, (uint32_t)wave) == PM_OK);
      EXPECT(pm_machine_set_bool(rig, machines, msize, 1, (uint32_t)talking, 1) == PM_OK);
    }
    EXPECT(pm_machine_step(rig, machines, msize, kCount, tracks, size) == PM_OK);
    EXPECT(pm_animator_update(rig, tracks, size, kCount, 1.0 / 60, -1, 1, raw, limited, NULL, kCount * N, w, wl, NULL,
                              kCount * NW, NULL, 0, NULL, NULL) == PM_OK);
  }
  char name[32];
  size_t length = 0;
  EXPECT(pm_machine_state_name(rig, (uint32_t)pm_machine_state(rig, machines, msize, 0, 0), name, sizeof name,
                               &length) == PM_OK &&
         strcmp(name, "idle") == 0);
  EXPECT(pm_machine_state_name(rig, (uint32_t)pm_machine_state(rig, machines, msize, 1, 0), name, sizeof name,
                               &length) == PM_OK &&
         strcmp(name, "waving") == 0);
  EXPECT(pm_machine_state(rig, machines, msize, 1, 1) == pm_machine_find_state(rig, "chatting"));
  EXPECT(pm_machine_step(rig, machines, msize, kCount, tracks, size - 1) == PM_ERROR_BUFFER_TOO_SMALL);
  /* Colour set by states (format 1.10): character 0 turns into the ghost,
   * fading over its 0.6 s mix; character 1 stays as drawn. */
  const int ghost = pm_machine_find_input(rig, "ghost");
  const size_t P = pm_rig_part_count(rig);
  EXPECT(ghost >= 0 && P == 4);
  EXPECT(pm_machine_set_bool(rig, machines, msize, 0, (uint32_t)ghost, 1) == PM_OK);
  pm_colour colours[kCount];
  float* parts = calloc(kCount * P, sizeof(float));
  for (int f = 0; f < 18; ++f) { /* 0.3 s: half way */
    EXPECT(pm_machine_step(rig, machines, msize, kCount, tracks, size) == PM_OK);
    EXPECT(pm_machine_colours(rig, machines, msize, kCount, 1.0 / 60, colours, parts, kCount * P) == PM_OK);
  }
  EXPECT(fabsf(colours[0].r - 0.85f) < 1e-4f && fabsf(colours[0].g - 0.925f) < 1e-4f && colours[0].b == 1);
  EXPECT(fabsf(parts[0] - 0.65f) < 1e-4f && parts[3] == 1); /* the body half way to 0.3, the head whole */
  EXPECT(colours[1].r == 1 && colours[1].a == 1 && parts[P] == 1);
  EXPECT(pm_machine_colours(rig, machines, msize, kCount, 0, colours, parts, kCount * P - 1) ==
         PM_ERROR_BUFFER_TOO_SMALL);
  printf("c_api_animator_test: machine: character 1 waving and chatting after its inputs, character 0 a ghost\n");
  free(parts), free(raw), free(limited), free(w), free(wl), free(tracks), free(machines);
}

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  long size = 0;
  unsigned char* bytes = ReadFile(argv[1], &size);
  if (!bytes) return 2;
  pm_rig* rig = NULL;
  pm_error err;
  EXPECT(pm_rig_load(bytes, (size_t)size, &rig, &err) == PM_OK);
  if (!rig) return 1;
  Animator(rig);
  Machine(rig);
  pm_rig_free(rig);
  free(bytes);
  printf("c_api_animator_test: %s\n", failures ? "FAILED" : "ok");
  return failures ? 1 : 0;
}
