// SPDX-License-Identifier: MIT
// The raw input of a bake: N poses of one triangle mesh, their points in pose
// space, optional drawings, bake parameters, animation paths. Schema:
// bake/RIG_DESCRIPTION.md.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "posemorph/bake/texture_atlas.h"
#include "posemorph/rig.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace posemorph::bake {

// A handle of a deformation: a vertex (given by index, or by a point on the
// source mesh that grabs its nearest vertex) and where it goes.
struct HandleDescription {
  bool by_vertex = false;
  std::uint32_t vertex = 0;
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
  Eigen::Vector2d to = Eigen::Vector2d::Zero();
};

// "This pose is pose `from` with these handles dragged" (paper section 3.2).
struct DeformDescription {
  std::string from;
  std::vector<HandleDescription> handles;
};

struct PoseDescription {
  std::string name;
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  std::vector<Eigen::Vector2d> vertices;
  std::string image;                 // as written in the description
  std::vector<Eigen::Vector2f> uvs;  // empty, or one per vertex
  bool deformed = false;             // vertices come from `deform` (deform_poses.h)
  DeformDescription deform;
  // A drawn pose: its mesh comes from N-way mapping (map_drawings.h).
  bool drawn = false;
  std::string drawing;  // PNG or SVG as written; empty for an outline
  // SVG: the layer (group) the outline comes from (mapping/outline_svg.h):
  // "layer" as given (required), or a part's own name (taken when the
  // drawing has a group of that name); empty: the whole drawing.
  std::string layer;
  bool layer_required = false;
  std::string drawing_path;                // resolved against the description's folder
  std::vector<Eigen::Vector2d> outline;    // given directly (rig coordinates, y up)
  std::vector<Eigen::Vector2d> landmarks;  // corresponding boundary points; the first is the start point
  // Corresponding points inside the shape (an eye's centre, a beak's tip),
  // as many and in the same order in every drawn pose: each becomes one mesh
  // vertex at exactly that point in every pose (drawing coordinates, or rig
  // coordinates for an outline, like the landmarks).
  std::vector<Eigen::Vector2d> features;
  // The drawing point (drawing units, y down) that becomes the rig origin, so
  // that drawings on canvases of different sizes or offsets line up; (0, 0)
  // by default: the drawing's own origin.
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
};

