// SPDX-License-Identifier: MIT
// The C surface: thin wrappers over the C++ jobs, nothing more. This file:
// loading, freeing, and what a rig holds (names, parts, bounds, canvases).
#include <cstdint>
#include <cstring>
#include <new>

#include "c_api_internal.h"
#include "draw_list_internal.h"
#include "posemorph/draw_list.h"
#include "posemorph/jobs.h"
#include "posemorph/path.h"
#include "posemorph/posemorph.h"
#include "posemorph/quantize.h"

using namespace posemorph::c_api;  // NOLINT(google-build-using-namespace): the C API's own helpers
using posemorph::Span;

namespace {

// The loader's options with the caller's limits (NULL: the format's).
posemorph::LoadOptions OptionsWith(const pm_load_limits* limits) {
  posemorph::LoadOptions options;
  if (limits) {
    posemorph::LoadLimits& l = options.limits;
    l.max_bytes = limits->max_bytes, l.max_memory = limits->max_memory, l.max_vertices = limits->max_vertices;
    l.max_poses = limits->max_poses, l.max_attachments = limits->max_attachments;
    l.max_factor_nonzeros = limits->max_factor_nonzeros, l.max_fill = limits->max_fill;
  }
  return options;
}

}  // namespace

extern "C" {

void pm_load_limits_untrusted(pm_load_limits* out) {
  if (!out) return;
  const posemorph::LoadLimits l = posemorph::LoadLimits::Untrusted();
  *out = {l.max_bytes, l.max_memory, l.max_vertices, l.max_poses, l.max_attachments, l.max_factor_nonzeros, l.max_fill};
}

int pm_rig_load(const void* bytes, size_t size, pm_rig** out_rig, pm_error* err) {
  return pm_rig_load_limited(bytes, size, nullptr, out_rig, err);
}

int pm_rig_load_limited(const void* bytes, size_t size, const pm_load_limits* limits, pm_rig** out_rig, pm_error* err) {
  posemorph::Error e;
  if (err) *err = pm_error{};
  if (const int status = CheckOutput(out_rig, err)) return status;
  pm_rig* rig = new (std::nothrow) pm_rig;
  if (!rig) return Fail(err, PM_ERROR_OUT_OF_MEMORY, "cannot allocate the rig handle");
  if (!posemorph::LoadRig(bytes, size, &rig->rig, &e, OptionsWith(limits))) {
    delete rig;
    return Report(err, e);
  }
  *out_rig = rig;
  return PM_OK;
}

int pm_rig_memory_size(const void* bytes, size_t size, size_t* needed, pm_error* err) {
  return pm_rig_memory_size_limited(bytes, size, nullptr, needed, err);
}

int pm_rig_memory_size_limited(const void* bytes, size_t size, const pm_load_limits* limits, size_t* needed,
                               pm_error* err) {
  posemorph::Error e;
  if (err) *err = pm_error{};
  std::size_t arena = 0;
  if (!posemorph::RigMemorySize(bytes, size, &arena, &e, OptionsWith(limits))) return Report(err, e);
  if (needed) *needed = kHandleBytes + arena;
  return PM_OK;
}

int pm_rig_load_in_place(const void* bytes, size_t size, void* memory, size_t memory_size, pm_rig** out_rig,
                         pm_error* err) {
  return pm_rig_load_in_place_limited(bytes, size, nullptr, memory, memory_size, out_rig, err);
}

int pm_rig_load_in_place_limited(const void* bytes, size_t size, const pm_load_limits* limits, void* memory,
                                 size_t memory_size, pm_rig** out_rig, pm_error* err) {
  posemorph::Error e;
  if (err) *err = pm_error{};
  if (const int status = CheckOutput(out_rig, err)) return status;
  if (!memory) return Fail(err, PM_ERROR_INVALID_ARGUMENT, "no memory given (pm_rig_memory_size says how much)");
  if (reinterpret_cast<std::uintptr_t>(memory) % PM_RIG_MEMORY_ALIGNMENT != 0)
    return Fail(err, PM_ERROR_INVALID_ARGUMENT, "memory is not aligned to PM_RIG_MEMORY_ALIGNMENT (16) bytes");
  if (memory_size < kHandleBytes)
    return Fail(err, PM_ERROR_INVALID_ARGUMENT, "memory is smaller than pm_rig_memory_size says");
  pm_rig* rig = new (memory) pm_rig;
  rig->in_place = true;
  if (!posemorph::LoadRigInPlace(bytes, size, static_cast<unsigned char*>(memory) + kHandleBytes,
                                 memory_size - kHandleBytes, &rig->rig, &e, OptionsWith(limits))) {
    rig->~pm_rig();
    return Report(err, e);
  }
  *out_rig = rig;
  return PM_OK;
}

void pm_rig_free(pm_rig* rig) {
  if (!rig) return;
  if (rig->in_place)
    rig->~pm_rig();  // the memory is the caller's
  else
    delete rig;
}

void pm_rig_get_info(const pm_rig* rig, pm_rig_info* info) {
  if (!rig || !info) return;
  const posemorph::Rig& r = rig->rig;
  *info = pm_rig_info{r.vertex_count(), r.triangle_count(), r.pose_count(),
                      r.path_count(),   r.default_sigma(),  r.bounding_box_diagonal()};
}

const uint32_t* pm_rig_triangles(const pm_rig* rig) { return rig ? rig->rig.triangles().data : nullptr; }

const float* pm_rig_uvs(const pm_rig* rig, uint32_t pose) { return rig ? rig->rig.uvs(pose).data : nullptr; }

const double* pm_rig_pose_positions(const pm_rig* rig, uint32_t pose) {
  return rig ? rig->rig.pose_positions(pose).data : nullptr;
}

const char* pm_version(void) {
#define PM_STRINGIFY2(x) #x
#define PM_STRINGIFY(x) PM_STRINGIFY2(x)
  return PM_STRINGIFY(PM_VERSION_MAJOR) "." PM_STRINGIFY(PM_VERSION_MINOR) "." PM_STRINGIFY(PM_VERSION_PATCH);
}

int pm_rig_pose_name(const pm_rig* rig, uint32_t pose, char* out, size_t capacity, size_t* length) {
  return CopyString(rig ? rig->rig.pose_name(pose) : posemorph::StringView{}, rig && pose < rig->rig.pose_count(), out,
                    capacity, length);
}

int pm_rig_pose_image(const pm_rig* rig, uint32_t pose, char* out, size_t capacity, size_t* length) {
  return CopyString(rig ? rig->rig.pose_image(pose) : posemorph::StringView{}, rig && pose < rig->rig.pose_count(), out,
                    capacity, length);
}

uint32_t pm_rig_part_count(const pm_rig* rig) { return rig ? rig->rig.part_count() : 0; }

int pm_rig_part(const pm_rig* rig, uint32_t part, pm_part* out) {
  if (!rig || !out || part >= rig->rig.part_count()) return PM_ERROR_INVALID_ARGUMENT;
  const posemorph::PartView view = rig->rig.part(part);
  *out = pm_part{view.first_triangle, view.triangle_count, view.draw_order};
  return PM_OK;
}

int pm_rig_part_draw_order(const pm_rig* rig, uint32_t part, uint32_t pose, int32_t* out) {
  if (!rig || !out || part >= rig->rig.part_count() || pose >= rig->rig.pose_count()) return PM_ERROR_INVALID_ARGUMENT;
  *out = rig->rig.part_draw_order(part, pose);
  return PM_OK;
}

int pm_rig_part_name(const pm_rig* rig, uint32_t part, char* out, size_t capacity, size_t* length) {
  return CopyString(rig ? rig->rig.part(part).name : posemorph::StringView{}, rig && part < rig->rig.part_count(), out,
                    capacity, length);
}

int pm_rig_part_image(const pm_rig* rig, uint32_t part, uint32_t pose, char* out, size_t capacity, size_t* length) {
  return CopyString(rig ? rig->rig.part_image(part, pose) : posemorph::StringView{},
                    rig && part < rig->rig.part_count() && pose < rig->rig.pose_count(), out, capacity, length);
}

int pm_rig_drawing_folder(const pm_rig* rig, char* out, size_t capacity, size_t* length) {
  return CopyString(rig ? rig->rig.drawing_folder() : posemorph::StringView{}, rig != nullptr, out, capacity, length);
}

int pm_rig_path_name(const pm_rig* rig, uint32_t path, char* out, size_t capacity, size_t* length) {
  return CopyString(rig ? rig->rig.path(path).name : posemorph::StringView{}, rig && path < rig->rig.path_count(), out,
                    capacity, length);
}

int pm_rig_grid(const pm_rig* rig, pm_grid_info* out) {
  if (!rig || !out || !rig->rig.loaded()) return PM_ERROR_INVALID_ARGUMENT;
  const posemorph::PoseSpaceGrid& g = rig->rig.grid();
  *out = pm_grid_info{g.origin_x, g.origin_y, g.origin_x + g.cell * g.cells_x, g.origin_y + g.cell * g.cells_y, g.cell,
                      g.cells_x,  g.cells_y};
  return PM_OK;
}

namespace {
void Extend(pm_bounds* b, const double* xy, std::size_t vertices) {
  for (std::size_t v = 0; v < vertices; ++v) {
    b->min_x = xy[2 * v] < b->min_x ? xy[2 * v] : b->min_x;
    b->max_x = xy[2 * v] > b->max_x ? xy[2 * v] : b->max_x;
    b->min_y = xy[2 * v + 1] < b->min_y ? xy[2 * v + 1] : b->min_y;
    b->max_y = xy[2 * v + 1] > b->max_y ? xy[2 * v + 1] : b->max_y;
  }
}
constexpr pm_bounds kEmptyBounds = {1e308, 1e308, -1e308, -1e308};
}  // namespace

int pm_rig_pose_bounds(const pm_rig* rig, uint32_t pose, pm_bounds* out) {
  if (!rig || !out || pose >= rig->rig.pose_count()) return PM_ERROR_INVALID_ARGUMENT;
  *out = kEmptyBounds;
  Extend(out, rig->rig.pose_positions(pose).data, rig->rig.vertex_count());
  return PM_OK;
}

size_t pm_hull_bounds_workspace_size(const pm_rig* rig) {
  if (!rig) return 0;
  const posemorph::Rig& r = rig->rig;
  return r.morph_workspace_size() + 2 * std::size_t(r.vertex_count()) + 2 * std::size_t(r.pose_count());
}

int pm_rig_hull_bounds(const pm_rig* rig, uint32_t samples, double* workspace, size_t workspace_capacity,
                       pm_bounds* out) {
  if (!rig || !out || !workspace || !Aligned(workspace) || samples < 2 || samples > 256 || !rig->rig.loaded())
    return PM_ERROR_INVALID_ARGUMENT;
  if (workspace_capacity < pm_hull_bounds_workspace_size(rig)) return PM_ERROR_BUFFER_TOO_SMALL;
  const posemorph::Rig& r = rig->rig;
  const std::size_t N = r.pose_count(), V = r.vertex_count();
  double* work = workspace;
  double* x = work + r.morph_workspace_size();
  double* w = x + 2 * V;
  double* ws = w + N;
  *out = kEmptyBounds;
  for (std::uint32_t i = 0; i < N; ++i) Extend(out, r.pose_positions(i).data, V);
  // Frames at points of the hull: every triangle (p_0, p_a, p_b) of pose
  // points covers the hull, so barycentric samples of each cover it too.
  const posemorph::Span<const double> p = r.pose_points();
  for (std::uint32_t a = 1; a < N; ++a)
    for (std::uint32_t b = a; b < N; ++b)
      for (std::uint32_t i = 0; i <= samples; ++i)
        for (std::uint32_t j = 0; i + j <= samples; ++j) {
          const double u = double(i) / samples, v = double(j) / samples, t = 1 - u - v;
          posemorph::WeightsJob wj;
          wj.rig = &r;
          wj.x = t * p[0] + u * p[2 * a] + v * p[2 * b];
          wj.y = t * p[1] + u * p[2 * a + 1] + v * p[2 * b + 1];
          wj.raw = {w, N}, wj.limited = {ws, N};
          posemorph::MorphJob mj;
          mj.rig = &r, mj.weights = {w, N}, mj.limited_weights = {ws, N};
          mj.workspace = {work, r.morph_workspace_size()}, mj.positions = {x, 2 * V};
          if (!wj.Run() || !mj.Run()) return PM_ERROR_INVALID_ARGUMENT;
          Extend(out, x, V);
        }
  return PM_OK;
}

int pm_rig_pose_canvas(const pm_rig* rig, uint32_t pose, pm_canvas* out) {
  if (!rig || !out || pose >= rig->rig.pose_count()) return PM_ERROR_INVALID_ARGUMENT;
  const posemorph::DrawingCanvas c = rig->rig.pose_canvas(pose);
  *out = pm_canvas{c.width, c.height, c.pivot_x, c.pivot_y};
  return PM_OK;
}

int pm_rig_texture_filter(const pm_rig* rig) {
  return rig && rig->rig.texture_filter() == posemorph::TextureFilter::kNearest ? PM_FILTER_NEAREST : PM_FILTER_LINEAR;
}

int pm_rig_checksum(const pm_rig* rig, uint32_t* crc) {
  if (!rig || !crc || !rig->rig.loaded()) return PM_ERROR_INVALID_ARGUMENT;
  *crc = rig->rig.checksum();
  return PM_OK;
}

int pm_rig_format_version(const pm_rig* rig, uint32_t* major, uint32_t* minor) {
  if (!rig || !major || !minor || !rig->rig.loaded()) return PM_ERROR_INVALID_ARGUMENT;
  *major = rig->rig.format_major();
  *minor = rig->rig.format_minor();
  return PM_OK;
}
}  // extern "C"
