// SPDX-License-Identifier: MIT
#include "posemorph/bake/stage.h"

#include <atomic>
#include <exception>

namespace posemorph::bake {
namespace {
thread_local const char* current_stage = "";
std::atomic<const char*> latest_stage{""};
std::atomic<std::uint64_t> stages_begun{0};
}  // namespace

const char* CurrentBakeStage() { return current_stage; }

BakeProgress LatestBakeStage() { return {latest_stage.load(), stages_begun.load()}; }

BakeStage::BakeStage(const char* stage) : previous_(current_stage), exceptions_(std::uncaught_exceptions()) {
  current_stage = stage;
  latest_stage.store(stage);
  stages_begun.fetch_add(1);
}

BakeStage::~BakeStage() {
  // Left normally: the enclosing stage again. Left by an exception: keep
  // naming this one for whoever catches it.
  if (std::uncaught_exceptions() == exceptions_) {
    current_stage = previous_;
    latest_stage.store(previous_);
  }
}

}  // namespace posemorph::bake
