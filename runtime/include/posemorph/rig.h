// SPDX-License-Identifier: MIT
// A baked rig: immutable after loading, safe to share between threads and
// characters. All arrays live in one arena allocated by LoadRig.
#pragma once
#include "posemorph/export.h"
#include <cstddef>
#include <cstdint>
#include <memory>

#include "posemorph/error.h"
#include "posemorph/grid_location.h"
#include "posemorph/isa.h"
#include "posemorph/machine_views.h"
#include "posemorph/span.h"

namespace posemorph {

namespace detail {
struct KernelTable;
struct RigInternals;
}  // namespace detail

enum class PathInterpolation : std::uint8_t { kLinear = 0, kCatmullRom = 1 };

// A named event on a path (format 1.8; RIG_DESCRIPTION.md, "events"): a
// footstep, a sound cue. The Animator reports each one it crosses
// (animator.h).
struct EventView {
  StringView name;
  std::uint32_t path = 0;  // the path it belongs to
  double time = 0;         // on the path's clock: within its first and last key times
};

// A pose-space animation path: keys (time, x, y), times strictly increasing.
struct PathView {
  StringView name;
  bool loop = false;
  PathInterpolation interpolation = PathInterpolation::kLinear;
  Span<const double> keys;  // 3 x key count: t0, x0, y0, t1, x1, y1, ...
  // The path's events in time order (ties in the description's order);
  // empty before format 1.8 and for paths without events.
  Span<const EventView> events;
  std::size_t key_count() const { return keys.size / 3; }
  // The first and last key's times (a loaded path has at least one key); 0 for an empty view.
  double start_time() const { return keys.size >= 3 ? keys.data[0] : 0.0; }
  double end_time() const { return keys.size >= 3 ? keys.data[keys.size - 3] : 0.0; }
};

// The regular pose-space grid whose vertex values are the baked weights
// (its geometry and point location: grid_location.h).
struct PoseSpaceGrid : GridGeometry {
  Span<const double> weights;  // (cells_x+1)*(cells_y+1) vertices x N, row-major in y then x
  // cells_x*cells_y cell centres x N, row-major in y then x (format 1.2): each
  // cell is four triangles meeting at its centre, a tessellation with the
  // grid's mirror and quarter-turn symmetries. Empty for rigs baked before
  // 1.2, whose cells are split on the (0,0)-(1,1) diagonal.
  Span<const double> centre_weights;
};

// The LDL^T factor of the pinned cotangent system, permuted: P K P^T = L D L^T.
struct Factor {
  std::uint32_t n = 0;                  // vertex_count - 1 (vertex 0 is pinned)
  Span<const std::uint32_t> order;      // order[k'] = free unknown k placed at k'
  Span<const std::uint32_t> col_start;  // n + 1, strict lower part of L by column
  Span<const std::uint32_t> row;        // nnz
  Span<const double> value;             // nnz
  Span<const double> inv_diagonal;      // n, 1 / D
};

namespace detail {
// Internal: the factor as the solve kernels read it, built at load (the
// loader fills it, the kernels reach it through RigInternals; no public
// accessor). The strict lower triangle both by columns (Factor's) and by
// rows, with indices pre-doubled to address the interleaved x, y pairs.
struct SolveLayout : Factor {
  Span<const std::uint32_t> row_start;  // n + 1
  Span<const std::uint32_t> row_col2;   // nnz: 2 x column, row by row (when the 16-bit copy is empty)
  Span<const double> row_value;         // nnz
  Span<const std::uint32_t> col_row2;   // nnz: 2 x row, column by column (as `row`)
  // The same two index arrays in 16 bits when 2n < 65536 (most rigs), in
  // place of the 32-bit ones: the solve streams fewer bytes. Empty otherwise.
  Span<const std::uint16_t> row_col2_16, col_row2_16;
};
}  // namespace detail

// A box of a pose space (Rig::pad_range): what a pad or a joystick maps to.
struct PadRange {
  double min_x = 0, min_y = 0, max_x = 0, max_y = 0;
};

// A pose's drawing: its canvas size and where the rig origin (0, 0) sits on
// the canvas (x right, y down), in drawing units (pixels for a PNG). A rig
// unit is a drawing unit, y up. All zero when the pose has no drawing or the
// rig predates format 1.1.
enum class TextureFilter { kLinear, kNearest };

struct DrawingCanvas {
  double width = 0, height = 0;
  double pivot_x = 0, pivot_y = 0;
};

// A texture a renderer uploads (Rig::page): a page of the rig's texture
// atlas (format 1.12), or, for a rig without one, one drawing as the bake
// found it. The drawing part p shows in pose i lies on page
// part_region(p, i).page.
struct TexturePage {
  // An atlas page: a PNG file beside the rig file (relative to its folder).
  // Without an atlas: part_image(p, i), found in the drawing folder.
  StringView name;
  std::uint32_t width = 0, height = 0;  // pixels (without an atlas: the pose's canvas; 0 when unknown)
  bool atlas = false;                   // an atlas page (beside the rig), not a drawing
  bool premultiplied = false;           // its pixels are premultiplied RGBA (atlas pages); drawings: straight alpha
};

// Where a part's drawing in a pose lies on its page: sample page `page` at
// (u scale_u + offset_u, v scale_v + offset_v), where (u, v) are the rig's
// uvs (Rig::uvs: 0..1 over the drawing's canvas). The part samples pixels
// inside x, y, width, height of the page (padding lies around it). Without
// an atlas: the identity, and the whole drawing.
struct TextureRegion {
  std::uint32_t page = 0;
  float scale_u = 1, offset_u = 0, scale_v = 1, offset_v = 0;
  std::uint32_t x = 0, y = 0, width = 0, height = 0;  // page pixels
};

// A part of a layered character (format 1.6): a run of the rig's triangles
// with its own drawings, drawn in order. A rig without parts is one part
// covering every triangle, named "", drawing the poses' images.
struct PartView {
  StringView name;
  std::uint32_t first_triangle = 0, triangle_count = 0;
  std::int32_t draw_order = 0;  // lower draws first (behind); ties in part order
};

class Rig;

// An attachment of a character with several control channels (format 1.7):
// a part driven by its own channel (a face's eyes and mouth by "face" while
// "body" drives the rest). It is a rig of its own, whose poses are its
// channel's; a frame solves it on its own, as rigidly as possible with its
// joint pinned, then turns it by the rotation of the parent triangle (the
// polar factor of that triangle's deformation from this rig's pose 0) and
// moves its joint onto the parent's joint (AttachJob, jobs.h; DESIGN.md
// section 8). So a channel's weights move no vertex of another channel.
struct AttachmentView {
  const Rig* rig = nullptr;              // the attachment's own rig: mesh, poses, drawings, paths
  std::uint32_t channel = 0;             // 1 .. channel_count() - 1
  std::uint32_t parent_triangle = 0;     // in the rig holding the attachment
  double parent_weights[3] = {0, 0, 0};  // the joint's barycentric weights in it (pose 0)
  std::uint32_t joint_triangle = 0;      // in the attachment's rig
  double joint_weights[3] = {0, 0, 0};   // the joint's barycentric weights there (its pose 0)
};

// Bounds for rigs from sources the game does not control (characters that
// players send): a rig beyond one is refused with ErrorCode::kTooLarge and a
// message naming the bound, before its arrays are read, so that the load's
// memory and each frame's solve stay within what the bounds allow. Each 0
// keeps the format's own limit (rig_format.h), as LoadOptions does by
// default. A character's attachments count with it: their bytes are inside
// the file, their memory inside its arena, their vertices and factors add
// to the body's.
struct LoadLimits {
  std::uint64_t max_bytes = 0;            // the file
  std::uint64_t max_memory = 0;           // the rig's arena (RigMemorySize), attachments included
  std::uint32_t max_vertices = 0;         // the body's and every attachment's together
  std::uint32_t max_poses = 0;            // in any one pose space (the body's, a channel's)
  std::uint32_t max_attachments = 0;      // parts of later channels
  std::uint64_t max_factor_nonzeros = 0;  // the solve's work per frame, body and attachments together
  // Factor nonzeros per vertex and bit of the vertex count, in each pose
  // space (nnz <= max_fill x V x ceil(log2 V)): the fill of an order the
  // bake would not write, however small the rig. The bake's orders give at
  // most 0.9 for the samples and 2.7 for a 90,000-vertex grid.
  std::uint32_t max_fill = 0;
  // Bounds for a game loading characters from players: 4 MiB files, 32 MiB
  // in memory, 20,000 vertices, 8 attachments, 1,000,000 factor nonzeros,
  // a fill of 8 (the samples need at most 1.4 MB files, 2 MB of memory, 991
  // vertices with attachments and 5,730 nonzeros). docs/runtime.md says
  // what they cost.
  static LoadLimits Untrusted() {
    LoadLimits l;
    l.max_bytes = std::uint64_t(4) << 20;
    l.max_memory = std::uint64_t(32) << 20;
    l.max_vertices = 20000;
    l.max_poses = 64;
    l.max_attachments = 8;
    l.max_factor_nonzeros = 1000000;
    l.max_fill = 8;
    return l;
  }
};

struct LoadOptions {
  // Tests turn this off to prove the structural checks alone keep corrupted
  // bytes from crashing the loader; applications leave it on.
  bool verify_checksum = true;
  // Tests turn this off to reach the jobs' own check of their output: the
  // loader refuses a rig whose solve could pass kMaxPosition (jobs.h) for
  // some weights the jobs accept; applications leave it on.
  bool bound_solve = true;
  // Tests turn this on to run the solve with 32-bit indices (what rigs of
  // 32,768 vertices or more use) on a small rig.
  bool wide_solve_indices = false;
  // The kernel path every job on this rig runs (all give the same bits).
  // kAuto takes the environment variable POSEMORPH_ISA when it is set, else
  // the fastest path the CPU runs. A path this build lacks or this CPU
  // cannot run fails the load with ErrorCode::kUnsupportedIsa.
  Isa isa = Isa::kAuto;
  // Bounds beyond the format's (LoadLimits::Untrusted() for rigs from players).
  LoadLimits limits;
};

class PM_API Rig {
 public:
  Rig();
  ~Rig();
  Rig(Rig&&) noexcept;
  Rig& operator=(Rig&&) noexcept;
  Rig(const Rig&) = delete;
  Rig& operator=(const Rig&) = delete;

