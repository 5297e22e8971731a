// SPDX-License-Identifier: MIT
// Reading the bake's inputs within limits: only regular files (not a
// directory, device or pipe, which could be endless or block), and at most a
// documented size, so that time and memory stay bounded on any input.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "posemorph/bake/error.h"

namespace posemorph::bake {

constexpr std::uint64_t kMaxTextFileBytes = std::uint64_t(64) << 20;  // descriptions, mesh files, SVG drawings
constexpr std::uint64_t kMaxRigFileBytes = std::uint64_t(256) << 20;  // baked rigs read by info, eval, sheet
constexpr std::uint64_t kMaxDrawingPixels = std::uint64_t(1) << 24;   // PNG drawings: 4096 x 4096

// The whole file, or BakeError(path, ...) naming why not: it cannot be
// opened, is not a regular file, or is larger than `limit` bytes (`what`
// names the kind of file in that message; `referenced_from`, when given,
// the file that named it).
std::vector<unsigned char> ReadInputFile(const std::string& path, std::uint64_t limit, const std::string& what,
                                         const std::string& referenced_from = "");
// The same, its errors named by `source` (ErrorSource::Error) instead of the
// path alone: a drawing's, "DESCRIPTION: POSE: DRAWING: problem".
std::vector<unsigned char> ReadInputFile(const std::string& path, std::uint64_t limit, const std::string& what,
                                         const ErrorSource& source);

// Refuses (BakeError) an output path that names an input, an existing
// directory, or an existing file that is not a regular file (a device, a
// pipe, or a symbolic link, which a rename would replace), and a name that
// cannot be written (OutputNameProblem: empty, or too long): before any
// work is done.
void CheckOutputPath(const std::string& output, const std::vector<std::string>& inputs);

}  // namespace posemorph::bake
