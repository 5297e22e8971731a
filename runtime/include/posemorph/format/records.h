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

namespace posemorph::format {

// ---- encoding ---------------------------------------------------------------

// Writes each field little-endian, one after another.
struct FieldEncoder {
  unsigned char* at;
  void Put(std::uint64_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) *at++ = static_cast<unsigned char>(v >> (8 * i));
  }
  void operator()(const std::uint8_t& v) { Put(v, 1); }
  void operator()(const std::uint16_t& v) { Put(v, 2); }
  void operator()(const std::uint32_t& v) { Put(v, 4); }
  void operator()(const std::int32_t& v) { Put(static_cast<std::uint32_t>(v), 4); }
  void operator()(const std::uint64_t& v) { Put(v, 8); }
  void operator()(const double& v) {
    std::uint64_t bits;
    std::memcpy(&bits, &v, 8);
    Put(bits, 8);
  }
  template <typename T, std::size_t K>
  void operator()(const T (&values)[K]) {
    for (const T& v : values) (*this)(v);
  }
};

// Reads each field little-endian, one after another.
struct FieldDecoder {
  const unsigned char* at;
  std::uint64_t Get(int bytes) {
    std::uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) v |= std::uint64_t(*at++) << (8 * i);
    return v;
  }
  void operator()(std::uint8_t& v) { v = static_cast<std::uint8_t>(Get(1)); }
  void operator()(std::uint16_t& v) { v = static_cast<std::uint16_t>(Get(2)); }
  void operator()(std::uint32_t& v) { v = static_cast<std::uint32_t>(Get(4)); }
  void operator()(std::int32_t& v) { v = static_cast<std::int32_t>(static_cast<std::uint32_t>(Get(4))); }
  void operator()(std::uint64_t& v) { v = Get(8); }
  void operator()(double& v) {
    const std::uint64_t bits = Get(8);
    std::memcpy(&v, &bits, 8);
  }
  template <typename T, std::size_t K>
  void operator()(T (&values)[K]) {
    for (T& v : values) (*this)(v);
  }
};

// Counts the bytes the fields take in the file (compile time).
struct FieldSizer {
  std::size_t size = 0;
  template <typename T>
  constexpr void operator()(const T&) {
    size += sizeof(T);
  }
};

template <typename R>
constexpr std::size_t EncodedSize() {
  R r{};
  FieldSizer s;
  R::Fields(r, s);
  return s.size;
}

// The record's kSize bytes at `out`.
template <typename R>
void EncodeRecord(const R& r, unsigned char* out) {
  FieldEncoder e{out};
  R::Fields(r, e);
}

// The record at `in` (kSize readable bytes).
template <typename R>
R DecodeRecord(const unsigned char* in) {
  R r{};
  FieldDecoder d{in};
  R::Fields(r, d);
  return r;
}

// The record at `offset` of `size` bytes at `data`; false, writing nothing,
// when it does not lie wholly inside them.
template <typename R>
bool ReadRecord(const unsigned char* data, std::uint64_t size, std::uint64_t offset, R* out) {
  if (offset > size || size - offset < R::kSize) return false;
  *out = DecodeRecord<R>(data + offset);
  return true;
}

// Record i of a table of records starting at `data` (bounds checked by the caller).
template <typename R>
R DecodeEntry(const unsigned char* data, std::uint64_t i) {
  return DecodeRecord<R>(data + i * R::kSize);
}

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

// MACH (1.9): a state machine (rig_format.h, kMachine): this header, then
// the inputs', layers', states', transitions' and conditions' entries, the
// layers' behaviours, then the inputs' and the states' names. Ranges are implied: a layer's states
// follow the previous layer's; the transitions are, layer by layer, the
// layer's any-state transitions then each of its states' in order; a
// transition's conditions follow the previous transition's.
struct MachineHeader {
  static constexpr std::uint32_t kSize = 24;
  std::uint32_t input_count;
  std::uint32_t layer_count;
  std::uint32_t state_count;
  std::uint32_t transition_count;
  std::uint32_t condition_count;
  std::uint32_t reserved;
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.input_count), f(r.layer_count), f(r.state_count), f(r.transition_count), f(r.condition_count), f(r.reserved);
  }
};
struct MachineInputEntry {
  static constexpr std::uint32_t kSize = 24;
  std::uint32_t type;  // MachineInputType (rig.h)
  std::uint32_t reserved;
  double default_x;  // bool: 0 or 1; number: its value; point: x
  double default_y;  // point: y; otherwise 0
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.type), f(r.reserved), f(r.default_x), f(r.default_y);
  }
};
struct MachineLayerEntry {
  static constexpr std::uint32_t kSize = 16;
  std::uint32_t channel;
  std::uint32_t state_count;  // 1 or more
  std::uint32_t initial;      // within the layer's states
  std::uint32_t any_count;    // transitions from any state of the layer
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.channel), f(r.state_count), f(r.initial), f(r.any_count);
  }
};
struct MachineStateEntry {
  static constexpr std::uint32_t kSize = 32;
  std::uint32_t kind;   // MachineStateKind (rig.h)
  std::uint32_t path;   // play, blend: in the layer's channel; otherwise 0
  std::uint32_t input;  // pad: a point input; blend: a number input; otherwise 0
  std::uint32_t flags;  // play: bit 0 loop given, bit 1 loop
  double speed;         // play: path seconds per second; otherwise 1
  std::uint32_t transition_count;
  std::uint32_t reserved;
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.kind), f(r.path), f(r.input), f(r.flags), f(r.speed), f(r.transition_count), f(r.reserved);
  }
};
struct MachineTransitionEntry {
  static constexpr std::uint32_t kSize = 32;
  std::uint32_t to;  // a state of the same layer (its index in the machine)
  std::uint32_t condition_count;
  std::uint32_t flags;  // bit 0: exit_time holds
  std::uint32_t reserved;
  double mix;        // seconds of crossfade
  double exit_time;  // of the state's path, 0..1 (bit 0)
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.to), f(r.condition_count), f(r.flags), f(r.reserved), f(r.mix), f(r.exit_time);
  }
};
struct MachineConditionEntry {
  static constexpr std::uint32_t kSize = 16;
  std::uint32_t input;
  std::uint32_t op;  // MachineOp (rig.h)
  double value;
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.input), f(r.op), f(r.value);
  }
};

