// SPDX-License-Identifier: MIT
// What a renderer needs to draw characters, computed in one job: positions
// (floats, rig units), the triangles, the drawings to blend with their
// weights and uvs, and where the character stands (a 2D transform). The
// runtime never draws: a renderer turns each DrawList into its own draw
// calls (see "Drawing a DrawList" below). No allocation and nothing thrown,
// like every job.
#pragma once
#include <cstddef>
#include <cstdint>

#include "posemorph/export.h"
#include "posemorph/jobs.h"
#include "posemorph/rig.h"
#include "posemorph/rig_format.h"
#include "posemorph/span.h"

namespace posemorph {

// At most this many drawings per character (a renderer's K is 1..8).
constexpr std::uint32_t kMaxBlendDrawings = 8;

// A 2D affine transform from rig units to the renderer's world units:
//   x' = a x + c y + tx,  y' = b x + d y + ty
// i.e. the columns (a, b) and (c, d) of a 2x2 matrix (column-major, as
// glm::mat2 and GLSL mat2 store it) and a translation. Floats: the renderer
// applies it (on the GPU); the runtime's positions stay in rig units, so a
// transform never changes the bits lockstep peers compare.
struct Transform2D {
  float a = 1, b = 0, c = 0, d = 1;
  float tx = 0, ty = 0;

