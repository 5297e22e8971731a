// SPDX-License-Identifier: MIT
// Errors the runtime reports. The runtime never throws across its API: every
// fallible call returns false and fills an Error.
#pragma once
#include "posemorph/export.h"

namespace posemorph {

enum class ErrorCode : int {
  kOk = 0,
  kInvalidArgument = 1,  // a job's inputs do not fit its rig (sizes, null spans)
  kTruncated = 2,        // fewer bytes than the header or a section says
  kBadMagic = 3,         // not a posemorph rig
  kBadVersion = 4,       // a format version this runtime cannot read
  kBadChecksum = 5,      // bytes changed after the bake wrote them
  kBadLayout = 6,        // section table: overlap, misalignment, missing or duplicate section
  kBadValue = 7,         // non-finite number, out-of-range index, inconsistent count
  kTooLarge = 8,         // counts above the runtime's limits
  kOutOfMemory = 9,      // the one arena allocation at load failed
  kUnsupportedIsa = 10,  // the requested kernel path is not in this build or not run by this CPU
};

struct Error {
  ErrorCode code = ErrorCode::kOk;
  char message[256] = {0};
};

PM_API const char* ErrorCodeName(ErrorCode code);

}  // namespace posemorph
