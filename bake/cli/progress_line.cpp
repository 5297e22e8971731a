// SPDX-License-Identifier: MIT
#include "progress_line.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "posemorph/bake/stage.h"

#if defined(_WIN32)
#include <io.h>
#define POSEMORPH_ISATTY(fd) _isatty(fd)
#else
#include <unistd.h>
#define POSEMORPH_ISATTY(fd) isatty(fd)
#endif

namespace posemorph::bake::cli {

bool StderrTakesProgress() {
  const char* term = std::getenv("TERM");
  return POSEMORPH_ISATTY(2) != 0 && !(term && std::strcmp(term, "dumb") == 0);
}

ProgressLine::ProgressLine(std::string tool, bool enabled, std::chrono::milliseconds delay)
    : tool_(std::move(tool)), delay_(delay), start_(std::chrono::steady_clock::now()) {
  if (enabled) thread_ = std::thread([this] { Run(); });
}

ProgressLine::~ProgressLine() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
  if (drawn_) {
    std::fputs("\r\033[K", stderr);  // the report that follows starts on a clean line
    std::fflush(stderr);
  }
}

void ProgressLine::Run() {
  std::unique_lock<std::mutex> lock(mutex_);
  if (wake_.wait_for(lock, delay_, [this] { return stop_; })) return;
  do {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const char* stage = LatestBakeStage().stage;
    std::fprintf(stderr, "\r\033[K%s: %s ... %.1f s", tool_.c_str(), *stage ? stage : "starting", seconds);
    std::fflush(stderr);
    drawn_ = true;
  } while (!wake_.wait_for(lock, std::chrono::milliseconds(100), [this] { return stop_; }));
}

}  // namespace posemorph::bake::cli
