// SPDX-License-Identifier: MIT
// The rig format's fixed-size records, defined once: the file header, the
// section table's entries, META, and each table entry and section header of
// runtime/FORMAT.md. Each is a struct whose size and field offsets are fixed
// by static_asserts, with one list of its fields (Fields) that both the
// bake's writer (EncodeRecord) and the loader's bounded reader (ReadRecord)
// walk, so the two cannot drift apart. Fields are little-endian in the file
// whatever the host; doubles are IEEE-754 binary64.
//
// Sections that are plain arrays of numbers (TRIS, POSE, LVAL, ...) are not
// records: their element type and count are in FORMAT.md and the counts.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "posemorph/format/machine_records.h"
#include "posemorph/format/record_codec.h"

namespace posemorph::format {

// ---- the records ------------------------------------------------------------

// The file header, 64 bytes at offset 0. The checksum (CRC-32) covers every
// byte after the header; the reserved bytes are zero.
struct FileHeader {
  static constexpr std::uint32_t kSize = 64;
  std::uint8_t magic[8];
  std::uint16_t version_major;
  std::uint16_t version_minor;
  std::uint32_t header_size;  // kSize
  std::uint64_t file_size;
  std::uint32_t section_count;
  std::uint32_t flags;  // none defined: zero
  std::uint32_t checksum;
  std::uint32_t reserved[7];
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.magic), f(r.version_major), f(r.version_minor), f(r.header_size), f(r.file_size), f(r.section_count),
        f(r.flags), f(r.checksum), f(r.reserved);
  }
};

// A section table entry; section_count of them follow the header. Sections
// start at multiples of 16 after the table and do not overlap.
struct SectionEntry {
  static constexpr std::uint32_t kSize = 24;
  std::uint32_t tag;
  std::uint32_t reserved;
  std::uint64_t offset;  // from the start of the file
  std::uint64_t size;
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.tag), f(r.reserved), f(r.offset), f(r.size);
  }
};

// META: the counts, flags (kMetaFlag*, rig_format.h) and the weight grid's geometry.
struct Meta {
  static constexpr std::uint32_t kSize = 72;
  std::uint32_t vertex_count;
  std::uint32_t triangle_count;
  std::uint32_t pose_count;
  std::uint32_t path_count;
  std::uint32_t grid_cells_x;
  std::uint32_t grid_cells_y;
  std::uint32_t factor_nonzeros;
  std::uint32_t flags;
  double grid_origin_x;
  double grid_origin_y;
  double grid_cell_size;
  double default_sigma;
  double rig_size;  // bounding-box diagonal of pose 0, the scale tolerances refer to
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.vertex_count), f(r.triangle_count), f(r.pose_count), f(r.path_count), f(r.grid_cells_x), f(r.grid_cells_y),
        f(r.factor_nonzeros), f(r.flags), f(r.grid_origin_x), f(r.grid_origin_y), f(r.grid_cell_size),
        f(r.default_sigma), f(r.rig_size);
  }
};

// PATH: one entry per path; its keys (t, x, y) follow in PKEY, path by path.
struct PathEntry {
  static constexpr std::uint32_t kSize = 8;
  std::uint32_t key_count;
  std::uint32_t flags;  // bit 0 loop; bits 8..15 interpolation
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.key_count), f(r.flags);
  }
};

// EVNT (1.8): one entry per event; its name is in STRS.
struct EventEntry {
  static constexpr std::uint32_t kSize = 16;
  double time;         // seconds on the path's clock, within its first and last key times
  std::uint32_t path;  // index into PATH
  std::uint32_t reserved;
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.time), f(r.path), f(r.reserved);
  }
};

// PLCE (1.11): where the character stands (the anchor, rig units) and which
// way its drawings face (flags: kPlacementFacingLeft).
struct PlacementRecord {
  static constexpr std::uint32_t kSize = 24;
  double anchor_x, anchor_y;
  std::uint32_t flags;
  std::uint32_t reserved;
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.anchor_x), f(r.anchor_y), f(r.flags), f(r.reserved);
  }
};

