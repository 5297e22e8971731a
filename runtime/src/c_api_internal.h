// SPDX-License-Identifier: MIT
// What the C API's files share (c_api.cpp: loading and what a rig holds;
// c_api_frames.cpp: weights, morphs, paths, quantised points, draw lists;
// c_api_channels.cpp: control channels and attachments; c_api_animator.cpp:
// the animator; c_api_machine.cpp: the state machine; c_api_character.cpp:
// the whole character): the handle and the
// helpers that check the caller's buffers and fill the error.
#pragma once
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "posemorph/posemorph.h"
#include "posemorph/rig.h"

struct pm_rig {
  posemorph::Rig rig;
  bool in_place = false;  // the handle and the rig's arrays live in the caller's memory
};

namespace posemorph::c_api {

// An in-place handle sits at the start of the caller's memory, the rig's
// arrays after it.
constexpr std::size_t kHandleBytes = (sizeof(pm_rig) + posemorph::kRigMemoryAlignment - 1) /
                                     posemorph::kRigMemoryAlignment * posemorph::kRigMemoryAlignment;
static_assert(PM_RIG_MEMORY_ALIGNMENT == posemorph::kRigMemoryAlignment, "published alignment");

template <typename T>
bool Aligned(const T* p) {
  return reinterpret_cast<std::uintptr_t>(p) % alignof(T) == 0;
}

inline int CopyString(posemorph::StringView v, bool valid, char* out, size_t capacity, size_t* length) {
  if (!valid) return PM_ERROR_INVALID_ARGUMENT;
  if (length) *length = v.size;
  if (!out || capacity < v.size + 1) return PM_ERROR_BUFFER_TOO_SMALL;
  if (v.size) std::memcpy(out, v.data, v.size);
  out[v.size] = 0;
  return PM_OK;
}

inline int Fail(pm_error* err, int code, const char* message) {
  if (err) {
    err->code = code;
    std::snprintf(err->message, sizeof(err->message), "%s", message);
  }
  return code;
}

// The output handle of a load: given, and not holding a rig (which the load
// would leak).
inline int CheckOutput(pm_rig** out_rig, pm_error* err) {
  if (!out_rig) return Fail(err, PM_ERROR_INVALID_ARGUMENT, "no output pointer given");
  if (*out_rig)
    return Fail(err, PM_ERROR_INVALID_ARGUMENT,
                "*out_rig is not NULL: free the rig it holds first (pm_rig_free), then set it to NULL");
  return PM_OK;
}

inline int Report(pm_error* err, const posemorph::Error& e) {
  if (err) {
    err->code = int(e.code);
    std::memcpy(err->message, e.message, sizeof(err->message));
  }
  return int(e.code);
}

}  // namespace posemorph::c_api
