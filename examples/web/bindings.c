// SPDX-License-Identifier: MIT
/* The runtime for the web: the C API (posemorph/posemorph.h) compiled to
 * WebAssembly is the whole interface; posemorph.js wraps it. This file adds
 * only what JavaScript cannot know by itself: where the fields of the C
 * structs it reads lie in wasm memory. */
#include <stddef.h>

#include "posemorph/posemorph.h"

/* Byte offsets and sizes, checked by posemorph.js when it starts. */
const size_t* pmw_layout(void) {
  static const size_t layout[] = {
      sizeof(pm_draw_list),
      offsetof(pm_draw_list, positions),
      offsetof(pm_draw_list, drawing_count),
      offsetof(pm_draw_list, drawings),
      sizeof(pm_blended_drawing),
      offsetof(pm_blended_drawing, weight),
      offsetof(pm_blended_drawing, uvs),
      offsetof(pm_draw_list, mirrored),
      sizeof(pm_rig_info),
      sizeof(pm_grid_info),
      sizeof(pm_canvas),
      sizeof(pm_draw_options),
      offsetof(pm_draw_list, colour),
      offsetof(pm_draw_options, colours),
      sizeof(pm_page),
      sizeof(pm_region),
  };
  return layout;
}