// PART (1.6): one entry per part; the parts tile the triangles in order.
struct PartEntry {
  static constexpr std::uint32_t kSize = 16;
  std::uint32_t first_triangle;
  std::uint32_t triangle_count;
  std::int32_t draw_order;  // lower draws first, ties by part index
  std::uint32_t reserved;
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.first_triangle), f(r.triangle_count), f(r.draw_order), f(r.reserved);
  }
};

// CHAN (1.7): the section's header; attachment_count AttachmentEntry
// records follow, then the channel names, then the nested rigs.
struct ChannelsHeader {
  static constexpr std::uint32_t kSize = 16;
  std::uint32_t channel_count;
  std::uint32_t attachment_count;
  std::uint32_t reserved[2];
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.channel_count), f(r.attachment_count), f(r.reserved);
  }
};

// CHAN (1.7): an attachment, a nested rig pinned to a triangle of this one.
struct AttachmentEntry {
  static constexpr std::uint32_t kSize = 80;
  std::uint32_t channel;          // 1..C-1
  std::uint32_t parent_triangle;  // this rig's
  std::uint32_t joint_triangle;   // the nested rig's
  std::uint32_t reserved;
  double parent_weights[3];  // the joint in the parent triangle (pose 0)
  double joint_weights[3];   // the joint in the joint triangle (the nested rig's pose 0)
  std::uint64_t offset;      // of the nested rig from the section's start, a multiple of 16
  std::uint64_t size;
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.channel), f(r.parent_triangle), f(r.joint_triangle), f(r.reserved), f(r.parent_weights), f(r.joint_weights),
        f(r.offset), f(r.size);
  }
};

// ATLS (1.12): the texture atlas's header; page_count AtlasPageEntry and
// region_count AtlasRegionEntry records follow, then the pages' names.
struct AtlasHeader {
  static constexpr std::uint32_t kSize = 16;
  std::uint32_t page_count;    // 1..kMaxAtlasPages
  std::uint32_t region_count;  // M x N: a region per part and pose, part-major (as the part images)
  std::uint32_t flags;         // kAtlasPremultiplied
  std::uint32_t reserved;
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.page_count), f(r.region_count), f(r.flags), f(r.reserved);
  }
};

// ATLS: a page's size in pixels.
struct AtlasPageEntry {
  static constexpr std::uint32_t kSize = 8;
  std::uint32_t width;
  std::uint32_t height;
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.width), f(r.height);
  }
};

// ATLS: where a part's drawing in a pose lies on a page: the crop of the
// drawing the part samples, width x height pixels whose top left is pixel
// (canvas_x, canvas_y) of the drawing's canvas (negative, or past its
// size, where the mesh reaches past the canvas: transparent there), lies at
// (x, y) on page `page`, padding around it. So the page's uv is
// (u W / PW + (x - canvas_x) / PW, v H / PH + (y - canvas_y) / PH) for the
// rig's uv (u, v), W x H the pose's canvas (CANV), PW x PH the page's size.
struct AtlasRegionEntry {
  static constexpr std::uint32_t kSize = 20;
  std::uint16_t page;
  std::uint16_t x, y, width, height;
  std::uint16_t reserved;
  std::int32_t canvas_x, canvas_y;
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.page), f(r.x), f(r.y), f(r.width), f(r.height), f(r.reserved), f(r.canvas_x), f(r.canvas_y);
  }
};

// QPOS (1.3): the quantised positions' header; pose_count Point records
// (each pose's origin) and the Exp-Golomb stream follow.
struct QuantPositionsHeader {
  static constexpr std::uint32_t kSize = 16;
  double step;
  std::uint32_t code_order;  // Exp-Golomb order k, 0..20 (every pose, or pose 0 against pose 0)
  // Bits (compact_codec.h): kPositionsAgainstPose0 (1.13), the poses after
  // the first coded against pose 0 (their residuals less pose 0's), each
  // after its own order in 5 bits; kPositionsFromNeighbours (1.14), each
  // vertex predicted by the mean of its earlier neighbours, not by the
  // previous vertex. Zero before 1.13.
  std::uint32_t prediction;
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.step), f(r.code_order), f(r.prediction);
  }
};

