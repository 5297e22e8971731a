// SPDX-License-Identifier: MIT
/* The C API from C99: load a baked rig from a file, evaluate at each pose
 * point and check the pose comes back, play a path, quantise, and reject a
 * truncated copy; with a second rig that has control channels, evaluate its
 * attachments and animate it. Usage: c_api_test RIG.pmrig [CHANNELS.pmrig] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "posemorph/posemorph.h"

static int failures = 0;
#define EXPECT(cond)                                                     \
  do {                                                                   \
    if (!(cond)) {                                                       \
      fprintf(stderr, "%s:%d: failed: %s\n", __FILE__, __LINE__, #cond); \
      ++failures;                                                        \
    }                                                                    \
  } while (0)

static unsigned char* ReadFile(const char* path, long* size) {
  FILE* f = fopen(path, "rb");
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  *size = ftell(f);
  fseek(f, 0, SEEK_SET);
  unsigned char* bytes = malloc((size_t)*size);
  if (fread(bytes, 1, (size_t)*size, f) != (size_t)*size) bytes = NULL;
  fclose(f);
  return bytes;
}

/* The distance between attachment a's joint (in its positions q) and its
 * parent's point (in the body's positions x). */
static double JointGap(const pm_rig* rig, uint32_t a, const double* x, const double* q) {
  pm_attachment at;
  if (pm_rig_attachment(rig, a, &at) != PM_OK) return 1e300;
  const uint32_t* body = pm_rig_triangles(rig) + 3 * (size_t)at.parent_triangle;
  const uint32_t* own = pm_rig_attachment_triangles(rig, a) + 3 * (size_t)at.joint_triangle;
  double p[2] = {0, 0}, j[2] = {0, 0};
  for (int c = 0; c < 2; ++c)
    for (int k = 0; k < 3; ++k) {
      p[c] += at.parent_weights[k] * x[2 * body[k] + c];
      j[c] += at.joint_weights[k] * q[2 * own[k] + c];
    }
  return hypot(p[0] - j[0], p[1] - j[1]);
}

/* Load limits: the untrusted bounds, a rig within them loading each way,
 * and one bound below the rig's count refusing it with its name, the
 * memory size query included. */
static void Limits(const unsigned char* bytes, size_t size) {
  pm_load_limits limits;
  pm_load_limits_untrusted(&limits);
  EXPECT(limits.max_bytes == 4u << 20 && limits.max_memory == 32u << 20 && limits.max_vertices == 20000 &&
         limits.max_poses == 64 && limits.max_attachments == 8 && limits.max_factor_nonzeros == 1000000 &&
         limits.max_fill == 8);
  pm_rig* rig = NULL;
  pm_error err;
  EXPECT(pm_rig_load_limited(bytes, size, &limits, &rig, &err) == PM_OK);
  pm_rig_info info;
  pm_rig_get_info(rig, &info);
  pm_rig_free(rig);
  size_t needed = 0;
  EXPECT(pm_rig_memory_size_limited(bytes, size, &limits, &needed, &err) == PM_OK && needed > 0);
  unsigned char* block = malloc(needed + PM_RIG_MEMORY_ALIGNMENT);
  void* memory = block + (PM_RIG_MEMORY_ALIGNMENT - (size_t)block % PM_RIG_MEMORY_ALIGNMENT) % PM_RIG_MEMORY_ALIGNMENT;
  rig = NULL;
  EXPECT(pm_rig_load_in_place_limited(bytes, size, &limits, memory, needed, &rig, &err) == PM_OK);
  pm_rig_free(rig);
  limits.max_vertices = info.vertex_count - 1;
  rig = NULL;
  EXPECT(pm_rig_load_limited(bytes, size, &limits, &rig, &err) == PM_ERROR_TOO_LARGE && rig == NULL);
  EXPECT(strstr(err.message, "(LoadLimits::max_vertices)") != NULL);
  EXPECT(pm_rig_memory_size_limited(bytes, size, &limits, &needed, &err) == PM_ERROR_TOO_LARGE);
  EXPECT(pm_rig_load_in_place_limited(bytes, size, &limits, memory, needed, &rig, &err) == PM_ERROR_TOO_LARGE);
  free(block);
}

/* A rig with a face channel: names, weights per channel, the attachments
 * placed with their joints on the body, one character and a batch agreeing
 * bit for bit, and bad arguments refused. */
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
  printf("c_api_test: animator: %zu events over 1.5 s for %d characters, weights within %g of the path's\n", seen,
         kCount, worst);
  free(raw), free(limited), free(w), free(wl), free(path_raw), free(path_limited), free(tracks);
}

