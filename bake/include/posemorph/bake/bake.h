// SPDX-License-Identifier: MIT
// The whole bake: description in, rig bytes out (DESIGN.md section 2).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "posemorph/bake/compact_rig.h"
#include "posemorph/bake/ghosting.h"
#include "posemorph/bake/inbetween_check.h"
#include "posemorph/bake/map_drawings.h"
#include "posemorph/bake/output_file.h"
#include "posemorph/bake/pose_meshes.h"
#include "posemorph/bake/rig_description.h"
#include "posemorph/bake/rig_sections.h"
#include "posemorph/bake/texture_atlas.h"
#include "posemorph/rig.h"

namespace posemorph::bake {

// One attachment of a character with control channels (bake_channels.h).
struct AttachmentReport {
  std::string part, channel, parent;  // the part, its channel, the body part it hangs from
  std::uint32_t vertices = 0, triangles = 0, poses = 0;
  std::uint32_t parent_triangle = 0;  // the body triangle under its joint
  std::uint64_t bytes = 0, exact_bytes = 0;
  double max_reproduction_error = 0;  // its own rig's, relative to its size
  // The attachment's drawn shape in each of its channel's poses, placed with
  // its joint on the body's (body at pose 0): the largest vertex distance from
  // what the whole rig evaluates there, in rig units.
  double placed_error = 0;
};

struct BakeReport {
  std::uint32_t vertices = 0, triangles = 0, poses = 0, paths = 0;
  // A layered character (join_parts.h): its parts (name, draw order,
  // triangles) and glue joints (shared vertices); empty without "parts".
  std::vector<MeshPart> parts;
  std::vector<std::uint32_t> joints;
  std::uint64_t factor_nonzeros = 0;  // strict lower part of L
  std::uint64_t matrix_nonzeros = 0;  // lower part of K, diagonal included
  std::uint32_t grid_cells_x = 0, grid_cells_y = 0;
  // A grid coarser than the default, chosen for a small sprite
  // (grid_resolution.h), and the estimate of how far its weights move a
  // vertex from the default grid's, at most (pixels; 0 when not coarsened).
  bool grid_coarsened = false;
  double grid_move_px = 0;
  std::uint64_t bytes = 0;
  double max_reproduction_error = 0;  // at the pose points, relative to the rig size (checked by the runtime)
  double seconds = 0;
  bool compact = false;               // the encoding written
  std::uint64_t exact_bytes = 0;      // size of the exact encoding
  double max_error_px = 0;            // the budget (compact)
  double pixels_per_unit = 0;         // drawing pixels per rig unit used for it
  CompactReport compact_report;       // what the compact encoding reached
  InbetweenCheck inbetweens;          // the rig written, evaluated over the pose hull and the paths
  std::vector<std::string> warnings;  // "FILE: ..." (folds, when allowed)
  MappingReport mapping;              // what mapping the drawings made (mapped: false when none is drawn)
  // The ghosting measure of the rig written (ghosting.h), when every pose
  // draws a PNG drawing; else why not.
  Ghosting ghosting;
  std::string ghosting_skipped;
  // Control channels (format 1.7): their names (empty with one channel) and
  // the attachments; the fields above are then the body's (the first
  // channel's parts), but bytes and seconds the whole rig's, and
  // exact_bytes the body's and the attachments' exact encodings summed.
  std::vector<std::string> channels;
  std::vector<AttachmentReport> attachments;
  // What the rig written draws (ReadRigDrawings), read from the bake's own
  // verification load: whether it can have a texture atlas.
  RigDrawings drawings;
};

// The paper's pipeline, one step per header: map the drawings
// (map_drawings.h) -> the rig's meshes, deformed poses computed
// (deform_poses.h) -> orient (orient_triangles.h) -> validate
// (validate_rig.h) -> analyse the poses: angles and stretches
// (pose_analysis.h) -> build and factor the ARAP system (arap_system.h) ->
// solve the pose-space weights (pose_space_weights.h) -> write
// (serialise_rig.h; compact_rig.h within the error budget) -> check the
// poses with the runtime (reproduction_check.h) -> check the in-betweens for
// folds (inbetween_check.h) -> measure the ghosting (ghosting.h). When the in-betweens fold inside the pose hull
// and the meshes come from drawings, the bake maps them again (the fold
// retries of map_again.h: matched-sample spacing x2, longest edge x1.5,
// both; the same with the outlines' thin notches filled; last the first
// pose's mesh deformed onto the others; the first fold-free one is written,
// with a warning naming it); if every
// variant folds, the fold of the mapping as given throws unless
// description.parameters.allow_folds (then the first mapping is written).
// Returns the rig's bytes. Throws BakeError naming the file and the problem.
std::vector<unsigned char> BakeRig(const RigDescription& description, BakeReport* report = nullptr);

// A baked rig: its sections, the file's bytes (WriteRig of them) and the Rig
// the bake's verification loaded from exactly those bytes (the runtime as
// the oracle), so that a later step adds to the sections or reads the rig
// without reading the bytes back.
struct BakedRig {
  RigSections sections;
  std::vector<unsigned char> bytes;
  Rig rig;                        // the bytes as the bake's checks loaded them
  PoseMeshes meshes;              // the poses it must give back
  double reproduction_tolerance;  // within this (relative to the rig's size)
};

// BakeRig for one pose space: a description without control channels, or
// one channel's part of a character (BakeCharacter bakes each with it).
// Throws BakeError as BakeRig does, and on a description with channels.
BakedRig BakeOne(const RigDescription& description, BakeReport* report = nullptr);

}  // namespace posemorph::bake
