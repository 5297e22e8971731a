// SPDX-License-Identifier: MIT
#include <iostream>

#include "cli.h"

int main(int argc, char** argv) {
  return posemorph::bake::RunBakeCommand(std::vector<std::string>(argv + 1, argv + argc), std::cout, std::cerr);
}
