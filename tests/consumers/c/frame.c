/* SPDX-License-Identifier: MIT */
/* A C99 program against the installed runtime, built with pkg-config:
 * load a rig, sample its first path, evaluate one frame, print a hash. */
#include <posemorph/posemorph.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char** argv) {
  if (argc < 2) return 2;
  FILE* f = fopen(argv[1], "rb");
  if (!f) return 1;
  fseek(f, 0, SEEK_END);
  long size = ftell(f);
  fseek(f, 0, SEEK_SET);
  unsigned char* bytes = malloc((size_t)size);
  if (!bytes || fread(bytes, 1, (size_t)size, f) != (size_t)size) return 1;
  fclose(f);
  pm_rig* rig = NULL;
  pm_error err;
  if (pm_rig_load(bytes, (size_t)size, &rig, &err) != PM_OK) {
    fprintf(stderr, "%s: %s\n", argv[1], err.message);
    return 1;
  }
  free(bytes);
  pm_rig_info info;
  pm_rig_get_info(rig, &info);
  double px = 0, py = 0;
  if (info.path_count) pm_path_sample(rig, 0, 0.5, &px, &py);
  double* w = malloc(sizeof(double) * info.pose_count);
  double* ws = malloc(sizeof(double) * info.pose_count);
  double* work = malloc(sizeof(double) * pm_morph_workspace_size(rig));
  double* x = malloc(sizeof(double) * 2 * info.vertex_count);
  if (pm_weights(rig, px, py, 0, 1, w, ws, NULL, info.pose_count) != PM_OK ||
      pm_morph(rig, w, ws, 0, work, pm_morph_workspace_size(rig), x, NULL, 2 * (size_t)info.vertex_count) != PM_OK)
    return 1;
  unsigned long long h = 0xcbf29ce484222325ull;
  for (uint32_t k = 0; k < 2 * info.vertex_count; ++k) {
    const unsigned char* p = (const unsigned char*)&x[k];
    for (unsigned i = 0; i < sizeof x[k]; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
  }
  printf("%u vertices, frame %016llx\n", info.vertex_count, h);
  free(w), free(ws), free(work), free(x);
  pm_rig_free(rig);
  return 0;
}
