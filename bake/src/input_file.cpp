// SPDX-License-Identifier: MIT
#include "posemorph/bake/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "posemorph/bake/error.h"
#include "posemorph/bake/output_file.h"

namespace posemorph::bake {

namespace {

std::vector<unsigned char> ReadBounded(const std::string& path, std::uint64_t limit, const std::string& what,
                                       const ErrorSource& source, const std::string& named) {
  // Non-blocking, so that opening a pipe returns at once and is refused below.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw source.Error("cannot open file" + named);
  struct stat st;
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw source.Error("is not a regular file (a directory, device or pipe)" + named);
  }
  std::FILE* f = ::fdopen(fd, "rb");
  if (!f) {
    ::close(fd);
    throw source.Error("cannot open file" + named);
  }
  if (std::uint64_t(st.st_size) > limit) {
    std::fclose(f);
    throw source.Error("is " + std::to_string(st.st_size) + " bytes, more than the limit of " + std::to_string(limit) +
                       " for " + what + named);
  }
  std::vector<unsigned char> bytes(std::size_t(st.st_size));
  const std::size_t got = bytes.empty() ? 0 : std::fread(bytes.data(), 1, bytes.size(), f);
  const bool more = std::fgetc(f) != EOF;  // grew while we read: still bounded by the limit check above
  std::fclose(f);
  if (got != bytes.size() || more) throw source.Error("changed size while being read" + named);
  return bytes;
}

}  // namespace

std::vector<unsigned char> ReadInputFile(const std::string& path, std::uint64_t limit, const std::string& what,
                                         const std::string& referenced_from) {
  return ReadBounded(path, limit, what, ErrorSource(path),
                     referenced_from.empty() ? "" : " (named in " + referenced_from + ")");
}

std::vector<unsigned char> ReadInputFile(const std::string& path, std::uint64_t limit, const std::string& what,
                                         const ErrorSource& source) {
  return ReadBounded(path, limit, what, source, "");
}

void CheckOutputPath(const std::string& output, const std::vector<std::string>& inputs) {
  namespace fs = std::filesystem;
  if (const std::optional<std::string> problem = OutputNameProblem(output))
    throw BakeError(ShownPath(output), "cannot write: " + *problem);
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(output, ec);
  if (ec || !fs::exists(status)) return;  // a new file
  if (fs::is_directory(status)) throw BakeError(output, "is a directory; give a file name to write");
  if (!fs::is_regular_file(status))
    throw BakeError(output, "exists and is not a regular file (a device, pipe or link); refusing to replace it");
  for (const std::string& in : inputs)
    if (fs::equivalent(output, in, ec)) throw BakeError(output, "is the input " + in + "; refusing to overwrite it");
}

}  // namespace posemorph::bake
