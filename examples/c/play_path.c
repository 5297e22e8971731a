// SPDX-License-Identifier: MIT
/* The smallest C program that uses posemorph: load a baked rig, play one of
 * its paths, and print what a renderer would draw each frame.
 *
 *   play_path RIG.pmrig [PATH-NAME]
 *
 * Everything here is C99 and the posemorph C API (posemorph/posemorph.h). */
#include <stdio.h>
#include <stdlib.h>

#include "posemorph/posemorph.h"

/* Reads a whole file; NULL (and a message naming it) if it cannot. */
static unsigned char* read_file(const char* path, size_t* size) {
  FILE* f = fopen(path, "rb");
  if (!f) return fprintf(stderr, "play_path: %s: cannot open the file\n", path), NULL;
  fseek(f, 0, SEEK_END);
  const long n = ftell(f);
  fseek(f, 0, SEEK_SET);
  unsigned char* bytes = n > 0 ? malloc((size_t)n) : NULL;
  if (!bytes || fread(bytes, 1, (size_t)n, f) != (size_t)n) {
    fprintf(stderr, "play_path: %s: cannot read the file\n", path);
    free(bytes), bytes = NULL;
  }
  fclose(f);
  *size = (size_t)n;
  return bytes;
}

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) return fprintf(stderr, "usage: play_path RIG.pmrig [PATH-NAME]\n"), 2;

  /* 1. Load. The rig copies what it needs: the file's bytes can go. */
  size_t size = 0;
  unsigned char* bytes = read_file(argv[1], &size);
  if (!bytes) return 1;
  pm_rig* rig = NULL;
  pm_error err;
  const int loaded = pm_rig_load(bytes, size, &rig, &err);
  free(bytes);
  if (loaded != PM_OK) return fprintf(stderr, "play_path: %s: %s\n", argv[1], err.message), 1;
  pm_rig_info info;
  pm_rig_get_info(rig, &info);
  printf("%s: %u vertices, %u triangles, %u poses, %u paths\n", argv[1], info.vertex_count, info.triangle_count,
         info.pose_count, info.path_count);

  /* 2. Pick a path: by name, or the first. */
  int path = argc == 3 ? pm_path_find(rig, argv[2]) : (info.path_count > 0 ? 0 : -1);
  if (path < 0) {
    fprintf(stderr, "play_path: %s: no path %s\n", argv[1], argc == 3 ? argv[2] : "at all");
    pm_rig_free(rig);
    return 1;
  }
  char name[64];
  pm_rig_path_name(rig, (uint32_t)path, name, sizeof name, NULL);

  /* 3. Buffers, once: the sizes come from the rig. */
  size_t work_size = 0, position_size = 0;
  pm_draw_list_buffers(rig, 1, &work_size, &position_size);
  double* work = malloc(work_size * sizeof(double));
  float* positions = malloc(position_size * sizeof(float));
  pm_draw_options options;
  pm_draw_options_default(&options);
  options.max_drawings = 2; /* this renderer blends two drawings at most */

  /* 4. Per frame: a point in pose space -> a draw list. No allocation here. */
  for (int frame = 0; frame < 6; ++frame) {
    const double seconds = frame * 0.25;
    double point[2];
    pm_path_sample(rig, (uint32_t)path, seconds, &point[0], &point[1]);
    pm_draw_list list;
    if (pm_draw_lists(rig, &options, 1, point, NULL, work, work_size, positions, position_size, &list, 1) != PM_OK) {
      fprintf(stderr, "play_path: evaluation failed\n");
      break;
    }
    /* A renderer would now upload list.positions (rig units, y up) and
     * list.indices, and blend the drawings of list.drawings[k].pose through
     * list.drawings[k].uvs with weight list.drawings[k].weight. */
    printf("%s t=%.2f point (%.3f, %.3f): vertex 0 at (%.3f, %.3f);", name, seconds, point[0], point[1],
           list.positions[0], list.positions[1]);
    for (uint32_t k = 0; k < list.drawing_count; ++k)
      printf(" drawing %u x %.3f", list.drawings[k].pose, list.drawings[k].weight);
    printf("\n");
  }

  free(work);
  free(positions);
  pm_rig_free(rig);
  return 0;
}