  bool loaded() const { return vertex_count_ != 0; }
  std::uint32_t vertex_count() const { return vertex_count_; }
  std::uint32_t triangle_count() const { return triangle_count_; }
  std::uint32_t pose_count() const { return pose_count_; }
  std::uint32_t path_count() const { return path_count_; }

  Span<const std::uint32_t> triangles() const { return triangles_; }  // 3 x T
  Span<const double> pose_positions(std::uint32_t pose) const;        // 2 x V, interleaved
  Span<const double> pose_points() const { return pose_points_; }     // 2 x N
  Span<const double> pose_centroids() const { return pose_centroids_; }
  Span<const double> vertex_masses() const { return vertex_masses_; }  // sum 1
  Span<const double> gradients() const { return gradients_; }          // 6 x T: area * D^T E^-1
  Span<const double> angles() const { return angles_; }                // N x T (triangle-major)
  // The symmetric stretch S of each triangle in each pose, 3N x T: S11, S12, S22.
  Span<const double> stretches() const { return stretches_; }
  Span<const float> uvs(std::uint32_t pose) const;  // 2 x V, or empty
  StringView pose_name(std::uint32_t pose) const;
  StringView pose_image(std::uint32_t pose) const;  // reference as written by the bake; may be empty
  DrawingCanvas pose_canvas(std::uint32_t pose) const;
  // Parts (format 1.6; 1 for older rigs and rigs baked without "parts").
  std::uint32_t part_count() const { return part_table_.empty() ? 1u : std::uint32_t(part_table_.size / 4); }
  PartView part(std::uint32_t index) const;  // an empty view beyond part_count()
  // The drawing part `index` shows in `pose`: pose_image(pose) for a rig without parts.
  StringView part_image(std::uint32_t index, std::uint32_t pose) const;
  // Texture pages (format 1.12, ATLS): the atlas the bake packed the
  // drawings into, or, for a rig without one (older rigs, rigs baked with
  // "atlas": false), one page per part and pose: page p x N + i is
  // part_image(p, i) with an identity region. Renderers upload the pages
  // and sample part_region(p, i) of page part_region(p, i).page; the same
  // code draws both. An attachment's rig has its own list (an atlas's
  // pages are the character's: the same names).
  bool has_atlas() const { return has_atlas_; }
  std::uint32_t page_count() const { return std::uint32_t(pages_.size); }
  TexturePage page(std::uint32_t index) const;                              // empty beyond the count
  TextureRegion part_region(std::uint32_t part, std::uint32_t pose) const;  // identity on page 0 beyond the counts
  // Part indices back to front (by draw order, ties by index): the order a
  // renderer draws them in. Never empty for a loaded rig. A rig whose order
  // changes with the pose (RIG_DESCRIPTION.md, "order" per pose) has one
  // sequence per pose: a frame draws in its dominant drawing's pose's order
  // (DrawList::parts); without a pose, pose 0's.
  Span<const std::uint32_t> draw_sequence() const { return draw_sequence(0); }
  Span<const std::uint32_t> draw_sequence(std::uint32_t pose) const;  // empty beyond pose_count()
  // Part `index`'s draw order in `pose` (part(index).draw_order when it does
  // not change with the pose); 0 beyond the counts.
  std::int32_t part_draw_order(std::uint32_t index, std::uint32_t pose) const;
  bool draw_order_changes() const { return !part_pose_orders_.empty(); }
  // Control channels (format 1.7; 1 for older rigs and rigs with one). The
  // rig is channel 0; every other channel drives one or more attachments.
  std::uint32_t channel_count() const { return channel_count_; }
  // The channel's name; "" for a rig with one channel.
  StringView channel_name(std::uint32_t channel) const;
  // The rig whose poses, pose points, weight grid and paths are the
  // channel's: this rig for channel 0, the channel's first attachment's rig
  // for another (every attachment of a channel has its pose count). A
  // WeightsJob on it gives the channel's weights. Null beyond the count.
  const Rig* channel_rig(std::uint32_t channel) const;
  // Index of the channel with this name, or -1.
  int FindChannel(const char* name) const;
  std::uint32_t attachment_count() const { return std::uint32_t(attachments_.size); }
  AttachmentView attachment(std::uint32_t index) const;  // an empty view beyond the count
  // Vertices of all attachments together (what AttachJob writes per character).
  std::uint32_t attached_vertex_count() const { return attached_vertex_count_; }
  // The channels' weights side by side, as AttachJob reads them: channels 1
  // .. C-1, each its channel_rig's pose count; 0 for a rig with one channel.
  std::uint32_t attached_weight_count() const { return attached_weight_count_; }
  // Where channel c's weights start in that layout (c >= 1; 0 otherwise).
  std::uint32_t channel_weight_offset(std::uint32_t channel) const;
  // Doubles an AttachJob needs as workspace, whatever its character count.
  std::size_t attach_workspace_size() const { return attach_workspace_; }