// A point (x, y): QPOS's pose origins.
struct Point {
  static constexpr std::uint32_t kSize = 16;
  double x;
  double y;
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.x), f(r.y);
  }
};

// QTRI (1.3): the delta-coded triangles' header; the stream follows.
struct CodedTrianglesHeader {
  static constexpr std::uint32_t kSize = 8;
  std::uint32_t code_order;  // Exp-Golomb order k, 0..20
  std::uint32_t reserved;
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.code_order), f(r.reserved);
  }
};

// QPRM (1.3): a packed array's header; the values follow, `width` bits each.
struct PackedArrayHeader {
  static constexpr std::uint32_t kSize = 8;
  std::uint32_t width;  // 1..32
  std::uint32_t reserved;
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.width), f(r.reserved);
  }
};

// QTRN (1.3): whole turns, base + a packed value of `width` bits each.
struct TurnsHeader {
  static constexpr std::uint32_t kSize = 8;
  std::int32_t base;
  std::uint32_t width;  // 0..32
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.base), f(r.width);
  }
};

// QGRD (1.3): the quantised weight grid's header; coded_poses GridPoseCode
// records and the Exp-Golomb stream follow.
struct GridHeader {
  static constexpr std::uint32_t kSize = 16;
  double step;
  std::uint32_t coded_poses;  // N, or N - 1 with the last pose 1 minus the others
  std::uint32_t reserved;
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.step), f(r.coded_poses), f(r.reserved);
  }
};

// QGRD: one coded pose's code parameters.
struct GridPoseCode {
  static constexpr std::uint32_t kSize = 4;
  std::uint8_t corner_order;       // Exp-Golomb order of the corner codes, 0..20
  std::uint8_t centre_order;       // of the cell centres' codes, 0..20
  std::uint16_t prediction_order;  // the corners' predictor: 1 or 2
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.corner_order), f(r.centre_order), f(r.prediction_order);
  }
};

// QUVA (1.3): per pose, its uvs as an affine map of a pose's positions.
struct AffineUvEntry {
  static constexpr std::uint32_t kSize = 56;
  std::uint32_t source_pose;
  std::uint32_t reserved;
  double map[6];  // u = m0 x + m1 y + m2, v = m3 x + m4 y + m5
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.source_pose), f(r.reserved), f(r.map);
  }
};

// QINF (optional, not read by the loader): what the compact encoding
// measured, for `posemorph-bake info`.
struct CompactInfo {
  static constexpr std::uint32_t kSize = 32;
  double error_budget_px;      // the bake's --max-error
  double max_error_px;         // the largest vertex error measured
  double pose_point_error_px;  // the largest at the pose points
  double pixels_per_unit;      // drawing pixels per rig unit
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.error_budget_px), f(r.max_error_px), f(r.pose_point_error_px), f(r.pixels_per_unit);
  }
};

