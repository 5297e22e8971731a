// SPDX-License-Identifier: MIT
#include "posemorph/bake/output_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "posemorph/bake/error.h"

namespace posemorph::bake {

void WriteFileAtomic(const std::string& path, const std::vector<unsigned char>& bytes) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw BakeError(path, "cannot write: folder " + dir.string() + " does not exist");
  // A unique temporary beside the target: rename is atomic only within one file system.
  std::string tmp = (dir / ("." + target.filename().string() + ".XXXXXX")).string();
  const int fd = mkstemp(tmp.data());
  if (fd < 0) throw BakeError(path, "cannot create a temporary file in " + dir.string());
  bool ok = ::fchmod(fd, 0644) == 0;
  std::size_t written = 0;
  while (ok && written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n <= 0)
      ok = false;
    else
      written += std::size_t(n);
  }
  ok = ok && ::fsync(fd) == 0;
  ok = (::close(fd) == 0) && ok;
  ok = ok && std::rename(tmp.c_str(), path.c_str()) == 0;
  if (!ok) {
    std::remove(tmp.c_str());
    throw BakeError(path, "cannot write the file");
  }
}

}  // namespace posemorph::bake