static void Channels(const char* path) {
  long size = 0;
  unsigned char* bytes = ReadFile(path, &size);
  EXPECT(bytes != NULL);
  if (!bytes) return;
  pm_rig* rig = NULL;
  pm_error err;
  EXPECT(pm_rig_load(bytes, (size_t)size, &rig, &err) == PM_OK);
  if (!rig) return;
  EXPECT(pm_rig_channel_count(rig) == 2);
  EXPECT(pm_rig_attachment_count(rig) == 3);
  EXPECT(pm_rig_find_channel(rig, "face") == 1 && pm_rig_find_channel(rig, "nose") == -1);
  char name[16];
  size_t length = 0;
  EXPECT(pm_rig_channel_name(rig, 1, name, sizeof name, &length) == PM_OK && strcmp(name, "face") == 0);
  EXPECT(pm_rig_channel_name(rig, 2, name, sizeof name, &length) == PM_ERROR_INVALID_ARGUMENT);
  EXPECT(pm_rig_attachment_name(rig, 2, name, sizeof name, &length) == PM_OK && strcmp(name, "mouth") == 0);
  uint32_t face_poses = 0;
  double points[8];
  EXPECT(pm_rig_channel_poses(rig, 1, &face_poses, points, 8) == PM_OK && face_poses == 4);
  pm_grid_info grid;
  EXPECT(pm_rig_channel_grid(rig, 1, &grid) == PM_OK && grid.cells_x > 0);
  /* 4 bytes per channel: a point of the face's space comes back within a step of its grid. */
  {
    const double fx = 0.37, fy = 0.61;
    double gx = 0, gy = 0;
    pm_channel_dequantize_point(rig, 1, pm_channel_quantize_point(rig, 1, fx, fy), &gx, &gy);
    EXPECT(fabs(gx - fx) <= (grid.max_x - grid.min_x) / 65535 && fabs(gy - fy) <= (grid.max_y - grid.min_y) / 65535);
    EXPECT(pm_channel_quantize_point(rig, 2, fx, fy) == 0);
  }
  pm_rig_info info;
  pm_rig_get_info(rig, &info);
  const size_t N = info.pose_count, NW = pm_rig_attached_weight_count(rig);
  const size_t v2 = 2 * (size_t)info.vertex_count, a2 = 2 * (size_t)pm_rig_attached_vertex_count(rig);
  EXPECT(NW == 4 && pm_rig_channel_weight_offset(rig, 1) == 0);
  for (uint32_t a = 0; a < 3; ++a) {
    pm_attachment at;
    EXPECT(pm_rig_attachment(rig, a, &at) == PM_OK && at.channel == 1 && at.pose_count == 4 && at.draw_order == 3);
    EXPECT(pm_rig_attachment_uvs(rig, a, 3) != NULL && pm_rig_attachment_uvs(rig, a, 4) == NULL);
  }
  EXPECT(pm_rig_attachment_triangles(rig, 3) == NULL);
  /* Five characters: the body along its path, the face along its own. */
  enum { kCount = 5 };
  double* raw = calloc(kCount * N, sizeof(double));
  double* limited = calloc(kCount * N, sizeof(double));
  double* w = calloc(kCount * NW, sizeof(double));
  double* wl = calloc(kCount * NW, sizeof(double));
  double* body = calloc(kCount * v2, sizeof(double));
  double* attached = calloc(kCount * a2, sizeof(double));
  double* one = calloc(a2, sizeof(double));
  const size_t work_size = pm_batch_workspace_size(rig) > pm_attach_workspace_size(rig) ? pm_batch_workspace_size(rig)
                                                                                        : pm_attach_workspace_size(rig);
  double* work = calloc(work_size, sizeof(double));
  const int chatter = pm_channel_path_find(rig, 1, "chatter");
  EXPECT(chatter == 0);
  for (size_t k = 0; k < kCount; ++k) {
    double bx, by, fx, fy;
    EXPECT(pm_path_sample(rig, 0, 0.7 * (double)k, &bx, &by) == PM_OK);
    EXPECT(pm_channel_path_sample(rig, 1, (uint32_t)chatter, 0.45 * (double)k, &fx, &fy) == PM_OK);
    EXPECT(pm_weights(rig, bx, by, 0, 1, raw + k * N, limited + k * N, NULL, N) == PM_OK);
    EXPECT(pm_channel_weights(rig, 1, fx, fy, 0, 1, w + k * NW, wl + k * NW, NULL, NW) == PM_OK);
  }
  EXPECT(pm_morph_batch(rig, kCount, raw, limited, work, work_size, body, NULL, kCount * v2) == PM_OK);
  EXPECT(pm_attach(rig, kCount, body, kCount * v2, w, wl, kCount * NW, 0, work, work_size, attached, NULL,
                   kCount * a2) == PM_OK);
  double gap = 0;
  int same = 1;
  for (size_t k = 0; k < kCount; ++k) {
    EXPECT(pm_attach(rig, 1, body + k * v2, v2, w + k * NW, wl + k * NW, NW, 0, work, work_size, one, NULL, a2) ==
           PM_OK);
    /* The batch holds attachment after attachment, each character after character. */
    size_t at = 0;
    for (uint32_t a = 0; a < 3; ++a) {
      pm_attachment info_a;
      pm_rig_attachment(rig, a, &info_a);
      const size_t p2 = 2 * (size_t)info_a.vertex_count;
      same &= memcmp(attached + at * kCount + k * p2, one + at, p2 * sizeof(double)) == 0;
      gap = fmax(gap, JointGap(rig, a, body + k * v2, one + at));
      at += p2;
    }
  }
  EXPECT(same);
  EXPECT(gap <= 1e-9 * info.size);
  EXPECT(pm_attach(rig, 1, body, v2 - 1, w, wl, NW, 0, work, work_size, one, NULL, a2) == PM_ERROR_BUFFER_TOO_SMALL);
  EXPECT(pm_attach(rig, 1, body, v2, w, wl, NW, 0, work, work_size, one, NULL, a2 - 1) == PM_ERROR_BUFFER_TOO_SMALL);
  EXPECT(pm_attach(NULL, 1, body, v2, w, wl, NW, 0, work, work_size, one, NULL, a2) == PM_ERROR_INVALID_ARGUMENT);
  w[1] = NAN;
  EXPECT(pm_attach(rig, 1, body, v2, w, wl, NW, 0, work, work_size, one, NULL, a2) == PM_ERROR_INVALID_ARGUMENT);
  printf("c_api_test: %s: %u channels, %u attachments, joint gap %g over %d characters\n", path,
         pm_rig_channel_count(rig), pm_rig_attachment_count(rig), gap, kCount);
  free(raw), free(limited), free(w), free(wl), free(body), free(attached), free(one), free(work);
  Animator(rig);
  pm_rig_free(rig);
  free(bytes);
}

