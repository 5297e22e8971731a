// SPDX-License-Identifier: MIT
// The C surface: thin wrappers over the C++ jobs, nothing more.
#include <cstdio>
#include <cstring>
#include <cstdint>
#include <new>

#include "draw_list_internal.h"
#include "posemorph/draw_list.h"
#include "posemorph/jobs.h"
#include "posemorph/path.h"
#include "posemorph/posemorph.h"
#include "posemorph/quantize.h"

struct pm_rig {
  posemorph::Rig rig;
  bool in_place = false;  // the handle and the rig's arrays live in the caller's memory
};

namespace {
// An in-place handle sits at the start of the caller's memory, the rig's
// arrays after it.
constexpr std::size_t kHandleBytes = (sizeof(pm_rig) + posemorph::kRigMemoryAlignment - 1) /
                                     posemorph::kRigMemoryAlignment * posemorph::kRigMemoryAlignment;
static_assert(PM_RIG_MEMORY_ALIGNMENT == posemorph::kRigMemoryAlignment, "published alignment");

template <typename T>
bool Aligned(const T* p) {
  return reinterpret_cast<std::uintptr_t>(p) % alignof(T) == 0;
}

int CopyString(posemorph::StringView v, bool valid, char* out, size_t capacity, size_t* length) {
  if (!valid) return PM_ERROR_INVALID_ARGUMENT;
  if (length) *length = v.size;
  if (!out || capacity < v.size + 1) return PM_ERROR_BUFFER_TOO_SMALL;
  if (v.size) std::memcpy(out, v.data, v.size);
  out[v.size] = 0;
  return PM_OK;
}

int Fail(pm_error* err, int code, const char* message) {
  if (err) {
    err->code = code;
    std::snprintf(err->message, sizeof(err->message), "%s", message);
  }
  return code;
}

// The output handle of a load: given, and not holding a rig (which the load
// would leak).
int CheckOutput(pm_rig** out_rig, pm_error* err) {
  if (!out_rig) return Fail(err, PM_ERROR_INVALID_ARGUMENT, "no output pointer given");
  if (*out_rig)
    return Fail(err, PM_ERROR_INVALID_ARGUMENT,
                "*out_rig is not NULL: free the rig it holds first (pm_rig_free), then set it to NULL");
  return PM_OK;
}

int Report(pm_error* err, const posemorph::Error& e) {
  if (err) {
    err->code = int(e.code);
    std::memcpy(err->message, e.message, sizeof(err->message));
  }
  return int(e.code);
}
}  // namespace

using posemorph::Span;

