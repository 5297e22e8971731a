// SPDX-License-Identifier: MIT
#include "posemorph/bake/stage.h"

#include <exception>

namespace posemorph::bake {
namespace {
thread_local const char* current_stage = "";
}  // namespace

const char* CurrentBakeStage() { return current_stage; }

BakeStage::BakeStage(const char* stage) : previous_(current_stage), exceptions_(std::uncaught_exceptions()) {
  current_stage = stage;
}

BakeStage::~BakeStage() {
  // Left normally: the enclosing stage again. Left by an exception: keep
  // naming this one for whoever catches it.
  if (std::uncaught_exceptions() == exceptions_) current_stage = previous_;
}

}  // namespace posemorph::bake