  // Scale (sx, sy), then flip horizontally (facing left: x -> -x) when
  // flip_x, then rotate counter-clockwise by `radians` (y up), then move to
  // (x, y). Non-finite inputs, and inputs whose fields would not fit a
  // float, give the identity: the fields are always finite.
  static PM_API Transform2D Make(double x, double y, double radians = 0, double scale_x = 1, double scale_y = 1,
                                 bool flip_x = false);
  // A character of `rig` standing at world (x, y): its anchor
  // (Rig::anchor_x/_y, the point it stands on) goes there, scaled, turned
  // counter-clockwise by `radians` about it, and facing left when face_left
  // (mirrored about the anchor's vertical when that is not the way its
  // drawings face: Rig::facing_left). The identity for non-finite inputs.
  static PM_API Transform2D Place(const Rig& rig, double x, double y, double radians = 0, double scale = 1,
                                  bool face_left = false);
  // A mirrored transform (negative determinant) turns counter-clockwise
  // triangles clockwise: a renderer that culls must cull the other face.
  bool mirrors() const { return double(a) * d - double(b) * c < 0; }
  void Apply(double x, double y, double* out_x, double* out_y) const {
    *out_x = double(a) * x + double(c) * y + tx;
    *out_y = double(b) * x + double(d) * y + ty;
  }
};
// outer * inner: first inner, then outer (a camera after a character's place);
// the identity when a field of the product would not fit a float.
PM_API Transform2D Compose(const Transform2D& outer, const Transform2D& inner);

// One drawing of a character's cross-fade.
struct BlendedDrawing {
  std::uint32_t pose = 0;      // whose drawing: rig.pose_image(pose)
  float weight = 0;            // renormalised over the picked drawings: they sum to 1
  const float* uvs = nullptr;  // rig.uvs(pose).data (2 x V), or null when the rig has none
};

// The `max_drawings` (1..8) largest texture weights, largest first (ties to
// the lower pose), clamped at 0 and renormalised to sum 1; all N drawings
// when N <= max_drawings. NaN and infinite weights count as 0; when every
// weight is 0 the first picked drawing gets weight 1. The weights written
// are finite and sum to 1 for any input. Writes min(N, max_drawings, out.size) entries (uvs left
// null) and returns that count; 0 for empty input.
PM_API std::uint32_t PickDrawings(Span<const double> texture_weights, std::uint32_t max_drawings,
                                  Span<BlendedDrawing> out);

// A character's colour: a renderer multiplies each premultiplied sample by
// (r, g, b, 1) x a, so (r, g, b) tints (multiplies the drawing's colour) and
// a is the opacity (0 hides, 1 as drawn). Components are in [0, 1].
struct Colour {
  float r = 1, g = 1, b = 1, a = 1;
};
// c with each component clamped to [0, 1]; a NaN component counts as 1 (as drawn).
PM_API Colour ClampColour(const Colour& c);

// One character's frame, ready to draw.
struct DrawList {
  Span<const float> positions;        // 2 x V, interleaved x, y, rig units (y up): a slice of the job's positions
  Span<const std::uint32_t> indices;  // 3 x T, the rig's triangles (counter-clockwise in pose 0)
  // The rig's parts back to front (rig.draw_sequence(drawings[0].pose): the
  // dominant drawing's pose decides, when the order changes with the pose): draw each part's
  // triangles (rig.part(p): indices 3 x first_triangle on, 3 x
  // triangle_count of them) in this order, each with its own drawings
  // (rig.part_image(p, drawings[k].pose)) and the same weights and uvs. A
  // rig without parts lists one part, every triangle.
  Span<const std::uint32_t> parts;
  std::uint32_t drawing_count = 0;  // 1..max_drawings
  BlendedDrawing drawings[kMaxBlendDrawings];
  Transform2D transform;  // rig units -> world
  bool mirrored = false;  // transform.mirrors(): triangles are clockwise in the world
  Colour colour;          // tint and opacity of the whole character (DrawListJob::colours)
  // Each part's own opacity, by part index (rig.part(p)); 1 beyond
  // rig.part_count(). Part p draws at colour.a x part_opacity[p] (PartColour).
  float part_opacity[format::kMaxParts];
  DrawList() {
    for (float& o : part_opacity) o = 1;
  }
};
// What part `part` of a list draws with: the list's tint, at the character's
// opacity times the part's (the character's alone for a part out of range).
inline Colour PartColour(const DrawList& list, std::uint32_t part) {
  Colour c = list.colour;
  if (part < format::kMaxParts) c.a *= list.part_opacity[part];
  return c;
}

// Draw lists for `count` characters sharing one rig, each at its own
// pose-space point. Rigid characters are evaluated as MorphBatchJob does (one
// character as MorphJob): the positions equal theirs bit for bit.
//
// A rig with control channels (format 1.7): give attached_output (and
// attached_positions) to get each character's attachments too, each
// evaluated as AttachJob does (the same bits) at the character's points of
// the later channels (channel_points; empty: each channel at its first
// pose's point), as a DrawList of the attachment's own rig (its positions,
// triangles, parts, drawings picked from its channel's texture weights,
// uvs) with the character's transform. CharacterDrawSteps merges a
// character's lists into one back-to-front order.
//
// An animator's characters (animator.h): give weights, limited_weights and
// texture_weights as AnimatorUpdateJob wrote them (count x N each; points
// empty) instead of points, and for a rig with attachments its
// attached_weights, attached_limited_weights and attached_texture_weights
// (AnimatorUpdateJob's layout; channel_points empty). The lists and
// positions are then what the points would give had WeightsJob written
// those weights: the same bits as MorphBatchJob (MorphJob) and AttachJob
// on them.
//
// Colour (set by code; states of the state machine do not set it yet):
// colours gives each character's tint and opacity (empty: as drawn) and
// part_opacities each character's opacity of each of its parts (count x
// rig.part_count(), part index order; empty: 1 for all); both are clamped
// as ClampColour does (NaN: 1) into the lists. A character's attachments
// draw with its colour and opacity; their own parts' opacities are 1.
//
// Validate() fails (and Run() does nothing) when: rig is null or not
// loaded; count is 0 or above MaxDrawListCount; points holds fewer than 2 x count values
// (weights not given); weights are given and points too, or one of the
// three holds fewer than count x N values, or a raw or limited weight is
// not finite or above kMaxJobWeight in magnitude (the attachments' alike,
// count x attached_weight_count, required with attached_output and
// weights; refused without weights);
// transforms is neither empty nor count long; colours is neither empty nor
// count long; part_opacities is neither empty nor at least count x
// rig.part_count() values; max_drawings is not in
// 1..kMaxBlendDrawings; workspace is shorter than DrawListWorkspaceSize;
// positions holds fewer than count x 2V floats; output holds fewer than
// count lists; attached_output is given for a rig without attachments, or
// holds fewer than count x attachment_count lists, or attached_positions
// fewer than count x 2 x attached_vertex_count floats, or channel_points is
// neither empty nor at least count x 2 x (channel_count - 1) values. Points
// are treated as WeightsJob treats them (clamped to the grid, NaN
// replaced), so any values give a finite frame.
struct PM_API DrawListJob {
  const Rig* rig = nullptr;
  std::size_t count = 1;       // characters
  Span<const double> points;   // count x (x, y), pose space; or empty, with weights:
  Span<const double> weights;  // count x N each, an animator's (above), or all three empty
  Span<const double> limited_weights;
  Span<const double> texture_weights;
  Span<const Transform2D> transforms;  // count, or empty: identity for all
  Span<const Colour> colours;          // count, or empty: as drawn
  Span<const float> part_opacities;    // count x rig->part_count(), or empty: every part opaque
  double sigma = -1;                   // texture sharpening in [0, 1]; < 0 or NaN: the rig's default
  bool limit_weights = true;
  Interpolation interpolation = Interpolation::kRigid;
  std::uint32_t max_drawings = kMaxBlendDrawings;  // K: drawings a renderer blends per character
  Span<double> workspace;                          // DrawListWorkspaceSize(*rig, count) doubles
  Span<float> positions;                           // count x 2V floats
  Span<DrawList> output;                           // count
  // Control channels (above); all three empty for the first channel alone.
  // channel_points: per character, channels 1 .. C-1's (x, y) in turn.
  Span<const double> channel_points;
  // Attachment after attachment, character after character (AttachJob's
  // layout): count x 2 x rig->attached_vertex_count() floats.
  Span<float> attached_positions;
  // Character after character, its attachments in order: count x rig->attachment_count().
  Span<DrawList> attached_output;
  // With weights: the later channels' (AnimatorUpdateJob's layout), count x
  // rig->attached_weight_count() each.
  Span<const double> attached_weights, attached_limited_weights, attached_texture_weights;

