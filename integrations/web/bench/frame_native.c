// SPDX-License-Identifier: MIT
/* The benchmark page's native twin (bench/bench.mjs): the same frame through
 * the same shim (src/posemorph_web.c), compiled natively. One frame: every
 * character's body point from path 0 at f / 60 + 0.37 k (channels: their
 * path 0 at 0.8 f / 60 + 0.23 k c), then pmw_crowd_evaluate (every list,
 * every attachment, the draw steps). Prints the median over REPS runs of
 * FRAMES frames, in microseconds per frame:
 *   posemorph-web-bench-native RIG.pmrig CHARACTERS FRAMES REPS */
#define _POSIX_C_SOURCE 199309L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "../src/posemorph_web.h"

static double now_us(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return 1e6 * (double)t.tv_sec + 1e-3 * (double)t.tv_nsec;
}
static int compare(const void* a, const void* b) {
  double x = *(const double*)a, y = *(const double*)b;
  return (x > y) - (x < y);
}

/* Sets every character's points for frame f (as bench.mjs's pose()). */
static void pose(const pm_rig* rig, pmw_crowd* crowd, size_t n, uint32_t channels, int f) {
  double* points = pmw_crowd_points(crowd);
  double* channel_points = pmw_crowd_channel_points(crowd);
  const double* out = pmw_out();
  for (size_t k = 0; k < n; ++k) {
    if (pmw_channel_path_count(rig, 0) > 0) {
      pmw_channel_path_sample(rig, 0, 0, f / 60.0 + 0.37 * (double)k);
    } else {
      pmw_channel_pose_point(rig, 0, (uint32_t)(k % pmw_channel_pose_count(rig, 0)));
    }
    points[2 * k] = out[0], points[2 * k + 1] = out[1];
    for (uint32_t c = 1; c < channels; ++c) {
      if (pmw_channel_path_count(rig, c) > 0) {
        pmw_channel_path_sample(rig, c, 0, 0.8 * f / 60.0 + 0.23 * (double)k * c);
      } else {
        pmw_channel_pose_point(rig, c, 0);
      }
      size_t at = 2 * (k * (channels - 1) + c - 1);
      channel_points[at] = out[0], channel_points[at + 1] = out[1];
    }
  }
}

int main(int argc, char** argv) {
  if (argc != 5) {
    fprintf(stderr, "usage: posemorph-web-bench-native RIG.pmrig CHARACTERS FRAMES REPS\n");
    return 2;
  }
  FILE* f = fopen(argv[1], "rb");
  if (!f) return fprintf(stderr, "%s: cannot open the file\n", argv[1]), 1;
  fseek(f, 0, SEEK_END);
  long size = ftell(f);
  fseek(f, 0, SEEK_SET);
  unsigned char* bytes = (unsigned char*)malloc(size > 0 ? (size_t)size : 1);
  size_t got = fread(bytes, 1, size > 0 ? (size_t)size : 0, f);
  fclose(f);
  pm_rig* rig = pmw_rig_load(bytes, got, 0);
  free(bytes);
  if (!rig) return fprintf(stderr, "%s: %s\n", argv[1], pmw_error()), 1;
  size_t n = (size_t)atoi(argv[2]);
  int frames = atoi(argv[3]), reps = atoi(argv[4]);
  pmw_crowd* crowd = pmw_crowd_new(rig, n);
  if (!crowd || frames < 1 || reps < 1 || reps > 1000) return fprintf(stderr, "%s: no crowd\n", argv[1]), 1;
  uint32_t channels = pmw_rig_count(rig, 4);
  double times[1000];
  for (int w = 0; w < 20; ++w) {
    pose(rig, crowd, n, channels, w);
    pmw_crowd_evaluate(crowd, 0, channels > 1 ? 1 : 0, -1, 8, 1, 0);
  }
  for (int r = 0; r < reps; ++r) {
    double start = now_us();
    for (int i = 0; i < frames; ++i) {
      pose(rig, crowd, n, channels, i);
      if (pmw_crowd_evaluate(crowd, 0, channels > 1 ? 1 : 0, -1, 8, 1, 0) != PM_OK) {
        return fprintf(stderr, "%s: the frame was refused\n", argv[1]), 1;
      }
    }
    times[r] = (now_us() - start) / frames;
  }
  qsort(times, (size_t)reps, sizeof(double), compare);
  printf("%.3f\n", times[reps / 2]);
  pmw_crowd_free(crowd);
  pm_rig_free(rig);
  return 0;
}
