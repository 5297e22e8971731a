// SPDX-License-Identifier: MIT
// Independent pieces of the bake's work shared out over the machine's cores:
// the refinement's runs (compatible_refinement.cpp), the tracing of each
// drawn pose (map_drawings.cpp), the atlas's decoding of its drawings
// (texture_atlas.cpp) and PNG encoding of its pages (posemorph-bake), the
// runs of frames the bake evaluates (pose_space_samples.h).
#pragma once
#include <cstddef>
#include <functional>

namespace posemorph::bake {

// Runs task(0) ... task(n - 1) on this thread and more, `threads` in all (0:
// as many as the machine has cores; never more than n), each taking the next
// task left. The tasks must not share what they write: then the outcome is
// the same bits however they are shared out. When tasks throw, the
// exception of the first of them by index is thrown, after all have ended.
// Where no thread can be started, this thread runs them all.
void RunEach(std::size_t n, unsigned threads, const std::function<void(std::size_t)>& task);

}  // namespace posemorph::bake
