// SPDX-License-Identifier: MIT
#include "posemorph/bake/output_file.h"

#include <pthread.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <system_error>

#include "posemorph/bake/error.h"

namespace posemorph::bake {
namespace {

constexpr std::size_t kMaxFileName = 255;  // bytes of one name in a folder (NAME_MAX on Linux and macOS)

// SIGXFSZ held for this thread while it writes: a write past the file-size
// limit then fails with EFBIG (its default action would end the process and
// leave the temporary behind), and the pending signal is taken back after.
class FileSizeSignalHeld {
 public:
  FileSizeSignalHeld() {
    sigemptyset(&signal_);
    sigaddset(&signal_, SIGXFSZ);
    held_ = pthread_sigmask(SIG_BLOCK, &signal_, &before_) == 0 && !sigismember(&before_, SIGXFSZ);
  }
  ~FileSizeSignalHeld() {
    if (!held_) return;
    const timespec now{0, 0};
    while (sigtimedwait(&signal_, nullptr, &now) == SIGXFSZ) {
    }
    pthread_sigmask(SIG_SETMASK, &before_, nullptr);
  }
  FileSizeSignalHeld(const FileSizeSignalHeld&) = delete;
  FileSizeSignalHeld& operator=(const FileSizeSignalHeld&) = delete;

 private:
  sigset_t signal_, before_;
  bool held_ = false;
};

}  // namespace

std::string ShownPath(const std::string& path) {
  return path.size() <= 80 ? path : path.substr(0, 60) + "... (" + std::to_string(path.size()) + " bytes)";
}

std::optional<std::string> OutputNameProblem(const std::string& path) {
  if (path.empty()) return std::string("the output file name is empty");
  const std::string name = std::filesystem::path(path).filename().string();
  if (name.empty()) return "names a folder (" + ShownPath(path) + "), not a file";
  if (name.size() > kMaxFileName)
    return "the file name is " + std::to_string(name.size()) + " bytes long; a file system allows " +
           std::to_string(kMaxFileName);
  return std::nullopt;
}

void WriteFileAtomic(const std::string& path, const std::vector<unsigned char>& bytes) {
  namespace fs = std::filesystem;
  if (const std::optional<std::string> problem = OutputNameProblem(path))
    throw BakeError(ShownPath(path), "cannot write: " + *problem);
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw BakeError(path, "cannot write: folder " + dir.string() + " does not exist");
  // A unique temporary beside the target (rename is atomic only within one
  // file system), its name short enough for any target's.
  const std::string stem = target.filename().string().substr(0, kMaxFileName - 16);
  std::string tmp = (dir / ("." + stem + ".XXXXXX")).string();
  const FileSizeSignalHeld held;
  const int fd = mkstemp(tmp.data());
  if (fd < 0) {
    const int cause = errno;
    throw BakeError(path, "cannot create a temporary file in " + dir.string() + ": " + std::strerror(cause));
  }
  int cause = 0;
  const char* step = "write the file";
  if (::fchmod(fd, 0644) != 0) cause = errno, step = "set the file's permissions";
  std::size_t written = 0;
  while (cause == 0 && written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      cause = n < 0 ? errno : EIO;
    else
      written += std::size_t(n);
  }
  if (cause == 0 && ::fsync(fd) != 0) cause = errno;
  if (::close(fd) != 0 && cause == 0) cause = errno;
  if (cause == 0 && std::rename(tmp.c_str(), path.c_str()) != 0) cause = errno, step = "replace the file";
  if (cause != 0) {
    std::remove(tmp.c_str());
    throw BakeError(ShownPath(path), std::string("cannot ") + step + ": " + std::strerror(cause));
  }
}

}  // namespace posemorph::bake
