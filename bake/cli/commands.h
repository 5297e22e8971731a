// SPDX-License-Identifier: MIT
// posemorph-bake's commands, one file each (NAME_command.cpp). Each takes the
// whole argument list and where its own arguments start, writes its report
// to `out`, and returns the exit status; it throws UsageError (status 2) or
// BakeError (status 1), which RunBakeCommand (cli.cpp) prints.
#pragma once
#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

namespace posemorph::bake::cli {

using Arguments = std::vector<std::string>;

int BakeCommand(const Arguments& a, std::size_t from, std::ostream& out, std::ostream& err);
int InfoCommand(const Arguments& a, std::size_t from, std::ostream& out);
int EvalCommand(const Arguments& a, std::size_t from, std::ostream& out);
int SheetCommand(const Arguments& a, std::size_t from, std::ostream& out);
int DeformCommand(const Arguments& a, std::size_t from, std::ostream& out);
int InitCommand(const Arguments& a, std::size_t from, std::ostream& out, std::ostream& err);
int ImportCommand(const Arguments& a, std::size_t from, std::ostream& out, std::ostream& err);
int OutlineCommand(const Arguments& a, std::size_t from, std::ostream& out, std::ostream& err);

}  // namespace posemorph::bake::cli
