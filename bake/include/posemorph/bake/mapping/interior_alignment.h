// SPDX-License-Identifier: MIT
// Stage 7 of N-way mapping: the drawings align the interiors (issue
// "Interior correspondence", docs/DESIGN.md section 7). The outlines and the
// features fix where the meshes' boundaries and feature vertices go; every
// other vertex of every pose after the first then moves so that its drawing,
// seen through its mesh, looks like the first pose's drawing seen through the
// first pose's mesh: eyes, mouths and patches that the outlines alone leave
// apart come together, and the cross-fade stops drawing them twice.
//
// The method: for pose k, minimise over its free vertices x
//   E(x) = sum over the pixels p of pose 0's mesh |I_k(x(p)) - I_0(p)|^2
//        + rigidity * sum over triangles t, edges (a, b) of t
//                     |(x_a - x_b) - R_t (xbar_a - xbar_b)|^2
// where x(p) is p's barycentric point in pose k's mesh, I the premultiplied
// RGBA drawing, xbar the mesh the mapping made and R_t the rotation that fits
// t best (as-rigid-as-possible, Alexa et al. section 3; local/global as in
// Sorkine and Alexa). Gauss-Newton (Lucas-Kanade on the mesh's vertices),
// coarse to fine over a 2x box pyramid blurred by a binomial kernel, the rotations
// refitted every step, a sparse LDLT per step, and a step that would turn a
// triangle over or shrink its smallest angle too far (angle_keep) is halved
// until it does not (or dropped).
#pragma once
#include <cstdint>
#include <vector>

#include "posemorph/bake/triangle_math.h"

namespace posemorph::bake::mapping {

// A drawing as the alignment reads it: premultiplied RGBA in [0, 1], rows top
// to bottom; pixel (i, j) covers [i, i + 1] x [j, j + 1].
struct AlignmentImage {
  int width = 0, height = 0;
  std::vector<float> rgba;
};
// From straight-alpha 8-bit RGBA (what libpng's simplified API reads),
// halved `halvings` times (each pixel the mean of the 2^h x 2^h it covers,
// transparent beyond the edge): coordinates divide by 2^halvings.
AlignmentImage AlignmentImageFromRgba(const unsigned char* rgba, int width, int height, int halvings = 0);
// The halvings that bring a drawing's longer side to at most kAlignmentMaxSide
// pixels: the alignment's memory and time stay bounded on any drawing.
constexpr int kAlignmentMaxSide = 1024;
int AlignmentHalvings(int width, int height);

struct AlignmentParameters {
  double rigidity = 0.005;  // the ARAP term's weight against the colour term (colour^2 per pixel^2)
  int levels = 4;           // pyramid levels: 1/8, 1/4, 1/2 and full resolution
  int iterations = 30;      // Gauss-Newton steps per level, at most
  // A triangle's smallest angle may fall to angle_keep of its value before,
  // but not below min_angle_floor_degrees, nor below the smallest angle of
  // the whole mesh (every pose) before when that is less: the mesh's
  // smallest angle ends at least min(before, the floor). The bake passes the
  // description's mapping.min_angle: the alignment keeps the quality asked
  // of the mesh, or never lowers the smallest angle when refinement could
  // not reach it.
  double angle_keep = 0.5;
  double min_angle_floor_degrees = 20;
  // Regions of flat colour (interior_regions.h) matched between pose 0 and
  // pose k pull their centres together: region_weight x the region's area
  // (pixels) x the squared distance joins the energy, so the descent starts
  // from where the regions went, not from where the outlines put them.
  bool match_regions = true;
  double region_weight = 0.003;
};

struct AlignmentReport {
  // Per pose (0 for the reference): the mean absolute colour difference (of
  // 1, over the RGBA channels) between pose 0's drawing and pose k's seen
  // through the meshes, over the pixels of pose 0's mesh, before and after;
  // the largest distance a vertex moved (pixels).
  std::vector<double> difference_before, difference_after, max_move;
  std::vector<int> regions_found;    // per pose: its interior regions
  std::vector<int> regions_matched;  // per pose: those paired with pose 0's (0 for pose 0)
  int steps = 0;                     // Gauss-Newton steps taken, all poses
  double seconds = 0;
};

// vertices[k]: pose k's mesh in its drawing's pixels (x right, y down), all
// poses with the same `triangles`; images[k] its drawing. Moves every vertex
// of poses 1.. for which fixed[v] is false; pose 0 is the reference. Every
// triangle keeps its orientation in every pose, and its smallest angle stays
// at least angle_keep times what it was. Time: O(levels x iterations x
// (pixels of pose 0's mesh + vertices^1.5)) per pose.
void AlignInteriors(const std::vector<AlignmentImage>& images, const Triangles& triangles,
                    const std::vector<bool>& fixed, std::vector<Points>& vertices,
                    const AlignmentParameters& parameters = {}, AlignmentReport* report = nullptr);

}  // namespace posemorph::bake::mapping
