// SPDX-License-Identifier: MIT
/* What the C99 tests of the C API share: a failure counter with EXPECT,
 * and reading a file into memory. */
#ifndef POSEMORPH_C_TEST_SUPPORT_H
#define POSEMORPH_C_TEST_SUPPORT_H
#include <stdio.h>
#include <stdlib.h>

static int failures = 0;
#define EXPECT(cond)                                                     \
  do {                                                                   \
    if (!(cond)) {                                                       \
      fprintf(stderr, "%s:%d: failed: %s\n", __FILE__, __LINE__, #cond); \
      ++failures;                                                        \
    }                                                                    \
  } while (0)

static inline unsigned char* ReadFile(const char* path, long* size) {
  FILE* f = fopen(path, "rb");
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  *size = ftell(f);
  fseek(f, 0, SEEK_SET);
  unsigned char* bytes = malloc((size_t)*size);
  if (fread(bytes, 1, (size_t)*size, f) != (size_t)*size) bytes = NULL;
  fclose(f);
  return bytes;
}

#endif