// How drawings become meshes (bake/RIG_DESCRIPTION.md, "mapping").
struct MappingParameters {
  // Lengths in working units: the drawing's pixels (or SVG units) at the
  // pyramid level the drawings are traced on (working_size); 0: from the
  // drawing's size (mapping/mapping_sizes.h).
  double simplify_tolerance = 0;  // how far the boundary may stand off the outline
  double max_edge_length = 0;     // longest mesh edge in any pose
  double min_angle = 20;          // degrees: refinement splits triangles below it (bounded rounds)
  // PNG: alpha at or above this is the shape. Low, so the mesh encloses the
  // anti-aliased fringe: the drawing's own alpha draws the silhouette.
  double alpha_threshold = 0.05;
  // PNG: a large dark, semi-transparent region beside or under the shape
  // (mapping/outline_image.h, FindDropShadow) is its drop shadow, left out
  // of the mesh with a warning (so it is not drawn); false traces it as part
  // of the shape, as before.
  bool drop_shadows = true;
  double curve_tolerance = 0.25;    // SVG: curve flattening, drawing units
  double spacing = 0;               // between matched boundary samples
  double landmark_distance = 0.05;  // a landmark may lie this far off its outline, times the outline's size
  int max_steiner_points = 100;     // interior points the compatible triangulation may add
  int max_vertices = 20000;         // refinement's vertex budget (mesh vertices in all)
  // PNG drawings larger than this (longer side, pixels) are traced and
  // mapped on the pyramid level that brings the largest to at most this
  // size (each level halves both sides), so that the same drawing at 256
  // or 4096 pixels gives the same mesh, scaled; the lengths above are that
  // level's pixels. 0: trace at full resolution (lengths in drawing pixels).
  int working_size = 256;
  // PNG drawings align the interiors (mapping/interior_alignment.h): on by
  // default; rigidity weighs the as-rigid-as-possible term against colour.
  bool align_interiors = true;
  double align_rigidity = 0.005;
  // The bake's own variants (map_again.h): where the in-betweens fold, or
  // the mesh is below min_angle, the drawings are mapped again in other
  // ways and the better mesh kept. false: mapped once, as the paper maps
  // them (a quicker bake while editing; the mesh may be poorer or fold).
  bool map_again = true;
  // Where the in-betweens fold, the fold retries are tried until the bake
  // of this pose space has run this long (seconds, by the clock); one
  // found fold-free by then is kept, and a bake that found none fails,
  // saying how many retries were left untried. A retry kept is the same
  // bits on any machine; only whether it is reached depends on the
  // machine's speed. 0: every retry is tried, however long it takes.
  double retry_seconds = 10;
  // Not in the description: the bake's own retries when the in-betweens fold
  // (bake.h) scale the spacing and the longest edge, automatic or given.
  double spacing_scale = 1, edge_scale = 1;
  // Not in the description either: PNG outlines traced with their thin
  // notches filled (mapping/outline_image.h), which the bake tries when the
  // outlines as traced cannot be mapped or their in-betweens fold.
  bool fill_notches = false;
  // Not in the description: the first pose's outline is traced from a PNG
  // drawing, its points about its border's pixels, so the splits for the
  // angle goal keep the mesh in proportion to it (nway_mapping.cpp). A
  // polygon's or an SVG's points say nothing of its size.
  bool proportional_vertices = false;
  // Not in the description: rounds of splitting triangles below min_angle
  // (mapping/compatible_refinement.h). The bake refines further when the
  // mesh it made stays below its quality floor (bake.h).
  int refinement_rounds = 4;
  // Not in the description: refinement also removes the boundary vertices
  // that make slivers opposite a short boundary edge (where one pose
  // squeezes the outline); the bake tries it with refining further.
  bool collapse_slivers = false;
  // Not in the description: the outlines' correspondence averaged over this
  // many matched samples on each side (mapping/boundary_matching.h); the
  // bake tries it with refining further.
  int correspondence_smoothing = 0;
  // Not in the description: the outlines' matching charges this per sample
  // advanced on one outline alone (MatchingParameters::stretch_cost; 0: its
  // default); the bake tries a stiffer matching where the mesh is poor.
  double stretch_cost = 0;
  // Not in the description: the meshes are made by deforming pose 0's mesh
  // onto the other poses (mapping/mesh_registration.h) instead of
  // triangulating all poses together.
  bool registration = false;
  // Not in the description: drawing units per working unit (2^halvings),
  // set by the mapping driver; messages multiply what they measure on the
  // drawing by it, so that they speak in the drawing's pixels.
  double working_scale = 1;
};

struct PathDescription {
  std::string name;
  bool loop = false;
  bool catmull_rom = false;
  std::vector<std::array<double, 3>> keys;  // t, x, y
  // Named events at times on the path's clock ("events": [[0.42,
  // "footstep"], ...]), within its keys' times; sorted by time at parse,
  // ties kept in the description's order. The Animator reports them.
  std::vector<std::pair<double, std::string>> events;
};

struct BakeParameters {
  // Cells along the longer side of the pose-space domain. Unless the
  // description gives it (grid_resolution_given) or code changed it, the
  // bake may take a coarser grid for a small sprite (grid_resolution.h,
  // ChooseGridResolution): a 64-cell grid was a third of a 60-pixel
  // sprite's rig.
  int grid_resolution = 64;
  bool grid_resolution_given = false;
  double margin = 1.0;  // domain = points' bounding box grown by margin x its larger side
  // Not in the description: poses on a horizontal or vertical line get a
  // grid only kLineLayoutCells wide across the line (pose_space_weights.h).
  // The bake sets it where it chooses the grid's resolution itself.
  bool narrow_line_layout = false;
  // Weight of the gradient term relative to the biharmonic one; the field
  // levels out beyond about spread * sqrt(3 / epsilon) from the points.
  double epsilon = 3.0;
  double sigma = 0.25;  // default texture sharpening
  // Encoding (issue: compact rigs): compact within max_error drawing pixels of
  // the exact rig for every vertex of every frame in the pose hull and along
  // the paths, or exact doubles. Pixels per rig unit: 1 when the poses come
  // from drawings (rig units are drawing units); for rigs given as vertices,
  // pixels_per_unit, or by default as if the rig's size were 1024 pixels.
  bool compact = true;
  double max_error_px = 0.01;
  double pixels_per_unit = 0;  // 0: the default above
  // The bake evaluates in-betweens over the pose hull and the paths
  // (inbetween_check.h); a triangle that turns over fails the bake unless
  // folds are allowed (then they are warnings).
  bool allow_folds = false;
};