extern "C" {

int pm_rig_load(const void* bytes, size_t size, pm_rig** out_rig, pm_error* err) {
  posemorph::Error e;
  if (err) *err = pm_error{};
  if (const int status = CheckOutput(out_rig, err)) return status;
  pm_rig* rig = new (std::nothrow) pm_rig;
  if (!rig) return Fail(err, PM_ERROR_OUT_OF_MEMORY, "cannot allocate the rig handle");
  if (!posemorph::LoadRig(bytes, size, &rig->rig, &e)) {
    delete rig;
    return Report(err, e);
  }
  *out_rig = rig;
  return PM_OK;
}

int pm_rig_memory_size(const void* bytes, size_t size, size_t* needed, pm_error* err) {
  posemorph::Error e;
  if (err) *err = pm_error{};
  std::size_t arena = 0;
  if (!posemorph::RigMemorySize(bytes, size, &arena, &e)) return Report(err, e);
  if (needed) *needed = kHandleBytes + arena;
  return PM_OK;
}

int pm_rig_load_in_place(const void* bytes, size_t size, void* memory, size_t memory_size, pm_rig** out_rig,
                         pm_error* err) {
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
                                 memory_size - kHandleBytes, &rig->rig, &e)) {
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

int pm_rig_pose_point(const pm_rig* rig, uint32_t pose, double* x, double* y) {
  if (!rig || !x || !y || pose >= rig->rig.pose_count()) return PM_ERROR_INVALID_ARGUMENT;
  *x = rig->rig.pose_points()[2 * pose];
  *y = rig->rig.pose_points()[2 * pose + 1];
  return PM_OK;
}

int pm_weights(const pm_rig* rig, double x, double y, double sigma, int limit_weights, double* raw, double* limited,
               double* texture, size_t capacity) {
  return pm_channel_weights(rig, 0, x, y, sigma, limit_weights, raw, limited, texture, capacity);
}

size_t pm_morph_workspace_size(const pm_rig* rig) { return rig ? rig->rig.morph_workspace_size() : 0; }

int pm_morph(const pm_rig* rig, const double* weights, const double* limited_weights, int linear, double* workspace,
             size_t workspace_capacity, double* positions, float* positions_f32, size_t positions_capacity) {
  if (!rig || !Aligned(workspace) || !Aligned(positions) || !Aligned(positions_f32)) return PM_ERROR_INVALID_ARGUMENT;
  const posemorph::Rig& r = rig->rig;
  const std::size_t n = r.pose_count(), v2 = 2 * std::size_t(r.vertex_count());
  if ((workspace && workspace_capacity < r.morph_workspace_size()) || positions_capacity < v2)
    return PM_ERROR_BUFFER_TOO_SMALL;
  posemorph::MorphJob job;
  job.rig = &r;
  job.weights = {weights, n};
  job.limited_weights = {limited_weights, n};
  job.interpolation = linear ? posemorph::Interpolation::kLinear : posemorph::Interpolation::kRigid;
  job.workspace = {workspace, r.morph_workspace_size()};
  job.positions = {positions, v2};
  job.positions_f32 = {positions_f32, positions_f32 ? v2 : 0};
  if (!job.Validate()) return PM_ERROR_INVALID_ARGUMENT;
  return job.Run() ? PM_OK : PM_ERROR_BAD_VALUE;  // a solve beyond kMaxPosition: zeros written
}

size_t pm_batch_workspace_size(const pm_rig* rig) { return rig ? rig->rig.batch_workspace_size() : 0; }

int pm_morph_batch(const pm_rig* rig, size_t count, const double* weights, const double* limited_weights,
                   double* workspace, size_t workspace_capacity, double* positions, float* positions_f32,
                   size_t positions_capacity) {
  if (!rig || !Aligned(workspace) || !Aligned(positions) || !Aligned(positions_f32)) return PM_ERROR_INVALID_ARGUMENT;
  const posemorph::Rig& r = rig->rig;
  const std::size_t n = r.pose_count(), v2 = 2 * std::size_t(r.vertex_count());
  if (count > (std::size_t(-1) / 2) / (v2 + n)) return PM_ERROR_INVALID_ARGUMENT;
  if (count && ((workspace && workspace_capacity < r.batch_workspace_size()) ||
                ((positions || positions_f32) && positions_capacity < count * v2)))
    return PM_ERROR_BUFFER_TOO_SMALL;
  posemorph::MorphBatchJob job;
  job.rig = &r;
  job.count = count;
  job.weights = {weights, weights ? count * n : 0};
  job.limited_weights = {limited_weights, limited_weights ? count * n : 0};
  job.workspace = {workspace, workspace ? r.batch_workspace_size() : 0};
  job.positions = {positions, positions ? count * v2 : 0};
  job.positions_f32 = {positions_f32, positions_f32 ? count * v2 : 0};
  if (!job.Validate()) return PM_ERROR_INVALID_ARGUMENT;
  return job.Run() ? PM_OK : PM_ERROR_BAD_VALUE;  // a solve beyond kMaxPosition: zeros written
}

void pm_transform_make(double x, double y, double radians, double scale_x, double scale_y, int flip_x,
                       pm_transform* out) {
  if (!out) return;
  const posemorph::Transform2D t = posemorph::Transform2D::Make(x, y, radians, scale_x, scale_y, flip_x != 0);
  *out = {t.a, t.b, t.c, t.d, t.tx, t.ty};
}

void pm_draw_options_default(pm_draw_options* out) {
  if (!out) return;
  *out = pm_draw_options{};
  out->sigma = -1.0;
  out->limit_weights = 1;
  out->linear = 0;
  out->max_drawings = posemorph::kMaxBlendDrawings;
}

int pm_draw_list_buffers(const pm_rig* rig, size_t count, size_t* workspace_doubles, size_t* position_floats) {
  if (!rig || count == 0 || count > posemorph::MaxDrawListCount(rig->rig)) return PM_ERROR_INVALID_ARGUMENT;
  const posemorph::CharacterBuffers b = posemorph::CharacterBuffers::For(rig->rig, count);
  if (workspace_doubles) *workspace_doubles = b.workspace;
  if (position_floats) *position_floats = b.positions;
  return PM_OK;
}

int pm_draw_lists(const pm_rig* rig, const pm_draw_options* options, size_t count, const double* points,
                  const pm_transform* transforms, double* workspace, size_t workspace_capacity, float* positions,
                  size_t positions_capacity, pm_draw_list* out, size_t out_capacity) {
  if (!rig || !points || !workspace || !positions || !out || count == 0 || !Aligned(points) || !Aligned(workspace) ||
      !Aligned(positions) || !Aligned(out) || !Aligned(transforms))
    return PM_ERROR_INVALID_ARGUMENT;
  pm_draw_options o;
  pm_draw_options_default(&o);
  if (options) o = *options;
  const posemorph::Rig& r = rig->rig;
  std::size_t need_workspace = 0, need_positions = 0;
  if (pm_draw_list_buffers(rig, count, &need_workspace, &need_positions) != PM_OK) return PM_ERROR_INVALID_ARGUMENT;
  if (workspace_capacity < need_workspace || positions_capacity < need_positions || out_capacity < count)
    return PM_ERROR_BUFFER_TOO_SMALL;
  posemorph::DrawListJob job;
  job.rig = &r;
  job.count = count;
  job.points = {points, 2 * count};
  job.sigma = o.sigma;
  job.limit_weights = o.limit_weights != 0;
  job.interpolation = o.linear ? posemorph::Interpolation::kLinear : posemorph::Interpolation::kRigid;
  job.max_drawings = o.max_drawings;
  job.workspace = {workspace, need_workspace};
  job.positions = {positions, need_positions};
  if (!job.Validate()) return PM_ERROR_INVALID_ARGUMENT;
  const auto transform_at = [transforms](std::size_t k) {
    posemorph::Transform2D t;
    if (transforms) {
      const pm_transform& c = transforms[k];
      t.a = c.a, t.b = c.b, t.c = c.c, t.d = c.d, t.tx = c.tx, t.ty = c.ty;
    }
    return t;
  };
  const bool ok =
      posemorph::detail::RunDrawLists(job, transform_at, [&](std::size_t k, const posemorph::DrawList& list) {
        pm_draw_list& d = out[k];
        d.positions = list.positions.data;
        d.indices = list.indices.data;
        d.vertex_count = r.vertex_count();
        d.index_count = std::uint32_t(list.indices.size);
        d.drawing_count = list.drawing_count;
        for (std::uint32_t i = 0; i < PM_MAX_BLEND_DRAWINGS; ++i)
          d.drawings[i] = {list.drawings[i].pose, list.drawings[i].weight, list.drawings[i].uvs};
        const posemorph::Transform2D& t = list.transform;
        d.transform = {t.a, t.b, t.c, t.d, t.tx, t.ty};
        d.mirrored = list.mirrored ? 1 : 0;
        d.parts = list.parts.data;
        d.part_count = std::uint32_t(list.parts.size);
      });
  return ok ? PM_OK : PM_ERROR_INVALID_ARGUMENT;
}

uint32_t pm_pick_drawings(const double* texture_weights, uint32_t pose_count, uint32_t max_drawings,
                          pm_blended_drawing* out, uint32_t capacity) {
  if (!texture_weights || !out || !Aligned(texture_weights) || !Aligned(out)) return 0;
  posemorph::BlendedDrawing picked[posemorph::kMaxBlendDrawings];
  const std::uint32_t room = capacity < posemorph::kMaxBlendDrawings ? capacity : posemorph::kMaxBlendDrawings;
  const std::uint32_t n = posemorph::PickDrawings({texture_weights, pose_count}, max_drawings, {picked, room});
  for (std::uint32_t k = 0; k < n; ++k) out[k] = {picked[k].pose, picked[k].weight, nullptr};
  return n;
}

int pm_path_find(const pm_rig* rig, const char* name) { return rig ? rig->rig.FindPath(name) : -1; }

int pm_path_sample(const pm_rig* rig, uint32_t path, double time, double* x, double* y) {
  if (!rig) return PM_ERROR_INVALID_ARGUMENT;
  return posemorph::SamplePath(rig->rig, path, time, x, y) ? PM_OK : PM_ERROR_INVALID_ARGUMENT;
}

uint32_t pm_quantize_point(const pm_rig* rig, double x, double y) { return pm_channel_quantize_point(rig, 0, x, y); }

void pm_dequantize_point(const pm_rig* rig, uint32_t packed, double* x, double* y) {
  pm_channel_dequantize_point(rig, 0, packed, x, y);
}

// Control channels (format 1.7).
namespace {
const posemorph::Rig* ChannelRig(const pm_rig* rig, uint32_t channel) {
  return rig ? rig->rig.channel_rig(channel) : nullptr;
}
const posemorph::Rig* AttachmentRig(const pm_rig* rig, uint32_t attachment) {
  return rig && attachment < rig->rig.attachment_count() ? rig->rig.attachment(attachment).rig : nullptr;
}
}  // namespace

uint32_t pm_rig_channel_count(const pm_rig* rig) { return rig ? rig->rig.channel_count() : 0; }

uint32_t pm_channel_quantize_point(const pm_rig* rig, uint32_t channel, double x, double y) {
  const posemorph::Rig* c = ChannelRig(rig, channel);
  if (!c) return 0;
  const posemorph::QuantizedPoint q = posemorph::QuantizePoint(c->grid(), x, y);
  return uint32_t(q.x) | uint32_t(q.y) << 16;
}

void pm_channel_dequantize_point(const pm_rig* rig, uint32_t channel, uint32_t packed, double* x, double* y) {
  const posemorph::Rig* c = ChannelRig(rig, channel);
  if (!c || !x || !y) return;
  posemorph::DequantizePoint(c->grid(), {uint16_t(packed & 0xFFFFu), uint16_t(packed >> 16)}, x, y);
}

int pm_rig_channel_name(const pm_rig* rig, uint32_t channel, char* out, size_t capacity, size_t* length) {
  return CopyString(rig ? rig->rig.channel_name(channel) : posemorph::StringView{},
                    rig && channel < rig->rig.channel_count(), out, capacity, length);
}

int pm_rig_find_channel(const pm_rig* rig, const char* name) { return rig ? rig->rig.FindChannel(name) : -1; }

int pm_rig_channel_poses(const pm_rig* rig, uint32_t channel, uint32_t* pose_count, double* points, size_t capacity) {
  const posemorph::Rig* c = ChannelRig(rig, channel);
  if (!c || !pose_count) return PM_ERROR_INVALID_ARGUMENT;
  *pose_count = c->pose_count();
  if (!points) return PM_OK;
  if (capacity < 2 * std::size_t(c->pose_count())) return PM_ERROR_BUFFER_TOO_SMALL;
  for (std::size_t k = 0; k < 2 * std::size_t(c->pose_count()); ++k) points[k] = c->pose_points()[k];
  return PM_OK;
}

int pm_rig_channel_grid(const pm_rig* rig, uint32_t channel, pm_grid_info* out) {
  const posemorph::Rig* c = ChannelRig(rig, channel);
  if (!c || !out) return PM_ERROR_INVALID_ARGUMENT;
  const posemorph::PoseSpaceGrid& g = c->grid();
  *out = pm_grid_info{g.origin_x, g.origin_y, g.origin_x + g.cell * g.cells_x, g.origin_y + g.cell * g.cells_y, g.cell,
                      g.cells_x,  g.cells_y};
  return PM_OK;
}

int pm_channel_weights(const pm_rig* rig, uint32_t channel, double x, double y, double sigma, int limit_weights,
                       double* raw, double* limited, double* texture, size_t capacity) {
  const posemorph::Rig* c = ChannelRig(rig, channel);
  if (!c || !raw || !Aligned(raw) || !Aligned(limited) || !Aligned(texture)) return PM_ERROR_INVALID_ARGUMENT;
  const std::size_t n = c->pose_count();
  if (capacity < n) return PM_ERROR_BUFFER_TOO_SMALL;
  posemorph::WeightsJob job;
  job.rig = c;
  job.x = x;
  job.y = y;
  job.sigma = sigma;
  job.limit_weights = limit_weights != 0;
  job.raw = {raw, n};
  job.limited = {limited, limited ? n : 0};
  job.texture = {texture, texture ? n : 0};
  return job.Run() ? PM_OK : PM_ERROR_INVALID_ARGUMENT;
}

int pm_channel_path_find(const pm_rig* rig, uint32_t channel, const char* name) {
  const posemorph::Rig* c = ChannelRig(rig, channel);
  return c ? c->FindPath(name) : -1;
}

int pm_channel_path_sample(const pm_rig* rig, uint32_t channel, uint32_t path, double time, double* x, double* y) {
  const posemorph::Rig* c = ChannelRig(rig, channel);
  if (!c) return PM_ERROR_INVALID_ARGUMENT;
  return posemorph::SamplePath(*c, path, time, x, y) ? PM_OK : PM_ERROR_INVALID_ARGUMENT;
}

uint32_t pm_rig_attachment_count(const pm_rig* rig) { return rig ? rig->rig.attachment_count() : 0; }

int pm_rig_attachment(const pm_rig* rig, uint32_t attachment, pm_attachment* out) {
  const posemorph::Rig* a = AttachmentRig(rig, attachment);
  if (!a || !out) return PM_ERROR_INVALID_ARGUMENT;
  const posemorph::AttachmentView v = rig->rig.attachment(attachment);
  pm_attachment r{};
  r.channel = v.channel;
  r.vertex_count = a->vertex_count(), r.triangle_count = a->triangle_count(), r.pose_count = a->pose_count();
  r.draw_order = a->part(0).draw_order;
  r.parent_triangle = v.parent_triangle, r.joint_triangle = v.joint_triangle;
  for (int k = 0; k < 3; ++k) r.parent_weights[k] = v.parent_weights[k], r.joint_weights[k] = v.joint_weights[k];
  *out = r;
  return PM_OK;
}

int pm_rig_attachment_name(const pm_rig* rig, uint32_t attachment, char* out, size_t capacity, size_t* length) {
  const posemorph::Rig* a = AttachmentRig(rig, attachment);
  return CopyString(a ? a->part(0).name : posemorph::StringView{}, a != nullptr, out, capacity, length);
}

int pm_rig_attachment_draw_order(const pm_rig* rig, uint32_t attachment, uint32_t pose, int32_t* out) {
  const posemorph::Rig* a = AttachmentRig(rig, attachment);
  if (!a || !out || pose >= a->pose_count()) return PM_ERROR_INVALID_ARGUMENT;
  *out = a->part_draw_order(0, pose);
  return PM_OK;
}

const uint32_t* pm_rig_attachment_triangles(const pm_rig* rig, uint32_t attachment) {
  const posemorph::Rig* a = AttachmentRig(rig, attachment);
  return a ? a->triangles().data : nullptr;
}

const float* pm_rig_attachment_uvs(const pm_rig* rig, uint32_t attachment, uint32_t pose) {
  const posemorph::Rig* a = AttachmentRig(rig, attachment);
  return a && pose < a->pose_count() && a->uvs(pose).size ? a->uvs(pose).data : nullptr;
}

int pm_rig_attachment_image(const pm_rig* rig, uint32_t attachment, uint32_t pose, char* out, size_t capacity,
                            size_t* length) {
  const posemorph::Rig* a = AttachmentRig(rig, attachment);
  return CopyString(a ? a->part_image(0, pose) : posemorph::StringView{}, a && pose < a->pose_count(), out, capacity,
                    length);
}

uint32_t pm_rig_attached_vertex_count(const pm_rig* rig) { return rig ? rig->rig.attached_vertex_count() : 0; }
uint32_t pm_rig_attached_weight_count(const pm_rig* rig) { return rig ? rig->rig.attached_weight_count() : 0; }
uint32_t pm_rig_channel_weight_offset(const pm_rig* rig, uint32_t channel) {
  return rig ? rig->rig.channel_weight_offset(channel) : 0;
}
size_t pm_attach_workspace_size(const pm_rig* rig) { return rig ? rig->rig.attach_workspace_size() : 0; }

int pm_attach(const pm_rig* rig, size_t count, const double* body_positions, size_t body_capacity,
              const double* weights, const double* limited_weights, size_t weights_capacity, int linear,
              double* workspace, size_t workspace_capacity, double* positions, float* positions_f32,
              size_t positions_capacity) {
  if (!rig || rig->rig.attachment_count() == 0 || !Aligned(body_positions) || !Aligned(weights) ||
      !Aligned(limited_weights) || !Aligned(workspace) || !Aligned(positions) || !Aligned(positions_f32))
    return PM_ERROR_INVALID_ARGUMENT;
  if (count == 0) return PM_OK;
  const std::size_t v2 = 2 * std::size_t(rig->rig.vertex_count()),
                    a2 = 2 * std::size_t(rig->rig.attached_vertex_count());
  const std::size_t nw = rig->rig.attached_weight_count();
  if (count > (std::size_t(-1) / 2) / (v2 + a2 + nw)) return PM_ERROR_INVALID_ARGUMENT;
  if (body_capacity < count * v2 || weights_capacity < count * nw || positions_capacity < count * a2 ||
      workspace_capacity < rig->rig.attach_workspace_size())
    return PM_ERROR_BUFFER_TOO_SMALL;
  posemorph::AttachJob job;
  job.rig = &rig->rig;
  job.count = count;
  job.body_positions = {body_positions, count * v2};
  job.weights = {weights, count * nw};
  job.limited_weights = {limited_weights, count * nw};
  job.interpolation = linear ? posemorph::Interpolation::kLinear : posemorph::Interpolation::kRigid;
  job.workspace = {workspace, workspace_capacity};
  job.positions = {positions, count * a2};
  job.positions_f32 = {positions_f32, positions_f32 ? count * a2 : 0};
  return job.Run() ? PM_OK : PM_ERROR_INVALID_ARGUMENT;
}

}  // extern "C"
