// SPDX-License-Identifier: MIT
// Per-frame work, ozz-animation style: a plain struct of inputs and
// caller-owned output spans; Validate() checks them, Run() does the work.
// Neither allocates nor throws. Run() returns false (and does nothing) when
// Validate() would.
#pragma once
#include "posemorph/export.h"
#include <cstdint>

#include "posemorph/rig.h"
#include "posemorph/span.h"

namespace posemorph {

// Weights at a pose-space point. The point is clamped to the baked grid (the
// field is constant beyond it); a NaN coordinate is replaced by pose 0's
// coordinate, so any input gives a finite, defined result.
//
// Validate() fails (and Run() does nothing) when: rig is null or not loaded;
// raw is null or shorter than N (the rig's pose count); limited or texture is
// given (non-empty) but null or shorter than N.
struct PM_API WeightsJob {
  const Rig* rig = nullptr;
  double x = 0, y = 0;
  double sigma = 0;           // texture sharpening in [0, 1] (clamped)
  bool limit_weights = true;  // false: limited = raw
  Span<double> raw;           // N: sum 1, may be negative or > 1
  // N, optional: the limited weights, phi(w) renormalised (phi = clamped
  // smoothstep): what MorphJob blends the stretches with (the paper limits
  // shear and scale, which raw weights would extrapolate).
  Span<double> limited;
  // N, optional: sharpened cross-fade weights w'', always a convex
  // combination (from phi(w), also when limit_weights is off) and continuous
  // in sigma up to and including 1.
  Span<double> texture;

  bool Validate() const;
  bool Run() const;
};

// MorphJob and MorphBatchJob refuse weights that are not finite or larger
// than this in magnitude (WeightsJob gives at most the rig's largest grid
// weight, kMaxGridWeight): with the loader's limits on stored values, every
// blend and right-hand side stays finite (the solve itself is checked
// against kMaxPosition).
constexpr double kMaxJobWeight = 1e6;

// The most a solved position may be in magnitude. Every value a rig stores is
// within its limit (rig_format.h), but a factor can still amplify the solve
// (values of 1e3 gave positions near 7.9e303, infinite in float): a job
// whose solve gives a position beyond this, or not finite, writes zeros for
// that character and returns false (its other characters are still
// evaluated). Rigs the bake writes stay far inside it (their solves are
// bounded at 1e7 to 1e12 for weights of kMaxJobWeight).
constexpr double kMaxPosition = 1e30;

enum class Interpolation : std::uint8_t {
  kRigid = 0,   // as-rigid-as-possible (the method)
  kLinear = 1,  // vertex positions blended linearly, for comparison
};

// Vertex positions for given weights.
//
// Validate() fails (and Run() does nothing) when: rig is null or not loaded;
// weights or limited_weights is null or shorter than N; a weight is not finite
// or above kMaxJobWeight in magnitude; workspace is null or shorter than
// rig->morph_workspace_size(); positions is null or shorter than 2V;
// positions_f32 is given but null or shorter than 2V; interpolation is not
// one of the enum's values. Run() also fails, writing zeros, when the solve
// gives a position beyond kMaxPosition or not finite.
struct PM_API MorphJob {
  const Rig* rig = nullptr;
  Span<const double> weights;          // N raw weights (rotation angles, centroid)
  Span<const double> limited_weights;  // N (stretches: shear and scale); pass weights again for no limiting
  Interpolation interpolation = Interpolation::kRigid;
  Span<double> workspace;     // rig->morph_workspace_size() doubles
  Span<double> positions;     // 2 x V, interleaved x, y
  Span<float> positions_f32;  // optional 2 x V copy for the GPU