  PathView path(std::uint32_t index) const;
  // Index of the path with this name, or -1.
  int FindPath(const char* name) const;
  // Every path's events, path after path (format 1.8; 0 before): event(i)
  // is the i-th, PathView::events a path's own run of them.
  std::uint32_t event_count() const { return std::uint32_t(events_.size); }
  EventView event(std::uint32_t index) const;  // an empty view beyond the count
  Span<const EventView> events() const { return events_; }

  // The state machine (format 1.9): empty spans when the rig has none.
  Span<const MachineInputView> machine_inputs() const { return machine_inputs_; }
  Span<const MachineLayerView> machine_layers() const { return machine_layers_; }
  Span<const MachineStateView> machine_states() const { return machine_states_; }
  // Index of the input, or of the state, with this name; -1 when none has it.
  int FindMachineInput(const char* name) const;
  int FindMachineState(const char* name) const;

  const PoseSpaceGrid& grid() const { return grid_; }
  const Factor& factor() const { return solve_; }
  double default_sigma() const { return default_sigma_; }
  // How the drawings want to be sampled (the description's "filter"; pixel
  // art: nearest). A hint for renderers; linear for rigs before format 1.4.
  TextureFilter texture_filter() const { return texture_filter_; }
  // Where the character stands, in rig units (y up): the point of its
  // drawings that Transform2D::Place puts at a world position (the
  // description's "anchor"; by default, and for rigs before format 1.11,
  // the bottom centre of pose 0's bounds). facing_left(): the drawings face
  // left (the description's "facing"; by default right), so Place mirrors
  // them to face the way the game asks.
  double anchor_x() const { return anchor_x_; }
  double anchor_y() const { return anchor_y_; }
  bool facing_left() const { return facing_left_; }
  bool anchor_given() const { return anchor_given_; }  // set in the description (PLCE), not the default
  // The pad's useful range: the pose points' bounds widened by a tenth of
  // their larger extent (at least one weight-grid cell) on each side,
  // within the weight grid (points beyond it are clamped to it anyway).
  PadRange pad_range() const;
  // Where the bake found the drawings (the description's folder), relative
  // to the folder of the rig file it wrote, '/'-separated: where a tool on
  // that machine looks for pose_image() references by default (the viewer's
  // --images). Empty for rigs before format 1.5, baked in memory, or whose
  // drawings lie on another root. It may contain '..' and comes from the
  // file: a game ships its drawings where it likes and ignores it.
  StringView drawing_folder() const { return drawing_folder_; }
  // The diagonal of pose 0's bounding box: the rig's scale, which relative
  // tolerances multiply.
  double bounding_box_diagonal() const { return rig_size_; }