int main(int argc, char** argv) {
  if (argc != 2 && argc != 3) return 2;
  long size = 0;
  unsigned char* bytes = ReadFile(argv[1], &size);
  if (!bytes) return 2;

  pm_rig* rig = NULL;
  pm_error err;
  EXPECT(pm_rig_load(bytes, (size_t)size / 2, &rig, &err) == PM_ERROR_TRUNCATED);
  EXPECT(rig == NULL && err.message[0] != 0);
  EXPECT(pm_rig_load(bytes, (size_t)size, &rig, &err) == PM_OK);
  if (!rig) return 1;

  pm_rig_info info;
  pm_rig_get_info(rig, &info);
  double* raw = calloc(info.pose_count, sizeof(double));
  double* limited = calloc(info.pose_count, sizeof(double));
  double* tex = calloc(info.pose_count, sizeof(double));
  double* work = calloc(pm_morph_workspace_size(rig), sizeof(double));
  double* x = calloc(2 * info.vertex_count, sizeof(double));
  float* xf = calloc(2 * info.vertex_count, sizeof(float));
  for (uint32_t i = 0; i < info.pose_count; ++i) {
    double px, py;
    EXPECT(pm_rig_pose_point(rig, i, &px, &py) == PM_OK);
    EXPECT(pm_weights(rig, px, py, info.default_sigma, 1, raw, limited, tex, info.pose_count) == PM_OK);
    EXPECT(fabs(raw[i] - 1) < 1e-12 && fabs(tex[i] - 1) < 1e-12);
    EXPECT(pm_morph(rig, raw, limited, 0, work, pm_morph_workspace_size(rig), x, xf, 2 * (size_t)info.vertex_count) ==
           PM_OK);
    const double* q = pm_rig_pose_positions(rig, i);
    double worst = 0;
    for (uint32_t k = 0; k < 2 * info.vertex_count; ++k) worst = fmax(worst, fabs(x[k] - q[k]));
    EXPECT(worst <= 1e-9 * info.size);
  }
  /* A batch of all poses at once gives what pm_morph gave, bit for bit. */
  {
    const size_t n = info.pose_count, v2 = 2 * (size_t)info.vertex_count;
    double* bw = calloc(n * n, sizeof(double));
    double* bws = calloc(n * n, sizeof(double));
    double* bwork = calloc(pm_batch_workspace_size(rig), sizeof(double));
    double* bx = calloc(n * v2, sizeof(double));
    for (uint32_t i = 0; i < info.pose_count; ++i) {
      double px, py;
      pm_rig_pose_point(rig, i, &px, &py);
      pm_weights(rig, px, py, 0, 1, bw + i * n, bws + i * n, NULL, n);
    }
    EXPECT(pm_morph_batch(rig, n, bw, bws, bwork, pm_batch_workspace_size(rig), bx, NULL, n * v2) == PM_OK);
    EXPECT(pm_morph_batch(rig, n, bw, bws, bwork, pm_batch_workspace_size(rig), bx, NULL, n * v2 - 1) ==
           PM_ERROR_BUFFER_TOO_SMALL);
    for (uint32_t i = 0; i < info.pose_count; ++i) {
      EXPECT(pm_morph(rig, bw + i * n, bws + i * n, 0, work, pm_morph_workspace_size(rig), x, NULL, v2) == PM_OK);
      EXPECT(memcmp(x, bx + i * v2, v2 * sizeof(double)) == 0);
    }
    EXPECT(pm_morph_batch(rig, n, bw, bws, bwork, pm_batch_workspace_size(rig), NULL, NULL, 0) ==
           PM_ERROR_INVALID_ARGUMENT);
    free(bw), free(bws), free(bwork), free(bx);
  }
  EXPECT(pm_path_find(rig, "no such path") == -1);
  if (info.path_count > 0) {
    double px, py;
    EXPECT(pm_path_sample(rig, 0, 0.25, &px, &py) == PM_OK);
    uint32_t packed = pm_quantize_point(rig, px, py);
    double qx, qy;
    pm_dequantize_point(rig, packed, &qx, &qy);
    EXPECT(fabs(qx - px) < 1e-3 && fabs(qy - py) < 1e-3);
  }
  EXPECT(pm_morph(rig, raw, limited, 0, NULL, 0, x, NULL, 2 * (size_t)info.vertex_count) == PM_ERROR_INVALID_ARGUMENT);
  /* Capacities: a buffer one short, or misaligned, is refused and left untouched. */
  EXPECT(pm_weights(rig, 0, 0, 0, 1, raw, limited, NULL, info.pose_count - 1) == PM_ERROR_BUFFER_TOO_SMALL);
  EXPECT(pm_morph(rig, raw, limited, 0, work, pm_morph_workspace_size(rig) - 1, x, NULL,
                  2 * (size_t)info.vertex_count) == PM_ERROR_BUFFER_TOO_SMALL);
  x[0] = 12345;
  EXPECT(pm_morph(rig, raw, limited, 0, work, pm_morph_workspace_size(rig), x, NULL,
                  2 * (size_t)info.vertex_count - 1) == PM_ERROR_BUFFER_TOO_SMALL);
  EXPECT(x[0] == 12345);
  EXPECT(pm_morph(rig, raw, limited, 0, work, pm_morph_workspace_size(rig), (double*)((char*)x + 1), NULL,
                  2 * (size_t)info.vertex_count - 1) == PM_ERROR_INVALID_ARGUMENT);
  /* What a renderer and a UI need to know about the rig. */
  {
    char name[64];
    size_t length = 0;
    EXPECT(strcmp(pm_version(), "0.5.0") == 0);
    EXPECT(pm_rig_pose_name(rig, 0, name, sizeof name, &length) == PM_OK && length == strlen(name) && length > 0);
    EXPECT(pm_rig_pose_name(rig, 0, name, length, &length) == PM_ERROR_BUFFER_TOO_SMALL && length == strlen(name));
    EXPECT(pm_rig_pose_name(rig, info.pose_count, name, sizeof name, &length) == PM_ERROR_INVALID_ARGUMENT);
    EXPECT(pm_rig_pose_image(rig, 0, name, sizeof name, &length) == PM_OK);
    /* The snake has no drawings: the bake records no folder. */
    EXPECT(pm_rig_drawing_folder(rig, name, sizeof name, &length) == PM_OK && length == 0 && name[0] == 0);
    EXPECT(pm_rig_drawing_folder(NULL, name, sizeof name, &length) == PM_ERROR_INVALID_ARGUMENT);
    /* The snake is one shape: one part, every triangle, named "", the poses' images. */
    {
      pm_part part;
      EXPECT(pm_rig_part_count(rig) == 1 && pm_rig_part_count(NULL) == 0);
      EXPECT(pm_rig_part(rig, 0, &part) == PM_OK && part.first_triangle == 0 &&
             part.triangle_count == info.triangle_count && part.draw_order == 0);
      EXPECT(pm_rig_part(rig, 1, &part) == PM_ERROR_INVALID_ARGUMENT);
      EXPECT(pm_rig_part_name(rig, 0, name, sizeof name, &length) == PM_OK && length == 0);
      EXPECT(pm_rig_part_image(rig, 0, info.pose_count, name, sizeof name, &length) == PM_ERROR_INVALID_ARGUMENT);
      {
        int32_t order = 9;
        EXPECT(pm_rig_part_draw_order(rig, 0, info.pose_count - 1, &order) == PM_OK && order == 0);
        EXPECT(pm_rig_part_draw_order(rig, 0, info.pose_count, &order) == PM_ERROR_INVALID_ARGUMENT);
        EXPECT(pm_rig_part_draw_order(rig, 1, 0, &order) == PM_ERROR_INVALID_ARGUMENT);
        EXPECT(pm_rig_part_draw_order(rig, 0, 0, NULL) == PM_ERROR_INVALID_ARGUMENT);
      }
    }
    if (info.path_count)
      EXPECT(pm_rig_path_name(rig, 0, name, sizeof name, NULL) == PM_OK && pm_path_find(rig, name) == 0);
    pm_grid_info grid;
    EXPECT(pm_rig_grid(rig, &grid) == PM_OK && grid.max_x > grid.min_x && grid.max_y > grid.min_y);
    EXPECT(fabs(grid.max_x - grid.min_x - grid.cell * grid.cells_x) < 1e-9);
    pm_bounds pose_bounds, hull;
    EXPECT(pm_rig_pose_bounds(rig, 0, &pose_bounds) == PM_OK && pose_bounds.max_x > pose_bounds.min_x);
    double* hull_work = calloc(pm_hull_bounds_workspace_size(rig), sizeof(double));
    EXPECT(pm_rig_hull_bounds(rig, 8, hull_work, pm_hull_bounds_workspace_size(rig) - 1, &hull) ==
           PM_ERROR_BUFFER_TOO_SMALL);
    EXPECT(pm_rig_hull_bounds(rig, 8, hull_work, pm_hull_bounds_workspace_size(rig), &hull) == PM_OK);
    for (uint32_t i = 0; i < info.pose_count; ++i) { /* the hull's bounds hold every pose's */
      EXPECT(pm_rig_pose_bounds(rig, i, &pose_bounds) == PM_OK);
      EXPECT(hull.min_x <= pose_bounds.min_x && hull.max_x >= pose_bounds.max_x);
      EXPECT(hull.min_y <= pose_bounds.min_y && hull.max_y >= pose_bounds.max_y);
    }
    free(hull_work);
    pm_canvas canvas;
    EXPECT(pm_rig_pose_canvas(rig, 0, &canvas) == PM_OK);
    EXPECT(pm_rig_texture_filter(rig) == PM_FILTER_LINEAR); /* no "filter" in the description */
    EXPECT(pm_rig_texture_filter(NULL) == PM_FILTER_LINEAR);
    EXPECT(pm_rig_pose_canvas(rig, info.pose_count, &canvas) == PM_ERROR_INVALID_ARGUMENT);
    uint32_t crc = 0, crc_at = 0, major = 0, minor = 9;
    memcpy(&crc_at, bytes + 32, 4); /* the header's checksum field */
    EXPECT(pm_rig_checksum(rig, &crc) == PM_OK && crc == crc_at);
    EXPECT(pm_rig_format_version(rig, &major, &minor) == PM_OK && major == 1 && minor == 9);
  }
  EXPECT(pm_rig_channel_count(rig) == 1 && pm_rig_attachment_count(rig) == 0);
  EXPECT(pm_rig_channel_count(NULL) == 0 && pm_rig_attached_vertex_count(rig) == 0);
  pm_rig_free(rig);
  Limits(bytes, (size_t)size);
  free(bytes), free(raw), free(limited), free(tex), free(work), free(x), free(xf);
  if (argc == 3) Channels(argv[2]);
  printf("c_api_test: %s\n", failures ? "FAILED" : "ok");
  return failures ? 1 : 0;
}
