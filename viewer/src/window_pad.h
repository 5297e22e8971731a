// SPDX-License-Identifier: MIT
// The window's pose pad: a pad per control channel (its weight field
// coloured by the dominant pose, the pose points, the point dragged), the
// gesture recorded from the first pad and played back, and the rig's stored
// paths played. It turns the scene the user set into the scene a frame
// shows (Shown).
#pragma once
#include <array>
#include <string>
#include <vector>

#include "scene.h"
#include "window_common.h"

namespace posemorph::viewer::window_impl {

struct Gesture {
  std::vector<std::array<double, 3>> keys;  // t, x, y
  bool recording = false, playing = false;
  double start = 0;
};

class PosePad {
 public:
  // The pads' weight fields, and a point for each later channel the scene
  // does not set (its first pose's).
  void Build(const Rig& rig, Scene* scene);
  // The panel's pads, gesture and stored-path controls; dragging a pad moves
  // the scene's point. `clock` restarts when a stored path starts playing.
  // True when the gesture's Save button was pressed.
  bool Ui(const Rig& rig, Scene* scene, double* clock);
  // The scene as the frame at `clock` shows it: along the playing path or
  // gesture (the pad's point moving with it, in `scene`).
  Scene Shown(const Rig& rig, Scene* scene, double clock);

  Gesture& gesture() { return gesture_; }
  // A pose point of the first pad dragged to a new place and let go (with
  // "move pose points" on): which pose and where; false when none was.
  struct PoseMove {
    std::uint32_t pose;
    double x, y;
  };
  bool TakeMove(PoseMove* move);
  // The smoke test's way to drag one.
  void MovePose(std::uint32_t pose, double x, double y) { moved_ = PoseMove{pose, x, y}, has_move_ = true; }

 private:
  // One channel's pad: its weight field as colours over its domain.
  struct Field {
    std::vector<ImU32> colours;
    double x0 = 0, y0 = 0, span = 1;
  };
  Field FieldOf(const Rig& rig) const;
  // Draws a pad of `rig`'s pose space with the point (x, y) and, if given,
  // the gesture's trail; true while it is dragged (then (x, y) follows the mouse).
  // With `movable`, and "move pose points" on, a press on a pose point
  // drags it instead (shown where the mouse is; PoseMove when let go).
  bool Draw(const Rig& rig, const Field& field, const char* id, const Gesture* trail, double* x, double* y,
            bool movable = false);

  static constexpr int kCells = 48;  // the weight field's cells across a pad
  Field body_;
  std::vector<Field> channels_;     // channels 1 .. C-1 (index c - 1)
  std::vector<char> play_channel_;  // channel c - 1 follows its first path
  Gesture gesture_;
  bool play_path_ = false;
  int path_index_ = 0;
  bool move_points_ = false;  // the panel's "move pose points"
  int moving_ = -1;           // the pose point being dragged
  double moving_x_ = 0, moving_y_ = 0;
  PoseMove moved_{0, 0, 0};
  bool has_move_ = false;
};

}  // namespace posemorph::viewer::window_impl