  bool Validate() const;
  bool Run() const;
};

// One step of drawing a character: part `part` of list `list`, where list 0
// is the character's own DrawList and list a + 1 its attachment a's.
struct DrawStep {
  std::uint32_t list = 0, part = 0;
};
// The order to draw one character with attachments: every part of its
// body's list and of its attachments' lists (attached: rig.attachment_count()
// lists, may be null when there are none), back to front by their draw
// orders in each list's dominant drawing's pose (ties: the body's parts in
// its order, then the attachments' in attachment order), as posemorph-view
// draws them. Writes min(steps, out.size) entries and returns how many
// steps there are (the body's part count plus one per attachment part).
PM_API std::uint32_t CharacterDrawSteps(const Rig& rig, const DrawList& body, const DrawList* attached,
                                        Span<DrawStep> out);

// The most characters one DrawListJob takes (their buffers' sizes stay far
// inside size_t, also on 32-bit targets); more than this fails Validate.
PM_API std::size_t MaxDrawListCount(const Rig& rig);
// Doubles of workspace a DrawListJob of `count` characters needs (0 when
// count is 0 or above MaxDrawListCount).
PM_API std::size_t DrawListWorkspaceSize(const Rig& rig, std::size_t count);

// Every per-character buffer a DrawListJob needs, sized from the rig in this
// one place. Owns nothing: Bind() carves the job's spans out of one block
// the caller provides (a stack array, an arena, a GPU staging buffer).
struct PM_API CharacterBuffers {
  std::size_t count = 0;       // characters
  std::size_t workspace = 0;   // doubles
  std::size_t positions = 0;   // floats (count x 2V): what a renderer uploads
  std::size_t draw_lists = 0;  // DrawList entries (count)
  // A rig with attachments: their floats (count x 2 x attached_vertex_count)
  // and lists (count x attachment_count), after the three above; 0 otherwise.
  std::size_t attached_positions = 0, attached_lists = 0;
  std::size_t bytes = 0;  // one block holding them all, in that order
  static constexpr std::size_t kAlignment = alignof(double) > alignof(DrawList) ? alignof(double) : alignof(DrawList);

  static CharacterBuffers For(const Rig& rig, std::size_t count);
  // Points job->workspace, positions and output (and, for a rig with
  // attachments, attached_positions and attached_output) into `block` (at
  // least `bytes` long, aligned to kAlignment) and sets job->rig and job->count.
  // False, changing nothing, when the block is too short or misaligned.
  bool Bind(const Rig& rig, void* block, std::size_t block_bytes, DrawListJob* job) const;
};

// Drawing a DrawList (what posemorph-view, the examples and the C API's
// users do). For each character:
//  1. Upload positions (or apply the transform on the CPU) and indices.
//  2. Exact cross-fade: draw the mesh once into a premultiplied-alpha
//     target with a fragment shader that sums, over the picked drawings,
//     weight x premultiplied(drawing_pose(uv_pose)), where uv_pose comes
//     from that drawing's own uvs at the same vertex; then composite the
//     result "over" the scene (ONE, ONE_MINUS_SRC_ALPHA). Because the sum is
//     formed before compositing, a pixel every drawing covers stays opaque.
//     A shader that reads all K drawings at once needs no offscreen target.
//  3. Cheaper, approximate: (a) the dominant drawing only (K = 1): no blend,
//     pops when the largest weight changes hands; (b) K sequential "over"
//     draws, drawing k (largest weight first) at opacity
//     w_k / (w_0 + ... + w_k): exact where every drawing is opaque; along
//     silhouettes that move between drawings the first shows at full
//     strength.
//  4. Colour: multiply the blended premultiplied colour of part p by
//     (r, g, b, 1) x a, with (r, g, b, a) = PartColour(list, p), before
//     compositing it (with the sequential approximation: each draw's).
//  docs/runtime.md "Drawing a character: draw lists" gives their measured cost on Pip.

}  // namespace posemorph
