// SPDX-License-Identifier: MIT
// Bad input to posemorph-bake, as its tests drive it: a scratch folder, a
// small valid description, the CLI run in-process, and the check that a
// failure is one line naming the file and the problem with nothing
// written.
#pragma once
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli.h"
#include "test_support.h"

namespace posemorph::test {

namespace fs = std::filesystem;
using nlohmann::json;

struct TempDir {
  fs::path path;
  TempDir() {
    path =
        fs::temp_directory_path() / ("posemorph-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
  static inline int counter = 0;
};

inline json ValidDescription() {
  return json::parse(R"({
    "posemorph": 1,
    "triangles": [[0, 1, 2], [0, 2, 3]],
    "poses": [
      {"name": "a", "point": [0, 0], "vertices": [[0, 0], [1, 0], [1, 1], [0, 1]]},
      {"name": "b", "point": [1, 0], "vertices": [[0, 0], [1, 0.2], [0.9, 1.1], [-0.1, 0.9]]}
    ],
    "bake": {"grid_resolution": 8}
  })");
}

struct Result {
  int status;
  std::string out, err;
};

inline Result Run(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  const int status = posemorph::bake::RunBakeCommand(args, out, err);
  return {status, out.str(), err.str()};
}

inline void Write(const fs::path& p, const std::string& text) {
  std::ofstream f(p, std::ios::binary);
  f << text;
}

// Bakes `text` (written to rig.json) over an existing output and checks the
// failure: status, message mentioning `file_part` and `problem`, output intact,
// nothing else left in the folder.
inline void ExpectFailure(const std::string& text, const std::string& problem,
                          const std::string& file_part = "rig.json",
                          const std::function<void(const fs::path&)>& extra = nullptr) {
  TempDir dir;
  const fs::path input = dir.path / "rig.json", output = dir.path / "out.pmrig";
  Write(input, text);
  if (extra) extra(dir.path);
  Write(output, "previous");
  std::size_t files_before = std::distance(fs::directory_iterator(dir.path), fs::directory_iterator());
  const Result r = Run({input.string(), "-o", output.string()});
  CAPTURE(r.err);
  CHECK(r.status != 0);
  CHECK(r.err.find(file_part) != std::string::npos);
  CHECK(r.err.find(problem) != std::string::npos);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);  // one message, one line
  std::ifstream f(output, std::ios::binary);
  std::string content((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  CHECK(content == "previous");
  CHECK(std::size_t(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator())) == files_before);

  // And without an existing output: none appears.
  fs::remove(output);
  CHECK(Run({input.string(), "-o", output.string()}).status != 0);
  CHECK_FALSE(fs::exists(output));
}

}  // namespace posemorph::test
