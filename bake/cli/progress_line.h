// SPDX-License-Identifier: MIT
// The progress line of a long command on a terminal: the bake's stage
// (posemorph/bake/stage.h) and the seconds so far, redrawn in place on
// stderr while the command runs, erased when it ends. Nothing is drawn for a
// command that ends within the delay, when stderr is not a terminal, when
// TERM is "dumb", or when the caller says so (--quiet).
#pragma once
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace posemorph::bake::cli {

// Whether a progress line may be drawn on stderr: a terminal, TERM not "dumb".
bool StderrTakesProgress();

class ProgressLine {
 public:
  // `tool` prefixes the line ("posemorph-bake"); drawn only when `enabled`,
  // from `delay` after construction, every 100 ms.
  ProgressLine(std::string tool, bool enabled, std::chrono::milliseconds delay = std::chrono::milliseconds(1000));
  ~ProgressLine();  // stops the drawing and erases the line, if one was drawn
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

 private:
  void Run();

  std::string tool_;
  std::chrono::milliseconds delay_;
  std::chrono::steady_clock::time_point start_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  bool drawn_ = false;
  std::thread thread_;
};

}  // namespace posemorph::bake::cli
