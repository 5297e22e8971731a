// SPDX-License-Identifier: MIT
// Writes the procedural sample rig descriptions in assets/ (run by hand when
// the generator changes; a test checks the committed files match it).
#include <fstream>
#include <iostream>

#include "gingerbread_rig.h"
#include "sample_json.h"
#include "strip_rig.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: posemorph-make-samples ASSETS_DIR\n";
    return 2;
  }
  const std::string dir = argv[1];
  const std::pair<std::string, posemorph::bake::RigDescription> samples[] = {
      {dir + "/snake/snake.json", posemorph::samples::SnakeRig()},
      {dir + "/worm-line/worm-line.json", posemorph::samples::WormLineRig()},
      {dir + "/gingerbread/gingerbread.json", posemorph::samples::GingerbreadRig()}};
  for (const auto& [path, rig] : samples) {
    std::ofstream out(path, std::ios::binary);
    out << posemorph::samples::DescriptionJson(rig);
    if (!out) {
      std::cerr << "posemorph-make-samples: cannot write " << path << "\n";
      return 1;
    }
    std::cout << "wrote " << path << "\n";
  }
  return 0;
}
