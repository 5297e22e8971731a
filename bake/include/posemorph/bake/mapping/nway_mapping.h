// SPDX-License-Identifier: MIT
// N-way mapping (DESIGN.md section 4, paper section 3.1): N drawings of one
// character in, N compatible triangle meshes out. Stages, one file each:
//   outline_image.cpp / outline_svg.cpp   drawing -> simple CCW polygon
//   boundary_matching.cpp                 dense corresponding boundary points
//   enclosing_simplification.cpp          fewer points, still enclosing
//   compatible_triangulation.cpp          stages I-III
//   compatible_refinement.cpp             splits, flips, smoothing
//   nway_mapping.cpp                      the driver
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "posemorph/bake/rig_description.h"

namespace posemorph::bake::mapping {

using Point = Eigen::Vector2d;
using Polygon = std::vector<Point>;  // closed implicitly

// --- Outlines -------------------------------------------------------------

struct ImageOutline {
  Polygon outline;  // pixel units, y down (image rows); either orientation
  int width = 0, height = 0;
  int dropped_components = 0;  // separate parts smaller than the kept shape
  std::size_t dropped_pixels = 0;
  std::vector<std::size_t> dropped_parts;  // pixels of each dropped part, largest first
  std::size_t shape_pixels = 0;            // every pixel at or above the threshold, before anything is dropped
  std::size_t filled_hole_pixels = 0;
};
// PNG with alpha: pixels with alpha >= threshold form the shape; the largest
// 4-connected component is kept, holes filled, diagonal pinches closed, and
// the outline traced where alpha crosses the threshold (marching squares,
// sub-pixel). Throws BakeError naming the file.
ImageOutline OutlineFromPng(const std::string& path, double alpha_threshold);
// The same from a PNG already in memory (`file` names it in messages).
ImageOutline OutlineFromPngBytes(const std::vector<unsigned char>& png, double alpha_threshold,
                                 const std::string& file);
// The alpha channel of a PNG (any colour type), row by row. Throws BakeError naming the file.
std::vector<unsigned char> ReadPngAlpha(const std::string& path, int* width, int* height);
ImageOutline OutlineFromAlpha(const std::vector<unsigned char>& alpha, int width, int height, double alpha_threshold,
                              const std::string& file);

struct SvgOutline {
  Polygon outline;            // user units, y down; either orientation
  Point canvas_origin{0, 0};  // viewBox origin (or 0, 0)
  Point canvas_size{0, 0};    // viewBox size (or width, height)
};
// The element with id="outline" if there is one, else the first <path> or
// <polygon>: M/L/H/V/C/Q/Z (absolute and relative) and polygon points; curves
// flattened to `tolerance`. Throws BakeError naming the file.
SvgOutline OutlineFromSvg(const std::string& path, double tolerance);
SvgOutline OutlineFromSvgText(const std::string& text, double tolerance, const std::string& file);
// Path data alone ("M 0 0 L 10 0 ..."), first subpath.
Polygon FlattenSvgPath(const std::string& d, double tolerance, const std::string& file);

// --- Geometry on the integer grid --------------------------------------------
// All mapping stages run on coordinates snapped to an integer grid (|x| <
// 2^26), so orientation tests are exact in 64-bit integers.

int Orient(const Point& a, const Point& b, const Point& c);  // +1 left turn, -1 right, 0 collinear
double SignedArea(const Polygon& p);
bool IsSimplePolygon(const Polygon& p);  // no two edges meet except neighbours at their shared vertex
// +1 strictly inside, 0 on the boundary, -1 outside. Exact.
int PointInPolygon(const Polygon& p, const Point& q);
// Every point of `inner` (vertices and edges) inside or on `outer`. Exact.
bool Encloses(const Polygon& outer, const Polygon& inner);

// --- Correspondence ---------------------------------------------------------

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
struct MatchingParameters {
  double spacing = 1.0;        // arc length between samples on pose 0's outline
  double stretch_cost = 0.05;  // per unmatched step, against bending differences in radians
  int bending_scale = 3;       // turning angle measured over +-this many samples
};
struct CorrespondedBoundary {
  std::vector<Polygon> points;          // per pose, M corresponding points on its outline
  std::vector<std::vector<double>> at;  // per pose, their arc-length positions (from the outline's vertex 0)
  std::vector<std::size_t> landmarks;   // index of each landmark among the M points
  double spacing = 0;                   // the spacing used: parameters.spacing, or more on long outlines
};
// outlines: CCW; landmarks[i][k]: the k-th user point of pose i (the first is
// the start point), already on outline i. Pose 0 is the parameter domain.
CorrespondedBoundary MatchBoundaries(const std::vector<Polygon>& outlines,
                                     const std::vector<std::vector<Point>>& landmarks,
                                     const MatchingParameters& parameters);
// Arc length from vertex 0 at each vertex, closing edge included (size n + 1; the last is the perimeter).
std::vector<double> CumulativeArcLength(const Polygon& outline);
// Where on `outline` (arc length from vertex 0) the point nearest q lies, and how far it is.
double NearestArcLength(const Polygon& outline, const Point& q, double* distance);
Point PointAtArcLength(const Polygon& outline, double s);

// --- Simplification ---------------------------------------------------------

struct SimplifiedBoundary {
  std::vector<Polygon> polygons;       // per pose, K vertices, simple, CCW, enclosing the outline
  std::vector<std::size_t> kept;       // index among the M corresponding points of each vertex
  std::vector<std::size_t> landmarks;  // index among the K vertices of each landmark
  double max_error = 0;                // largest distance added between outline and polygon
};
// Greedily removes corresponding N-tuples with the smallest error (maximum over
// poses) while it stays <= tolerance, sliding neighbours outward so every
// polygon keeps enclosing its outline and stays simple. Landmarks are kept.
SimplifiedBoundary SimplifyEnclosing(const std::vector<Polygon>& outlines, const CorrespondedBoundary& boundary,
                                     double tolerance);

// --- Compatible triangulation -------------------------------------------------

struct CompatibleMesh {
  std::vector<Polygon> vertices;                      // per pose, one position per vertex
  std::vector<std::array<std::size_t, 3>> triangles;  // shared, CCW in every pose
  std::size_t boundary_vertices = 0;                  // vertices 0..boundary_vertices-1 are the polygon's, in order
  std::size_t steiner_points = 0;                     // interior vertices the triangulation added
};
// Splits all N polygons along chords valid in every pose (stage I), through
// one Steiner point per pose (II) or the fewest over shortest link paths
// (III) until every piece is a triangle. Throws BakeError naming `what` when
// no compatible split exists or more than `max_steiner_points` would be needed.
CompatibleMesh TriangulateCompatibly(const std::vector<Polygon>& polygons, const std::string& what,
                                     std::size_t max_steiner_points);

struct RefinementParameters {
  double max_edge_length = 0;  // 0: no splitting for length
  double min_angle_goal = 20;  // degrees; triangles below it get their longest edge split (bounded)
  int rounds = 4;
  std::size_t max_vertices = 20000;  // no split beyond this many vertices
};
// Edge splits, flips legal in all N meshes that raise the smallest angle over
// all poses, and angle-based smoothing of interior vertices that never
// inverts a triangle or lowers the local smallest angle. Boundary vertices
// stay where they are (only new points on boundary edges are added).
// Stops splitting at parameters.max_vertices; returns false when splitting
// for max_edge_length stopped there (the edges are then longer than asked).
bool RefineCompatibly(CompatibleMesh& mesh, const RefinementParameters& parameters);

double MinAngleDegrees(const CompatibleMesh& mesh);  // over all triangles and poses

// --- All stages -------------------------------------------------------------

struct MappingStages {
  double grid_scale = 1;                      // grid units per rig unit (a power of two)
  std::vector<Polygon> outlines;              // grid, counter-clockwise, simple
  std::vector<std::vector<Point>> landmarks;  // on the outlines, grid
  CorrespondedBoundary matched;
  SimplifiedBoundary simplified;
  CompatibleMesh mesh;                // grid
  std::vector<std::string> warnings;  // limits that changed what was asked (e.g. a coarser spacing)
};
// Outlines and landmarks in rig coordinates (y up, any orientation); labels
// name each pose in messages. The driver behind MapDrawings, exposed so
// tests can check every stage's promise. Throws BakeError naming `file`.
MappingStages MapPolygons(const std::vector<Polygon>& outlines, const std::vector<std::vector<Point>>& landmarks,
                          const MappingParameters& parameters, const std::vector<std::string>& labels,
                          const std::string& file);

}  // namespace posemorph::bake::mapping
