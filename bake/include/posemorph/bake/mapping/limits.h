// SPDX-License-Identifier: MIT
// The mapping's bounds on work and memory, whatever the drawing (issue: hardening).
#pragma once
#include <cstddef>
#include <cstdint>

namespace posemorph::bake::mapping {

// Bounds on the matching's work, whatever the drawing: pose 0's outline gets
// at most kMaxMatchedSamples samples between landmarks (the spacing grows on
// long outlines), so one span's dynamic programme holds at most
// (kMaxMatchedSamples + 1)^2 one-byte steps (67 MB) and two rows of costs;
// the samples added where another pose stretches are bounded the same way
// against that pose's perimeter. Landmarks: at most kMaxLandmarks per pose.
constexpr std::size_t kMaxMatchedSamples = 8192;
// Outline points per pose, as traced, flattened or given (a 4096-pixel disc
// traces to about 23,000); the exact checks on outlines are at worst quadratic.
constexpr std::size_t kMaxOutlinePoints = 100000;
// A traced PNG border, before collinear points are dropped: bounds the
// tracer's memory on any drawing the pixel limit admits.
constexpr std::size_t kMaxTracedBorder = 1000000;
// The compatible triangulation's work in elementary steps (segment tests,
// Floyd-Warshall relaxations), a few seconds at most.
constexpr std::uint64_t kMaxTriangulationWork = std::uint64_t(4) << 30;
constexpr std::size_t kMaxLandmarks = 512;
constexpr std::size_t kMaxFeatures = 256;  // per pose

}  // namespace posemorph::bake::mapping
