// SPDX-License-Identifier: MIT
// Rig's own code: moving, and the accessors over the arena the loader
// (rig_load.cpp) filled.
#include <cmath>
#include <cstring>
#include <utility>

#include "kernels/kernel_table.h"
#include "posemorph/rig.h"

namespace posemorph {

Rig::Rig() = default;
Rig::~Rig() = default;
// A moved-from rig is empty (loaded() false, every span empty), never a
// view into the arena its new owner holds.
Rig::Rig(Rig&& other) noexcept { *this = std::move(other); }

Rig& Rig::operator=(Rig&& other) noexcept {
  if (this == &other) return *this;
  arena_ = std::move(other.arena_);
  arena_size_ = std::exchange(other.arena_size_, 0);
  vertex_count_ = std::exchange(other.vertex_count_, 0);
  triangle_count_ = std::exchange(other.triangle_count_, 0);
  pose_count_ = std::exchange(other.pose_count_, 0);
  path_count_ = std::exchange(other.path_count_, 0);
  triangles_ = std::exchange(other.triangles_, {});
  pose_positions_ = std::exchange(other.pose_positions_, {});
  pose_points_ = std::exchange(other.pose_points_, {});
  pose_centroids_ = std::exchange(other.pose_centroids_, {});
  vertex_masses_ = std::exchange(other.vertex_masses_, {});
  gradients_ = std::exchange(other.gradients_, {});
  angles_ = std::exchange(other.angles_, {});
  stretches_ = std::exchange(other.stretches_, {});
  blend_blocks_ = std::exchange(other.blend_blocks_, {});
  uvs_ = std::exchange(other.uvs_, {});
  canvases_ = std::exchange(other.canvases_, {});
  strings_ = std::exchange(other.strings_, {});
  part_table_ = std::exchange(other.part_table_, {});
  draw_sequence_ = std::exchange(other.draw_sequence_, {});
  part_pose_orders_ = std::exchange(other.part_pose_orders_, {});
  part_strings_ = std::exchange(other.part_strings_, {});
  pages_ = std::exchange(other.pages_, {});
  regions_ = std::exchange(other.regions_, {});
  has_atlas_ = std::exchange(other.has_atlas_, false);
  paths_ = std::exchange(other.paths_, {});
  events_ = std::exchange(other.events_, {});
  machine_inputs_ = std::exchange(other.machine_inputs_, {});
  machine_layers_ = std::exchange(other.machine_layers_, {});
  machine_states_ = std::exchange(other.machine_states_, {});
  attachments_ = std::exchange(other.attachments_, {});
  channel_names_ = std::exchange(other.channel_names_, {});
  channel_offsets_ = std::exchange(other.channel_offsets_, {});
  channel_count_ = std::exchange(other.channel_count_, 1);
  attached_vertex_count_ = std::exchange(other.attached_vertex_count_, 0);
  attached_weight_count_ = std::exchange(other.attached_weight_count_, 0);
  attach_workspace_ = std::exchange(other.attach_workspace_, 0);
  grid_ = std::exchange(other.grid_, {});
  solve_ = std::exchange(other.solve_, {});
  default_sigma_ = std::exchange(other.default_sigma_, 0);
  anchor_x_ = std::exchange(other.anchor_x_, 0);
  anchor_y_ = std::exchange(other.anchor_y_, 0);
  facing_left_ = std::exchange(other.facing_left_, false);
  anchor_given_ = std::exchange(other.anchor_given_, false);
  texture_filter_ = std::exchange(other.texture_filter_, TextureFilter::kLinear);
  drawing_folder_ = std::exchange(other.drawing_folder_, {});
  rig_size_ = std::exchange(other.rig_size_, 0);
  kernels_ = std::exchange(other.kernels_, nullptr);
  checksum_ = std::exchange(other.checksum_, 0);
  format_major_ = std::exchange(other.format_major_, 0);
  format_minor_ = std::exchange(other.format_minor_, 0);
  compact_encoding_ = std::exchange(other.compact_encoding_, false);
  return *this;
}

PadRange Rig::pad_range() const {
  PadRange r;
  if (!loaded()) return r;
  r.min_x = r.max_x = pose_points_[0], r.min_y = r.max_y = pose_points_[1];
  for (std::size_t i = 2; i + 1 < pose_points_.size; i += 2) {
    r.min_x = std::fmin(r.min_x, pose_points_[i]), r.max_x = std::fmax(r.max_x, pose_points_[i]);
    r.min_y = std::fmin(r.min_y, pose_points_[i + 1]), r.max_y = std::fmax(r.max_y, pose_points_[i + 1]);
  }
  const double margin = std::fmax(0.1 * std::fmax(r.max_x - r.min_x, r.max_y - r.min_y), grid_.cell);
  const double gx1 = grid_.origin_x + grid_.cell * grid_.cells_x, gy1 = grid_.origin_y + grid_.cell * grid_.cells_y;
  r.min_x = std::fmax(r.min_x - margin, grid_.origin_x), r.max_x = std::fmin(r.max_x + margin, gx1);
  r.min_y = std::fmax(r.min_y - margin, grid_.origin_y), r.max_y = std::fmin(r.max_y + margin, gy1);
  return r;
}

Isa Rig::isa() const { return kernels_ ? kernels_->isa : Isa::kAuto; }

Span<const double> Rig::pose_positions(std::uint32_t pose) const {
  if (pose >= pose_count_) return {};
  return pose_positions_.subspan(std::size_t(pose) * 2 * vertex_count_, 2 * std::size_t(vertex_count_));
}

Span<const float> Rig::uvs(std::uint32_t pose) const {
  if (pose >= pose_count_ || uvs_.empty()) return {};
  return uvs_.subspan(std::size_t(pose) * 2 * vertex_count_, 2 * std::size_t(vertex_count_));
}

StringView Rig::pose_name(std::uint32_t pose) const { return pose < pose_count_ ? strings_[pose] : StringView{}; }

StringView Rig::pose_image(std::uint32_t pose) const {
  return pose < pose_count_ ? strings_[pose_count_ + pose] : StringView{};
}

DrawingCanvas Rig::pose_canvas(std::uint32_t pose) const {
  if (pose >= pose_count_ || canvases_.empty()) return {};
  const double* c = canvases_.data + 4 * std::size_t(pose);
  return {c[0], c[1], c[2], c[3]};
}

PartView Rig::part(std::uint32_t index) const {
  if (!loaded() || index >= part_count()) return {};
  if (part_table_.empty()) return {StringView{"", 0}, 0, triangle_count_, 0};
  const std::uint32_t* e = part_table_.data + 4 * std::size_t(index);
  return {part_strings_[index], e[0], e[1], std::int32_t(e[2])};
}

StringView Rig::part_image(std::uint32_t index, std::uint32_t pose) const {
  if (!loaded() || index >= part_count() || pose >= pose_count_) return {};
  if (part_table_.empty()) return pose_image(pose);
  return part_strings_[part_count() + std::size_t(index) * pose_count_ + pose];
}

TexturePage Rig::page(std::uint32_t index) const { return index < pages_.size ? pages_[index] : TexturePage{}; }

TextureRegion Rig::part_region(std::uint32_t part, std::uint32_t pose) const {
  if (!loaded() || part >= part_count() || pose >= pose_count_ || regions_.empty()) return {};
  return regions_[std::size_t(part) * pose_count_ + pose];
}

Span<const std::uint32_t> Rig::draw_sequence(std::uint32_t pose) const {
  static const std::uint32_t kWhole[1] = {0};
  if (!loaded() || pose >= pose_count_) return {};
  if (draw_sequence_.empty()) return {kWhole, 1};
  const std::size_t M = part_count();
  return part_pose_orders_.empty() ? draw_sequence_ : draw_sequence_.subspan(std::size_t(pose) * M, M);
}

std::int32_t Rig::part_draw_order(std::uint32_t index, std::uint32_t pose) const {
  if (!loaded() || index >= part_count() || pose >= pose_count_) return 0;
  if (part_pose_orders_.empty()) return part(index).draw_order;
  return std::int32_t(part_pose_orders_[std::size_t(pose) * part_count() + index]);
}

PathView Rig::path(std::uint32_t index) const { return index < path_count_ ? paths_[index] : PathView{}; }

EventView Rig::event(std::uint32_t index) const { return index < events_.size ? events_[index] : EventView{}; }

int Rig::FindPath(const char* name) const {
  if (!name) return -1;
  const std::size_t n = std::strlen(name);
  for (std::uint32_t i = 0; i < path_count_; ++i)
    if (paths_[i].name.size == n && std::memcmp(paths_[i].name.data, name, n) == 0) return int(i);
  return -1;
}

namespace {
template <typename View>
int FindNamed(Span<const View> views, const char* name) {
  if (!name) return -1;
  const std::size_t n = std::strlen(name);
  for (std::size_t i = 0; i < views.size; ++i)
    if (views[i].name.size == n && std::memcmp(views[i].name.data, name, n) == 0) return int(i);
  return -1;
}
}  // namespace

int Rig::FindMachineInput(const char* name) const { return FindNamed(machine_inputs_, name); }
int Rig::FindMachineState(const char* name) const { return FindNamed(machine_states_, name); }

StringView Rig::channel_name(std::uint32_t channel) const {
  return channel < channel_names_.size ? channel_names_[channel] : StringView{};
}

const Rig* Rig::channel_rig(std::uint32_t channel) const {
  if (channel == 0) return loaded() ? this : nullptr;
  for (std::size_t a = 0; a < attachments_.size; ++a)
    if (attachments_[a].channel == channel) return attachments_[a].rig;
  return nullptr;
}

int Rig::FindChannel(const char* name) const {
  if (!name) return -1;
  const std::size_t n = std::strlen(name);
  for (std::uint32_t c = 0; c < channel_names_.size; ++c)
    if (channel_names_[c].size == n && std::memcmp(channel_names_[c].data, name, n) == 0) return int(c);
  return -1;
}

AttachmentView Rig::attachment(std::uint32_t index) const {
  return index < attachments_.size ? attachments_[index] : AttachmentView{};
}

std::uint32_t Rig::channel_weight_offset(std::uint32_t channel) const {
  return channel < channel_offsets_.size ? channel_offsets_[channel] : 0;
}

const char* ErrorCodeName(ErrorCode code) {
  switch (code) {
    case ErrorCode::kOk:
      return "ok";
    case ErrorCode::kInvalidArgument:
      return "invalid argument";
    case ErrorCode::kTruncated:
      return "truncated";
    case ErrorCode::kBadMagic:
      return "bad magic";
    case ErrorCode::kBadVersion:
      return "unsupported version";
    case ErrorCode::kBadChecksum:
      return "bad checksum";
    case ErrorCode::kBadLayout:
      return "bad layout";
    case ErrorCode::kBadValue:
      return "bad value";
    case ErrorCode::kTooLarge:
      return "too large";
    case ErrorCode::kOutOfMemory:
      return "out of memory";
    case ErrorCode::kUnsupportedIsa:
      return "unsupported code path";
  }
  return "unknown";
}

}  // namespace posemorph