// A part of a layered character (bake/RIG_DESCRIPTION.md, "parts"): its own
// mesh or drawings in every pose, drawn in order.
struct PartDescription {
  std::string name;
  int order = 0;                                        // draw order: lower draws first (behind); ties in part order
  std::vector<int> pose_orders;                         // empty, or one draw order per rig pose (order is pose 0's)
  std::vector<std::array<std::uint32_t, 3>> triangles;  // when its poses are given as vertices
  std::vector<PoseDescription> poses;                   // one per pose of its channel, in the channel's order
  std::size_t channel = 0;  // the control channel driving it (index into RigDescription::channels)
};

// Two parts held together at a joint: one point of `part` and one of `to`
// become one vertex, so the solve keeps them together in every frame.
struct GlueDescription {
  std::string part, to;
  std::size_t part_index = 0, to_index = 0;
  // The joint: one point per pose (drawing coordinates for drawn parts, rig
  // coordinates for meshes), or one point (meshes only: in pose 0).
  std::vector<Eigen::Vector2d> at;
};

// A control channel (bake/RIG_DESCRIPTION.md, "channels"): a pose space of
// its own, driving some of the parts.
struct ChannelDescription {
  std::string name;
  std::vector<PoseDescription> poses;  // names and points
  std::vector<PathDescription> paths;
};

// A state machine (bake/RIG_DESCRIPTION.md, "state_machine"; the runtime's
// posemorph/state_machine.h): names resolved and checked at parse.
struct MachineInputDescription {
  std::string name;
  MachineInputType type = MachineInputType::kBool;
  double default_x = 0, default_y = 0;
};
struct MachineConditionDescription {
  std::uint32_t input = 0;
  MachineOp op = MachineOp::kIsTrue;
  double value = 0;
};
struct MachineTransitionDescription {
  bool any = false;        // "from": "*"
  std::uint32_t from = 0;  // a state of the layer (index in the layer)
  std::uint32_t to = 0;
  std::vector<MachineConditionDescription> when;
  double mix = 0.2;
  bool has_exit_time = false;
  double exit_time = 0;
};
struct MachineStateDescription {
  std::string name;
  MachineStateKind kind = MachineStateKind::kStop;
  std::uint32_t path = 0;   // play, blend: in the layer's channel
  std::uint32_t input = 0;  // pad, blend
  int loop = -1;
  double speed = 1;
  // "colour" [r, g, b] or [r, g, b, a] and "opacity" a (multiplied into a):
  // the character's while the layer is in this state (format 1.10).
  std::array<double, 4> colour{1, 1, 1, 1};
  // "parts": {"name": opacity}: body parts' opacities, by the part's index
  // in the body (the parts of the first channel, in the description's order).
  std::vector<std::pair<std::uint32_t, double>> part_opacities;
};
struct MachineLayerDescription {
  MachineBehavioursView behaviours;  // "behaviours": what the channel runs from the first step
  std::uint32_t channel = 0;
  std::uint32_t initial = 0;  // in `states`
  std::vector<MachineStateDescription> states;
  std::vector<MachineTransitionDescription> transitions;  // in the description's order (priority)
};
struct StateMachineDescription {
  std::vector<MachineInputDescription> inputs;
  std::vector<MachineLayerDescription> layers;  // empty: no state machine
};

