// SPDX-License-Identifier: MIT
// Where a rig is used, as points of its pose space: the pose points, a grid
// over their convex hull, the hull's edges, the segment between every two
// pose points, and every path. The bake evaluates its rig there with the
// runtime: to choose the compact encoding's steps (compact_rig.h) and to find
// folding in-betweens (inbetween_check.h).
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "posemorph/rig.h"

namespace posemorph::bake {

struct PoseSpaceSampling {
  int grid = 24;       // grid cells along each side of the pose points' bounding box (points inside the hull kept)
  int per_edge = 32;   // parts each hull edge is cut into
  int per_pair = 0;    // parts the segment between every two pose points is cut into (0: none)
  int per_path = 200;  // parts each path's duration is cut into
};

struct PoseSpaceSample {
  Eigen::Vector2d at;
  std::int32_t path = -1;  // the path it lies on, or -1
  bool in_hull = true;     // inside or on the convex hull of the pose points
};

// In this order: pose points, hull edges, grid, pairs, paths.
std::vector<PoseSpaceSample> SamplePoseSpace(const Rig& rig, const PoseSpaceSampling& sampling);

// The convex hull, counter-clockwise, collinear points dropped (fewer than
// three points when the pose points are collinear).
std::vector<Eigen::Vector2d> ConvexHull(std::vector<Eigen::Vector2d> points);

// The frame at a pose-space point with the rig's default settings (raw and
// limited weights, as a game's first call gives). False if a job fails.
bool EvaluateFrame(const Rig& rig, const Eigen::Vector2d& at, std::vector<double>& positions);
// The same, with the limited weights (what the texture weights come from).
bool EvaluateFrame(const Rig& rig, const Eigen::Vector2d& at, std::vector<double>& positions,
                   std::vector<double>& limited_weights);
// What EvaluateFrames works in, kept from one call to the next (a large
// rig's workspace is then allocated once): positions holds the frames.
struct FrameBuffers {
  std::vector<double> raw, limited, workspace;
  std::vector<double> positions;  // count x 2V, frame after frame
};

// The frames at at[first], ..., at[first + count - 1] into buffers.positions,
// each bit for bit what EvaluateFrame gives: MorphBatchJob, which reads the
// rig's data once per group of kFrameBatch frames. False if a job fails.
// Callers that may stop early pass kFrameBatch frames at a time.
constexpr std::size_t kFrameBatch = 8;
bool EvaluateFrames(const Rig& rig, const std::vector<Eigen::Vector2d>& at, std::size_t first, std::size_t count,
                    FrameBuffers& buffers);

// How many runs EvaluateFramesOnEachCore cuts n points into: one per
// thread (threads 0: per core), at most 8 (each run holds its own buffers,
// and its caller's per-run results), at most one per kFrameBatch group, at
// least one.
std::size_t FrameRunCount(std::size_t n, unsigned threads = 0);
// The frames at every point of `at` on the machine's cores: the points are
// cut into FrameRunCount(at.size(), threads) runs of kFrameBatch groups,
// each run evaluated group by group into its own buffers (parts[run], sized
// here), and visit(run, first, count, positions) called after each group
// with that group's count frames. A visit that returns false, or a job that
// fails, stops every run at its next group. Visits of one run come in
// order, different runs' at once, so a visit writes only what belongs to
// its run or its points, and the caller merges the runs in order: the
// outcome is then the same bits on any number of cores. False if a job
// failed.
bool EvaluateFramesOnEachCore(
    const Rig& rig, const std::vector<Eigen::Vector2d>& at, std::vector<FrameBuffers>& parts,
    const std::function<bool(std::size_t run, std::size_t first, std::size_t count, const double* positions)>& visit,
    unsigned threads = 0);

}  // namespace posemorph::bake
