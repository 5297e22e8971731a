// SPDX-License-Identifier: MIT
/* The C API from C99: load a baked rig from a file, evaluate at each pose
 * point and check the pose comes back, play a path, quantise, and reject a
 * truncated copy; with a second rig that has control channels, evaluate its
 * attachments (c_api_animator_test.c animates it). Usage: c_api_test RIG.pmrig [CHANNELS.pmrig] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "posemorph/posemorph.h"

#include "c_test_support.h"

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
  pm_rig_free(rig);
  free(bytes);
}

/* Pell with a face drawn from pm_character_draw_lists alone: the body's and
 * the attachments' positions are pm_morph_batch's and pm_attach's floats bit
 * for bit, every step names a part with its drawings, and the steps draw
 * every triangle of the character once, back to front. */
static void DrawCharacter(const char* path) {
  long size = 0;
  unsigned char* bytes = ReadFile(path, &size);
  pm_rig* rig = NULL;
  pm_error err;
  EXPECT(bytes && pm_rig_load(bytes, (size_t)size, &rig, &err) == PM_OK);
  if (!rig) return;
  enum { kCount = 4 };
  pm_character_buffer_sizes sizes;
  EXPECT(pm_character_buffers(rig, kCount, &sizes) == PM_OK);
  double* work = calloc(sizes.workspace_doubles, sizeof(double));
  float* positions = calloc(sizes.position_floats, sizeof(float));
  float* attached_positions = calloc(sizes.attached_position_floats, sizeof(float));
  pm_draw_list* lists = calloc(kCount, sizeof(pm_draw_list));
  pm_draw_list* attached = calloc(sizes.attached_lists, sizeof(pm_draw_list));
  double points[2 * kCount], face_points[2 * kCount];
  pm_transform places[kCount];
  for (int k = 0; k < kCount; ++k) {
    EXPECT(pm_path_sample(rig, 0, 0.5 * k, &points[2 * k], &points[2 * k + 1]) == PM_OK);
    EXPECT(pm_channel_path_sample(rig, 1, 0, 0.3 * k, &face_points[2 * k], &face_points[2 * k + 1]) == PM_OK);
    pm_transform_make(60.0 * k, 0, 0, 1, 1, k % 2, &places[k]);
  }
  pm_character_inputs in;
  memset(&in, 0, sizeof in);
  in.points = points;
  in.channel_points = face_points;
  in.transforms = places;
  EXPECT(pm_character_draw_lists(rig, NULL, kCount, &in, work, sizes.workspace_doubles, positions,
                                 sizes.position_floats, attached_positions, sizes.attached_position_floats, lists,
                                 kCount, attached, sizes.attached_lists) == PM_OK);
  /* The same characters from the morph and attach calls. */
  pm_rig_info info;
  pm_rig_get_info(rig, &info);
  const size_t N = info.pose_count, NW = pm_rig_attached_weight_count(rig), A = pm_rig_attachment_count(rig);
  const size_t v2 = 2 * (size_t)info.vertex_count, a2 = 2 * (size_t)pm_rig_attached_vertex_count(rig);
  double* raw = calloc(kCount * N, sizeof(double));
  double* limited = calloc(kCount * N, sizeof(double));
  double* w = calloc(kCount * NW, sizeof(double));
  double* wl = calloc(kCount * NW, sizeof(double));
  double* body = calloc(kCount * v2, sizeof(double));
  float* body_f32 = calloc(kCount * v2, sizeof(float));
  double* parts = calloc(kCount * a2, sizeof(double));
  float* parts_f32 = calloc(kCount * a2, sizeof(float));
  const size_t work_size = pm_batch_workspace_size(rig) > pm_attach_workspace_size(rig) ? pm_batch_workspace_size(rig)
                                                                                        : pm_attach_workspace_size(rig);
  double* work2 = calloc(work_size, sizeof(double));
  double sigma = -1, face_sigma = -1;
  EXPECT(pm_channel_default_sigma(rig, 0, &sigma) == PM_OK && sigma == info.default_sigma);
  EXPECT(pm_channel_default_sigma(rig, 1, &face_sigma) == PM_OK);
  for (int k = 0; k < kCount; ++k) {
    EXPECT(pm_weights(rig, points[2 * k], points[2 * k + 1], sigma, 1, raw + k * N, limited + k * N, NULL, N) == PM_OK);
    EXPECT(pm_channel_weights(rig, 1, face_points[2 * k], face_points[2 * k + 1], face_sigma, 1, w + k * NW,
                              wl + k * NW, NULL, NW) == PM_OK);
  }
  EXPECT(pm_morph_batch(rig, kCount, raw, limited, work2, work_size, body, body_f32, kCount * v2) == PM_OK);
  EXPECT(pm_attach(rig, kCount, body, kCount * v2, w, wl, kCount * NW, 0, work2, work_size, parts, parts_f32,
                   kCount * a2) == PM_OK);
  EXPECT(memcmp(positions, body_f32, kCount * v2 * sizeof(float)) == 0);
  EXPECT(memcmp(attached_positions, parts_f32, kCount * a2 * sizeof(float)) == 0);
  /* Draw: each step's triangles with its part's drawings, back to front. */
  uint32_t triangles_of_character = info.triangle_count;
  for (uint32_t a = 0; a < A; ++a) {
    pm_attachment at;
    pm_rig_attachment(rig, a, &at);
    triangles_of_character += at.triangle_count;
  }
  EXPECT(pm_character_list_count(rig) == 1 + A);
  for (int k = 0; k < kCount; ++k) {
    pm_draw_step steps[16];
    const uint32_t n = pm_character_draw_steps(rig, &lists[k], &attached[k * A], steps, 16);
    EXPECT(n == 7);
    uint32_t drawn = 0;
    int32_t last_order = -1000000;
    for (uint32_t s = 0; s < n && s < 16; ++s) {
      const pm_draw_list* l = steps[s].list == 0 ? &lists[k] : &attached[k * A + steps[s].list - 1];
      pm_part part;
      EXPECT(pm_character_part(rig, steps[s].list, steps[s].part, &part) == PM_OK);
      drawn += part.triangle_count;
      EXPECT(part.first_triangle + part.triangle_count <= l->index_count / 3);
      int32_t order = 0;
      if (steps[s].list == 0)
        EXPECT(pm_rig_part_draw_order(rig, steps[s].part, l->drawings[0].pose, &order) == PM_OK);
      else
        EXPECT(pm_rig_attachment_draw_order(rig, steps[s].list - 1, l->drawings[0].pose, &order) == PM_OK);
      EXPECT(order >= last_order);
      last_order = order;
      for (uint32_t d = 0; d < l->drawing_count; ++d) {
        char image[256];
        size_t length = 0;
        pm_canvas canvas;
        EXPECT(pm_character_part_image(rig, steps[s].list, steps[s].part, l->drawings[d].pose, image, sizeof image,
                                       &length) == PM_OK &&
               length > 0);
        EXPECT(pm_character_canvas(rig, steps[s].list, l->drawings[d].pose, &canvas) == PM_OK && canvas.width > 0);
        EXPECT(l->drawings[d].uvs != NULL);
      }
      EXPECT(l->transform.tx == places[k].tx && l->mirrored == k % 2);
    }
    EXPECT(drawn == triangles_of_character);
  }
  printf("c_api_test: %s: %d characters drawn from pm_character_draw_lists, %u triangles each\n", path, kCount,
         triangles_of_character);
  free(work), free(positions), free(attached_positions), free(lists), free(attached);
  free(raw), free(limited), free(w), free(wl), free(body), free(body_f32), free(parts), free(parts_f32), free(work2);
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
    EXPECT(pm_rig_format_version(rig, &major, &minor) == PM_OK && major == 1 && minor == 14);
  }
  EXPECT(pm_rig_channel_count(rig) == 1 && pm_rig_attachment_count(rig) == 0);
  EXPECT(pm_rig_channel_count(NULL) == 0 && pm_rig_attached_vertex_count(rig) == 0);
  pm_rig_free(rig);
  Limits(bytes, (size_t)size);
  free(bytes), free(raw), free(limited), free(tex), free(work), free(x), free(xf);
  if (argc == 3) Channels(argv[2]), DrawCharacter(argv[2]);
  printf("c_api_test: %s\n", failures ? "FAILED" : "ok");
  return failures ? 1 : 0;
}