  bool Validate() const;
  bool Run() const;
};

// Rigid positions for many characters sharing one rig. They are evaluated in
// groups of 8 whose arithmetic runs in SIMD lanes, so the rig's data is read
// once per group; every result equals what MorphJob gives for that character,
// bit for bit. To use several threads, run one job per thread over disjoint
// ranges of characters, each with its own workspace.
//
// Validate() fails (and Run() does nothing) when: rig is null or not loaded;
// count is so large that count x (2V + N) overflows half of size_t; weights
// or limited_weights is null or shorter than count x N; a weight is not finite
// or above kMaxJobWeight in magnitude; workspace is null or shorter than
// rig->batch_workspace_size(); neither positions nor positions_f32 is given;
// one that is given is null or shorter than count x 2V. A count of 0 is valid
// and does nothing, whatever the spans. Run() also fails when some
// character's solve gives a position beyond kMaxPosition or not finite: that
// character's positions are zeros, the others are evaluated.
struct PM_API MorphBatchJob {
  const Rig* rig = nullptr;
  std::size_t count = 0;               // characters
  Span<const double> weights;          // count x N raw weights, character after character
  Span<const double> limited_weights;  // count x N
  Span<double> workspace;              // rig->batch_workspace_size() doubles
  Span<double> positions;              // count x 2V, or empty when only floats are wanted
  Span<float> positions_f32;           // count x 2V, or empty; at least one of the two

  bool Validate() const;
  bool Run() const;
};

// The attachments of a character with several control channels (format
// 1.7, Rig::attachment), for `count` characters sharing one rig: each
// attachment's own rigid solve with its channel's weights (as MorphBatchJob,
// or MorphJob for one character, gives it), turned by the rotation of its
// parent triangle in the character's body positions and moved so that its
// joint lies on the parent's joint (DESIGN.md section 8). The body's
// positions are MorphJob's (or MorphBatchJob's) output on the same rig. Only
// the channel's own weights move an attachment's shape; the body moves it
// as a whole. With the same inputs, every character's result is the same
// bits whatever `count` and whichever kernel path.
//
// Layouts: weights and limited_weights hold, channel by channel (1 .. C-1),
// count x rig->channel_rig(c)->pose_count() values (character after
// character); for one character that is rig->attached_weight_count() values
// starting at rig->channel_weight_offset(c). positions (and positions_f32)
// hold, attachment by attachment, count x 2 x that attachment's vertex count:
// for one character, the attachments side by side, 2 x
// rig->attached_vertex_count() in all.
//
// Validate() fails (and Run() does nothing) when: rig is null, not loaded or
// has no attachments; count is so large that count x (2 x
// attached_vertex_count + attached_weight_count) overflows half of size_t;
// body_positions is null or shorter than count x 2V; weights or
// limited_weights is null or shorter than count x attached_weight_count(); a
// weight is not finite or above kMaxJobWeight in magnitude; a body position
// is not finite; workspace is null or shorter than
// rig->attach_workspace_size(); positions is null or shorter than count x 2 x
// attached_vertex_count(); positions_f32 is given but null or that short;
// interpolation is not one of the enum's values. A count of 0 is valid and
// does nothing. Run() also fails when an attachment's solve gives a position
// beyond kMaxPosition or not finite (that attachment's character is placed
// from zeros; the rest are evaluated).
struct PM_API AttachJob {
  const Rig* rig = nullptr;
  std::size_t count = 1;               // characters
  Span<const double> body_positions;   // count x 2V: each character's body (channel 0)
  Span<const double> weights;          // raw weights of channels 1 .. C-1 (layout above)
  Span<const double> limited_weights;  // the same layout; pass weights again for no limiting
  Interpolation interpolation = Interpolation::kRigid;
  Span<double> workspace;     // rig->attach_workspace_size() doubles
  Span<double> positions;     // count x 2 x attached_vertex_count() (layout above)
  Span<float> positions_f32;  // optional copy for the GPU, the same layout

  bool Validate() const;
  bool Run() const;
};

// The scalar maps behind WeightsJob, exposed for tests and renderers.
PM_API double LimitWeight(double w);  // smoothstep clamped to [0, 1]
PM_API void TextureWeights(Span<const double> limited_weights, double sigma, Span<double> out);

}  // namespace posemorph