// One per layer, after the conditions: the behaviours the layer's channel
// runs from the machine's first step (animator.h, Behaviours).
struct MachineBehavioursEntry {
  static constexpr std::uint32_t kSize = 120;
  std::uint32_t enabled;  // 1 blink, 2 breath, 4 look-at, 8 spring
  std::uint32_t blink_pose;
  double blink_interval, blink_jitter, blink_duration, blink_strength;
  std::uint64_t blink_seed;  // plus the character's index in its batch
  double breath_period, breath_x, breath_y;
  std::uint32_t look_input;  // a point input the look-at target follows, or 0xFFFFFFFF
  std::uint32_t reserved;
  double look_smoothing, look_strength;
  double spring_frequency, spring_damping, spring_strength;
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.enabled), f(r.blink_pose), f(r.blink_interval), f(r.blink_jitter), f(r.blink_duration), f(r.blink_strength),
        f(r.blink_seed), f(r.breath_period), f(r.breath_x), f(r.breath_y), f(r.look_input), f(r.reserved),
        f(r.look_smoothing), f(r.look_strength), f(r.spring_frequency), f(r.spring_damping), f(r.spring_strength);
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

// QPOS (1.3): the quantised positions' header; pose_count Point records
// (each pose's origin) and the Exp-Golomb stream follow.
struct QuantPositionsHeader {
  static constexpr std::uint32_t kSize = 16;
  double step;
  std::uint32_t code_order;  // Exp-Golomb order k, 0..20
  std::uint32_t reserved;
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.step), f(r.code_order), f(r.reserved);
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

// Each record's size, field list and C++ layout agree: the fields are
// listed in declaration order with no padding, at these offsets.
#define PM_FORMAT_RECORD(R)                                                         \
  static_assert(sizeof(R) == R::kSize, #R ": the struct is not its record's size"); \
  static_assert(EncodedSize<R>() == R::kSize, #R ": the field list is not the record's size")
#define PM_FORMAT_FIELD(R, field, at) static_assert(offsetof(R, field) == (at), #R "::" #field " is not at byte " #at)
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
PM_FORMAT_RECORD(MachineHeader);
PM_FORMAT_FIELD(MachineHeader, reserved, 20);
PM_FORMAT_RECORD(MachineInputEntry);
PM_FORMAT_FIELD(MachineInputEntry, default_x, 8);
PM_FORMAT_RECORD(MachineLayerEntry);
PM_FORMAT_FIELD(MachineLayerEntry, any_count, 12);
PM_FORMAT_RECORD(MachineStateEntry);
PM_FORMAT_FIELD(MachineStateEntry, speed, 16);
PM_FORMAT_FIELD(MachineStateEntry, reserved, 28);
PM_FORMAT_RECORD(MachineTransitionEntry);
PM_FORMAT_FIELD(MachineTransitionEntry, mix, 16);
PM_FORMAT_FIELD(MachineTransitionEntry, exit_time, 24);
PM_FORMAT_RECORD(MachineConditionEntry);
PM_FORMAT_FIELD(MachineConditionEntry, value, 8);
PM_FORMAT_RECORD(MachineBehavioursEntry);
PM_FORMAT_FIELD(MachineBehavioursEntry, blink_seed, 40);
PM_FORMAT_FIELD(MachineBehavioursEntry, look_input, 72);
PM_FORMAT_FIELD(MachineBehavioursEntry, spring_strength, 112);
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
PM_FORMAT_RECORD(QuantPositionsHeader);
PM_FORMAT_FIELD(QuantPositionsHeader, code_order, 8);
PM_FORMAT_FIELD(QuantPositionsHeader, reserved, 12);
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
#undef PM_FORMAT_RECORD
#undef PM_FORMAT_FIELD

}  // namespace posemorph::format