  // Doubles a MorphJob needs as workspace.
  std::size_t morph_workspace_size() const { return 4 * std::size_t(vertex_count_); }
  // Doubles a MorphBatchJob needs as workspace, whatever its character count.
  std::size_t batch_workspace_size() const;
  std::size_t arena_bytes() const { return arena_size_; }
  // The CRC-32 stored in the file and its format version: two network peers
  // compare them to know they hold the same rig.
  std::uint32_t checksum() const { return checksum_; }
  std::uint16_t format_major() const { return format_major_; }
  std::uint16_t format_minor() const { return format_minor_; }
  // True when the file holds the compact encoding (runtime/FORMAT.md,
  // "Compact encoding"), decoded at load; false for exact doubles.
  bool compact_encoding() const { return compact_encoding_; }
  // The kernel path chosen at load (never kAuto once loaded).
  Isa isa() const;

 private:
  friend struct RigLoader;
  friend struct detail::RigInternals;  // the kernels' layout (runtime/src/rig_internals.h)

  std::unique_ptr<unsigned char[]> arena_;
  std::size_t arena_size_ = 0;
  std::uint32_t vertex_count_ = 0, triangle_count_ = 0, pose_count_ = 0, path_count_ = 0;
  Span<const std::uint32_t> triangles_;
  Span<const double> pose_positions_, pose_points_, pose_centroids_, vertex_masses_;
  Span<const double> gradients_, angles_, stretches_;
  // The angles and stretches regrouped at load for SIMD: per block of 8
  // triangles, per pose, the 8 values of alpha, S11, S12, S22 (4N x 8 per block).
  Span<const double> blend_blocks_;
  Span<const float> uvs_;
  Span<const double> canvases_;  // 4N, or empty
  Span<const StringView>
      strings_;  // N names, N images, P path names (, drawing folder) (, part strings) (, event names)
  Span<const std::uint32_t> part_table_;        // 4 per part (PART), or empty
  Span<const std::uint32_t> draw_sequence_;     // part indices back to front, or empty; N x M with PORD
  Span<const std::uint32_t> part_pose_orders_;  // N x M i32 (PORD), or empty
  Span<const StringView> part_strings_;         // M names, then M x N images, or empty
  Span<const TexturePage> pages_;               // ATLS's pages, or M x N drawings
  Span<const TextureRegion> regions_;           // M x N, part-major
  bool has_atlas_ = false;
  Span<const PathView> paths_;
  Span<const EventView> events_;                 // format 1.8, or empty
  Span<const MachineInputView> machine_inputs_;  // format 1.9 (MACH), or empty
  Span<const MachineLayerView> machine_layers_;
  Span<const MachineStateView> machine_states_;
  // Format 1.7: the attachments (each a Rig in the arena, loaded in place)
  // and the channel names; empty for a rig with one channel.
  Span<const AttachmentView> attachments_;
  Span<const StringView> channel_names_;
  Span<const std::uint32_t> channel_offsets_;  // C: channel_weight_offset
  std::uint32_t channel_count_ = 1, attached_vertex_count_ = 0, attached_weight_count_ = 0;
  std::size_t attach_workspace_ = 0;
  PoseSpaceGrid grid_;
  detail::SolveLayout solve_;
  double default_sigma_ = 0, rig_size_ = 0;
  double anchor_x_ = 0, anchor_y_ = 0;
  bool facing_left_ = false, anchor_given_ = false;
  TextureFilter texture_filter_ = TextureFilter::kLinear;
  StringView drawing_folder_;
  const detail::KernelTable* kernels_ = nullptr;
  std::uint32_t checksum_ = 0;
  std::uint16_t format_major_ = 0, format_minor_ = 0;
  bool compact_encoding_ = false;
};

// Validates every byte and builds a Rig. On failure returns false, fills err
// (if given) and leaves *out empty. Never throws; the only allocation is the
// rig's arena.
PM_API bool LoadRig(const void* data, std::size_t size, Rig* out, Error* err,
                    const LoadOptions& options = LoadOptions());

// A section of a rig file (runtime/FORMAT.md): its tag (four ASCII letters
// read as a little-endian u32, format::kMeta ...), where its bytes start in
// the file and how many there are.
struct RigSection {
  std::uint32_t tag = 0;
  std::uint64_t offset = 0, size = 0;
};

// The file's section table, read and checked as LoadRig reads it (header,
// checksum, each section in bounds, aligned and apart from the others; not
// what the sections hold): for tools that show where a rig's bytes go.
// Writes the sections in file-table order to out[0 .. *count). False, with
// err, where LoadRig would refuse the header or the table, and
// (kInvalidArgument) when `capacity` is below the count; format::kMaxSections
// entries are always enough. Never throws or allocates.
PM_API bool ReadRigSections(const void* data, std::size_t size, RigSection* out, std::uint32_t capacity,
                            std::uint32_t* count, Error* err = nullptr);

// Caller-owned memory, as Cubism Core does it: ask for the size, then load
// into memory you provide (aligned to kRigMemoryAlignment). Nothing is
// allocated; the rig's arrays live in `memory`, which must outlive the rig
// and every use of it (the Rig object itself owns nothing then). The bytes
// may be released after loading, as with LoadRig.
constexpr std::size_t kRigMemoryAlignment = 16;
// The bytes of memory LoadRigInPlace needs for this rig (the header, section
// table and counts are validated; the values only when loading).
PM_API bool RigMemorySize(const void* data, std::size_t size, std::size_t* needed, Error* err,
                          const LoadOptions& options = LoadOptions());
// LoadRig into `memory`: fails with kInvalidArgument when memory is null,
// misaligned or smaller than RigMemorySize says.
PM_API bool LoadRigInPlace(const void* data, std::size_t size, void* memory, std::size_t memory_size, Rig* out,
                           Error* err, const LoadOptions& options = LoadOptions());

}  // namespace posemorph
