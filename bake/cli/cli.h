// SPDX-License-Identifier: MIT
// posemorph-bake's commands, callable in-process (the tests do) or from main.
#pragma once
#include <ostream>
#include <string>
#include <vector>

namespace posemorph::bake {

// args excludes the program name. Returns the process exit status.
int RunBakeCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace posemorph::bake