struct RigDescription {
  std::string file;  // where it came from, for messages
  // Where the rig will be written, if known (the CLI's -o): the rig then
  // records the description's folder, where its drawing references resolve,
  // relative to the rig's folder (format 1.5, Rig::drawing_folder).
  std::string rig_file;
  std::string name;
  bool nearest_filter = false;  // "filter": "nearest": the drawings are pixel art (a hint for renderers)
  // "anchor": [x, y], the point the character stands on: in the first pose's
  // drawing pixels (x right, y down) when it is drawn, else in rig units;
  // "facing": "left" when the drawings face left. Written as PLCE (format
  // 1.11) when either is given; the runtime's default otherwise (the bottom
  // centre of pose 0, facing right).
  bool anchor_given = false;
  Eigen::Vector2d anchor = Eigen::Vector2d::Zero();
  bool facing_left = false;
  // "atlas": false, or {"max_page_size": S, "padding": P}: how posemorph-bake
  // packs the drawings into texture pages (texture_atlas.h); on by default.
  AtlasSettings atlas;
  bool atlas_given = false;  // the key was there (the writer keeps it)
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<PoseDescription> poses;  // with parts: names and points only
  std::vector<PartDescription> parts;  // empty: one shape (the poses' own meshes or drawings)
  std::vector<GlueDescription> glue;
  // Empty, or two channels or more: then `poses` and `paths` are the first
  // channel's, and each part names its channel (PartDescription::channel).
  std::vector<ChannelDescription> channels;
  BakeParameters parameters;
  MappingParameters mapping;
  std::vector<PathDescription> paths;
  StateMachineDescription state_machine;
  std::vector<std::string> warnings;  // from reading it: keys this bake does not know (a misspelt option)
  // "import": the layered files (OpenRaster, Photoshop) its drawings were
  // imported from (init writes it): resolved against its folder, and how
  // (`init --channels`, `--flatten`). The bake reads the PNGs as they are;
  // posemorph-view --watch imports again when one of these changes.
  struct Import {
    std::vector<std::string> files;
    bool channels = false, flatten = false;
  } import;
};

// Reads and parses a description; relative mesh paths resolve against its
// folder. Throws BakeError naming the file and the problem.
RigDescription ReadRigDescription(const std::string& path);
RigDescription ParseRigDescription(const std::string& json_text, const std::string& file, const std::string& base_dir);

// Writing (rig_description_writer.cpp), the inverse of reading: the one
// writer of descriptions (the sample generator, the viewer's saves and
// `posemorph-bake deform` use it). ParseRigDescription(RigDescriptionText(d))
// gives back d's poses, triangles, parameters and paths; values written are
// the doubles held, exactly. Optional keys are written when they differ from
// their defaults (the "bake" block's grid_resolution, margin, epsilon and
// sigma always).
std::string RigDescriptionText(const RigDescription& rig);  // one line of JSON and a newline
// The mesh file a pose's "mesh" names: {"triangles": [...], "vertices": [...]}.
std::string MeshFileText(const std::vector<Eigen::Vector2d>& vertices,
                         const std::vector<std::array<std::uint32_t, 3>>& triangles);

// Adds poses and paths to a description's JSON text, keeping everything else
// it says (what the viewer saves into the description it was started with).
// Each added pose's and path's name is a stem: it is written as "STEM-K", the
// smallest K >= 1 that no entry of its list has. BakeError(file, ...) when
// the text is not a JSON object or its "poses" or "paths" is not an array.
struct DescriptionAddition {
  std::string text;  // the description laid out as DescriptionJsonText, and a newline
  std::vector<std::string> pose_names, path_names;
};
DescriptionAddition AddToRigDescription(const std::string& text, const std::string& file,
                                        const std::vector<PoseDescription>& poses,
                                        const std::vector<PathDescription>& paths);
// The description with pose `pose`'s "point" set to (x, y), rounded to 4
// decimals (the first channel's pose in a rig with channels; what the
// viewer's pad saves when a pose point is dragged). BakeError(file, ...)
// when the text is not a JSON object or has no such pose.
std::string MovePosePoint(const std::string& text, const std::string& file, const std::string& pose, double x,
                          double y);
// The description with the "landmarks" (or "features", `key`) of every pose
// of part `part` ("": the rig's own poses) set to lists[pose], in drawing
// coordinates rounded to 3 decimals (what the viewer saves when landmarks
// are placed by clicking). BakeError(file, ...) when there is no such part,
// its pose count is not lists.size(), or the rig has channels.
std::string SetDrawnPoints(const std::string& text, const std::string& file, const std::string& part,
                           const std::string& key, const std::vector<std::vector<Eigen::Vector2d>>& lists);
// How the writers lay a description out: the text's own key order, an
// object's keys one a line, arrays without objects on one line (one
// element a line past 100 characters), indented by two.
std::string DescriptionJsonText(const std::string& text, const std::string& file);

}  // namespace posemorph::bake
