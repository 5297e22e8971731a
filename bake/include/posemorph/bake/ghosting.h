// SPDX-License-Identifier: MIT
// The ghosting measure (issue "Interior correspondence"): how much two
// poses' drawings disagree when the cross-fade lays them on the same
// in-between. At the midpoint between two adjacent poses the runtime's mesh
// is drawn twice, once with each pose's drawing at that pose's uvs, and the
// measure is the mean absolute difference of the two pictures' premultiplied
// RGBA (of 255, averaged over the four channels) over the pixels where either
// is at least half opaque: 0 when the interiors line up, larger the more an
// eye or a patch is drawn in two places.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "posemorph/rig.h"

namespace posemorph::bake {

// A pose's drawing: straight-alpha RGBA bytes, rows top to bottom.
struct DrawingPixels {
  std::uint32_t width = 0, height = 0;
  const unsigned char* rgba = nullptr;
};

// Premultiplied RGBA (of 1) of a drawing at uv (0..1 across it, y down),
// bilinear between pixel centres, transparent outside the drawing (the
// viewer's clamp-to-border sampler).
void SampleDrawing(const DrawingPixels& d, double u, double v, double out[4]);

struct GhostingPair {
  std::uint32_t a = 0, b = 0;  // pose indices, a < b
  std::string name_a, name_b;  // their names
  Eigen::Vector2d at;          // the midpoint of their pose points
  double difference = 0;       // of 255
  std::uint64_t pixels = 0;    // pixels compared (rig units are drawing pixels)
};

// A point of the pose hull where two drawings or more cross-fade (texture
// weights of kGhostingMinTextureWeight or more): the same measure with
// every such drawing, weighted: sum_(i<j) w_i w_j |c_i - c_j| over
// sum_(i<j) w_i w_j, per pixel (for two drawings, their difference).
struct GhostingSample {
  Eigen::Vector2d at;
  std::uint32_t drawings = 0;  // how many cross-fade there
  double difference = 0;       // of 255
  std::uint64_t pixels = 0;
};

struct Ghosting {
  std::vector<GhostingPair> pairs;  // in order of a, then b
  double mean = 0;                  // over the pairs
  // Over the pose hull: the in-between check's points (pose_space_samples.h)
  // on a kGhostingHullGrid grid and kGhostingHullEdge parts per hull edge,
  // those where two drawings or more cross-fade; their mean and the worst.
  std::vector<GhostingSample> hull;
  double hull_mean = 0;
  std::size_t hull_worst = 0;
};
constexpr int kGhostingHullGrid = 8, kGhostingHullEdge = 4;
constexpr double kGhostingMinTextureWeight = 0.05;

// Adjacent poses: two pose points with no third strictly inside the circle
// on their segment (the Gabriel graph: neighbours of the Delaunay
// triangulation that face each other; on a line, the consecutive points).
std::vector<std::pair<std::uint32_t, std::uint32_t>> AdjacentPoses(const Rig& rig);

// The measure for every pair of adjacent poses of a rig baked from drawings
// (drawings[i] is pose i's, at any size: it is sampled at the uvs), and at
// the points of the pose hull, rasterised at one pixel per rig unit, or
// coarser so that no in-between takes more than kGhostingMaxPixels samples
// (per drawing drawn; the hull's points share kGhostingMaxHullPixels). Throws BakeError(file) when
// the rig has no uvs or does not evaluate. The bounds are those of a
// drawing of 512 x 512 pixels, so that an HD drawing's measure costs what
// a 512-pixel one's does (the bake measures up to four meshes: Pip drawn at
// 2048 px spent a fifth of its bake here with bounds four times larger).
constexpr double kGhostingMaxPixels = 262144, kGhostingMaxHullPixels = 4194304;
Ghosting MeasureGhosting(const Rig& rig, const std::vector<DrawingPixels>& drawings, const std::string& file);

// A drawing halved (premultiplied 2 x 2 means) until its longer side is at
// most max_side: what the bake keeps of each drawing for the measure (512:
// no finer than the measure's raster of kGhostingMaxPixels samples).
std::vector<unsigned char> ReduceDrawing(std::vector<unsigned char> rgba, std::uint32_t* width, std::uint32_t* height,
                                         std::uint32_t max_side = 512);

// "rest-stretch 4.1, rest-squash 3.2, ...; mean 3.6 (of 255)".
std::string DescribeGhosting(const Ghosting& ghosting);
// "mean 3.9 over 41 points, worst 6.2 at (0.5, 0.25) with 3 drawings (of 255)".
std::string DescribeHullGhosting(const Ghosting& ghosting);

}  // namespace posemorph::bake
