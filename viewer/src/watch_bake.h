// SPDX-License-Identifier: MIT
// posemorph-view --watch RIG.json: the description baked in memory, then
// watched: when it or a file it names (drawings, images) changes on disk, a
// thread of its own bakes it again, and the window swaps the new rig in
// (window.cpp); a bake that fails leaves the shown rig as it is and says
// why. Implemented by watch_bake.cpp, which links the bake (the edit-mode
// component); a viewer built without it refuses --watch.
#pragma once
#include <memory>
#include <string>

#include "drawings.h"
#include "posemorph/rig.h"

namespace posemorph::viewer {

// A rig baked in memory, with its drawings (from the description's folder)
// and one line saying what was baked.
struct BakedRig {
  Rig rig;
  Drawings drawings;
  std::string summary;
};

class WatchedBake {
 public:
  virtual ~WatchedBake() = default;  // stops watching (waits for a bake under way)
  enum class Result { kNone, kBaked, kFailed };
  // A bake finished since the last call: kBaked with the rig in *rig, or
  // kFailed with the bake's message; kNone while nothing has.
  virtual Result Take(std::unique_ptr<BakedRig>* rig, std::string* message) = 0;
  // What is under way, for the panel: "baking RIG.json: STAGE, 2.4 s", or
  // "" while it only watches.
  virtual std::string Progress() const = 0;
};

// Bakes `description` now, on this thread (saying so on stderr), into *first, then watches it (four times a second) on
// a thread of its own. nullptr, with the message in *problem, when the first bake fails or this viewer is built without
// the bake.
std::unique_ptr<WatchedBake> WatchDescription(const std::string& description, std::unique_ptr<BakedRig>* first,
                                              std::string* problem);

}  // namespace posemorph::viewer
