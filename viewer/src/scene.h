// SPDX-License-Identifier: MIT
// What a frame shows: one character at a pose-space point (or a path time)
// placed by a transform, or a crowd on a ground line walking a path at
// staggered phases. Used by the headless capture, the window and the frame
// tests alike. Every character goes through the runtime's DrawListJob.
#pragma once
#include <string>
#include <vector>

#include "rig_renderer.h"

namespace posemorph::viewer {

class MachineDriver;

// A control channel after the first (format 1.7): its point, or a path of
// its own rig that its characters follow (at the scene's time and phases).
struct ChannelInput {
  double x = 0, y = 0;
  std::string path;
};

struct Scene {
  double x = 0, y = 0;  // pose-space point (when path is empty)
  std::string path;     // a path of the rig: characters follow it
  double time = 0;      // seconds along the path
  double sigma = -1;    // texture sharpening; < 0: the rig's default
  bool limit_weights = true;
  bool linear = false;      // linear vertex blending instead of rigid (the paper's comparison)
  std::uint32_t crowd = 1;  // characters: > 1 lays them out on a ground line (see CrowdLayout)
  std::uint32_t seed = 1;   // the crowd layout's random positions, sizes and facings
  Transform2D transform;    // a single character's place in the world
  std::uint32_t max_drawings = kDrawingsPerCharacter;  // K drawings blended per character
  bool wireframe = false;
  bool compare_linear = false;        // two characters: rigid (left) and linear (right) at the same point
  bool show_bases = false;            // the N base poses in a row, each exactly at its point
  int filter = -1;                    // drawings sampled: 0 linear, 1 nearest, -1 as the rig asks (its "filter")
  std::uint64_t hidden_parts = 0;     // a layered character's parts not drawn: bit p hides part p
  Colour colour;                      // every character's tint and opacity (DrawListJob::colours)
  std::vector<float> part_opacities;  // by part index, rig.part_count() of them, or empty: all 1
  // Channels 1 .. C-1 of a rig with control channels, in order; a missing
  // entry puts its channel at its first pose's point.
  std::vector<ChannelInput> channels;
  // A rig's state machine drives the characters (--inputs, the window's
  // panel): their weights are its animators' (x, y, path and channels are
  // not read); as many characters as it runs, and neither bases nor the
  // rigid | linear comparison.
  const MachineDriver* machine = nullptr;
};

// How many characters the scene draws.
std::uint32_t SceneCharacters(const Rig& rig, const Scene& scene);
// How the drawings are sampled: --filter, else the rig's hint.
TextureFilter SceneFilter(const Rig& rig, const Scene& scene);

// The CPU buffers a scene's evaluation reuses from frame to frame.
struct SceneScratch {
  std::vector<double> points, workspace;
  std::vector<Transform2D> transforms;
  std::vector<double> phases;  // crowd: each drawn character's share of the path
  std::vector<DrawList> lists;
  std::vector<Colour> colours;        // the scene's colour, once per character
  std::vector<float> part_opacities;  // the scene's part opacities, once per character
  // A character with channels: the later channels' points, the
  // attachments' positions and lists (DrawListJob's).
  std::vector<double> channel_points;
  std::vector<float> attached_positions;
  std::vector<DrawList> attachment_lists;
};

// Where a frame's characters are, in world units: a camera fits one of them.
struct SceneBounds {
  View all;    // every character (fit to crowd)
  View first;  // the first character, or the single one (fit to character)
};

// A crowd of `count` on a ground line, random (seeded: the same on every
// platform) positions, sizes and facings, sorted back to front (the draw
// order). Characters farther back stand higher and smaller. phase[k] in
// [0, 1) is drawn character k's offset along the path.
void CrowdLayout(const Rig& rig, std::uint32_t count, std::uint32_t seed, Transform2D* transforms, double* phases);

// Evaluates the characters of a scene with the runtime's DrawListJob into
// the renderer's buffers (positions and instances, in draw order) and
// returns where they are. False with a message for an unknown path or more
// characters than the renderer holds.
bool PrepareScene(const Rig& rig, const Scene& scene, RigRenderer& renderer, SceneScratch& scratch, SceneBounds* bounds,
                  std::uint32_t* count, std::string* error);

// The rectangle of rig space that holds every pose of one character (with a 6% margin).
View CharacterBounds(const Rig& rig);
// The world rectangle holding `rect` after a transform.
View TransformBounds(const Transform2D& t, const View& rect);

}  // namespace posemorph::viewer
