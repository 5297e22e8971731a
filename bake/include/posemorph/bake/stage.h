// SPDX-License-Identifier: MIT
// Which stage of the bake the calling thread is in ("mapping the drawings",
// "solving the pose-space weights", ...), for the failures that carry no
// context of their own: out of memory, an unexpected exception. A scope
// names its stage while it runs; when it is left by an exception, the stage
// stays named, so the handler that catches it can say where it happened.
#pragma once
#include <cstdint>

namespace posemorph::bake {

const char* CurrentBakeStage();  // "" outside any stage

// For a progress display on another thread: the stage entered or returned
// to last, on any thread ("" before the first), and how many stages have
// begun so far (a stage entered again, as a remapping does, counts again).
struct BakeProgress {
  const char* stage;
  std::uint64_t stages_begun;
};
BakeProgress LatestBakeStage();

class BakeStage {
 public:
  explicit BakeStage(const char* stage);
  ~BakeStage();
  BakeStage(const BakeStage&) = delete;
  BakeStage& operator=(const BakeStage&) = delete;

 private:
  const char* previous_;
  int exceptions_;
};

}  // namespace posemorph::bake
