// SPDX-License-Identifier: MIT
// Filling an Error while loading: the loader and the compact decoder report
// through this one helper.
#pragma once
#include <cstdarg>
#include <cstdio>

#include "posemorph/error.h"

namespace posemorph::detail {

// Sets err's code and printf-formatted message (when err is given); false.
inline bool LoadFail(Error* err, ErrorCode code, const char* format, ...) {
  if (err) {
    err->code = code;
    va_list args;
    va_start(args, format);
    std::vsnprintf(err->message, sizeof(err->message), format, args);
    va_end(args);
  }
  return false;
}

}  // namespace posemorph::detail