PM_FORMAT_RECORD(FileHeader);
PM_FORMAT_FIELD(FileHeader, version_major, 8);
PM_FORMAT_FIELD(FileHeader, version_minor, 10);
PM_FORMAT_FIELD(FileHeader, header_size, 12);
PM_FORMAT_FIELD(FileHeader, file_size, 16);
PM_FORMAT_FIELD(FileHeader, section_count, 24);
PM_FORMAT_FIELD(FileHeader, flags, 28);
PM_FORMAT_FIELD(FileHeader, checksum, 32);
PM_FORMAT_FIELD(FileHeader, reserved, 36);
PM_FORMAT_RECORD(SectionEntry);
PM_FORMAT_FIELD(SectionEntry, reserved, 4);
PM_FORMAT_FIELD(SectionEntry, offset, 8);
PM_FORMAT_FIELD(SectionEntry, size, 16);
PM_FORMAT_RECORD(Meta);
PM_FORMAT_FIELD(Meta, flags, 28);
PM_FORMAT_FIELD(Meta, grid_origin_x, 32);
PM_FORMAT_FIELD(Meta, rig_size, 64);
PM_FORMAT_RECORD(PathEntry);
PM_FORMAT_FIELD(PathEntry, flags, 4);
PM_FORMAT_RECORD(EventEntry);
PM_FORMAT_FIELD(EventEntry, path, 8);
PM_FORMAT_FIELD(EventEntry, reserved, 12);
PM_FORMAT_RECORD(PlacementRecord);
PM_FORMAT_FIELD(PlacementRecord, anchor_y, 8);
PM_FORMAT_FIELD(PlacementRecord, flags, 16);
PM_FORMAT_FIELD(PlacementRecord, reserved, 20);
PM_FORMAT_RECORD(PartEntry);
PM_FORMAT_FIELD(PartEntry, triangle_count, 4);
PM_FORMAT_FIELD(PartEntry, draw_order, 8);
PM_FORMAT_FIELD(PartEntry, reserved, 12);
PM_FORMAT_RECORD(ChannelsHeader);
PM_FORMAT_FIELD(ChannelsHeader, attachment_count, 4);
PM_FORMAT_FIELD(ChannelsHeader, reserved, 8);
PM_FORMAT_RECORD(AttachmentEntry);
PM_FORMAT_FIELD(AttachmentEntry, parent_triangle, 4);
PM_FORMAT_FIELD(AttachmentEntry, joint_triangle, 8);
PM_FORMAT_FIELD(AttachmentEntry, reserved, 12);
PM_FORMAT_FIELD(AttachmentEntry, parent_weights, 16);
PM_FORMAT_FIELD(AttachmentEntry, joint_weights, 40);
PM_FORMAT_FIELD(AttachmentEntry, offset, 64);
PM_FORMAT_FIELD(AttachmentEntry, size, 72);
PM_FORMAT_RECORD(AtlasHeader);
PM_FORMAT_FIELD(AtlasHeader, region_count, 4);
PM_FORMAT_FIELD(AtlasHeader, flags, 8);
PM_FORMAT_FIELD(AtlasHeader, reserved, 12);
PM_FORMAT_RECORD(AtlasPageEntry);
PM_FORMAT_FIELD(AtlasPageEntry, height, 4);
PM_FORMAT_RECORD(AtlasRegionEntry);
PM_FORMAT_FIELD(AtlasRegionEntry, x, 2);
PM_FORMAT_FIELD(AtlasRegionEntry, height, 8);
PM_FORMAT_FIELD(AtlasRegionEntry, reserved, 10);
PM_FORMAT_FIELD(AtlasRegionEntry, canvas_x, 12);
PM_FORMAT_FIELD(AtlasRegionEntry, canvas_y, 16);
PM_FORMAT_RECORD(QuantPositionsHeader);
PM_FORMAT_FIELD(QuantPositionsHeader, code_order, 8);
PM_FORMAT_FIELD(QuantPositionsHeader, prediction, 12);
PM_FORMAT_RECORD(Point);
PM_FORMAT_FIELD(Point, y, 8);
PM_FORMAT_RECORD(CodedTrianglesHeader);
PM_FORMAT_FIELD(CodedTrianglesHeader, reserved, 4);
PM_FORMAT_RECORD(PackedArrayHeader);
PM_FORMAT_FIELD(PackedArrayHeader, reserved, 4);
PM_FORMAT_RECORD(TurnsHeader);
PM_FORMAT_FIELD(TurnsHeader, width, 4);
PM_FORMAT_RECORD(GridHeader);
PM_FORMAT_FIELD(GridHeader, coded_poses, 8);
PM_FORMAT_FIELD(GridHeader, reserved, 12);
PM_FORMAT_RECORD(GridPoseCode);
PM_FORMAT_FIELD(GridPoseCode, centre_order, 1);
PM_FORMAT_FIELD(GridPoseCode, prediction_order, 2);
PM_FORMAT_RECORD(AffineUvEntry);
PM_FORMAT_FIELD(AffineUvEntry, reserved, 4);
PM_FORMAT_FIELD(AffineUvEntry, map, 8);
PM_FORMAT_RECORD(CompactInfo);
PM_FORMAT_FIELD(CompactInfo, pixels_per_unit, 24);

}  // namespace posemorph::format
