/* SPDX-License-Identifier: MIT */
/* PM_API marks what the runtime exports when it is built as a shared
 * library (BUILD_SHARED_LIBS=ON: everything else is hidden). Static builds
 * and their users need nothing: PM_API is then empty. */
#ifndef POSEMORPH_EXPORT_H
#define POSEMORPH_EXPORT_H

#if defined(POSEMORPH_SHARED)
#if defined(_WIN32) || defined(__CYGWIN__)
#if defined(POSEMORPH_BUILDING)
#define PM_API __declspec(dllexport)
#else
#define PM_API __declspec(dllimport)
#endif
#else
#define PM_API __attribute__((visibility("default")))
#endif
#else
#define PM_API
#endif

#endif /* POSEMORPH_EXPORT_H */
