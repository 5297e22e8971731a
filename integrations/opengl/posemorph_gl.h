// SPDX-License-Identifier: MIT
// posemorph's OpenGL renderer: everything a game on OpenGL 3.3 (or OpenGL
// ES 3.0) needs to draw posemorph characters from a DrawListJob -- the
// texture pages of every list (the body and each attachment: Rig::page, the
// atlas the bake packed the drawings into, or for an older rig each
// drawing) in one texture array (one for the whole character when its lists
// share an atlas), every pose's uvs mapped onto the pages
// (Rig::part_region), the triangles, the characters' positions, and the
// program that cross-fades up to 8 drawings in premultiplied alpha, as
// posemorph-view does. It splits each list's vertices per part (a glued
// joint's vertex, which two parts share, gets one per part: its drawings
// lie in two regions) and orders the triangles by each draw sequence, so
// the steps of CharacterDrawSteps that follow each other in one list draw
// in one call: a rig without parts draws a character in one call, Pell
// with a face in four (its body, then each face part's list), where one
// call per step took seven; with an atlas it binds one texture a frame.
//
//   posemorph::gl::Renderer renderer;
//   renderer.Init(rig, ReadMyPng, {}, &error);      // once, with a current GL context
//   job.Run();                                       // each frame: a DrawListJob with attached_output
//   renderer.Draw(job, posemorph::gl::View(...));    // every character of the job, back to front
//
// The caller owns the context, the window and the image decoding (a
// callback hands over each page as premultiplied RGBA8). The renderer
// sets the blend to premultiplied "over" (ONE, ONE_MINUS_SRC_ALPHA) and
// leaves program, vertex array and texture bindings changed.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "posemorph/draw_list.h"
#include "posemorph/rig.h"

namespace posemorph::gl {

// A drawing as the renderer wants it: width x height RGBA8, premultiplied,
// rows top to bottom.
struct Pixels {
  std::uint32_t width = 0, height = 0;
  std::vector<unsigned char> rgba;
  std::string source;  // where it was read from (a path), for messages; the name when empty
};
// Reads texture page `page` (Rig::page: page.atlas, an atlas page, its
// name relative to the rig file's folder, premultiplied already; else a
// drawing as the bake named it, relative to the drawing folder, straight
// alpha) into *out, premultiplied; false with *error naming the file and
// the problem.
using ImageReader = std::function<bool(const TexturePage& page, Pixels* out, std::string* error)>;

struct Settings {
  bool es = false;              // OpenGL ES 3.0 shaders (#version 300 es) instead of OpenGL 3.3 core
  int filter = -1;              // -1: each rig's hint (Rig::texture_filter); 0 linear; 1 nearest
  bool clamp_to_border = true;  // outside a drawing: nothing (ES 3.0 has no border: edge clamping there)
};

// World (the characters' transforms' target) to clip space: clip = scale x world + offset.
struct View {
  float scale_x = 1, scale_y = 1, offset_x = 0, offset_y = 0;
  // A window of width x height pixels showing the world box centred at (cx, cy), zoom pixels per unit, y up.
  static View Fit(double width, double height, double cx, double cy, double zoom) {
    View v;
    v.scale_x = float(2 * zoom / width), v.scale_y = float(2 * zoom / height);
    v.offset_x = float(-cx * 2 * zoom / width), v.offset_y = float(-cy * 2 * zoom / height);
    return v;
  }
};

class Renderer {
 public:
  Renderer() = default;
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Uploads `rig`'s texture pages (every list's), uvs and triangles and
  // builds the program; the rig must outlive the renderer. False with
  // *error (naming the page and the problem) when a page cannot be read or
  // is not the size the rig says, or the rig was not baked from drawings.
  bool Init(const Rig& rig, const ImageReader& read, const Settings& settings, std::string* error);
  // Draws every character of `job` (which ran on this renderer's rig; its
  // attachments too when it has attached_output) back to front.
  void Draw(const DrawListJob& job, const View& view);
  // Draw calls the last Draw made (one per step), and the textures it bound.
  std::uint32_t draw_calls() const { return draw_calls_; }
  std::uint32_t texture_binds() const { return texture_binds_; }

 private:
  struct List;  // one list's GPU objects (posemorph_gl.cpp)
  // List `r`'s vertices split per part, their page uvs per pose, their parts
  // and its triangles in each draw sequence's order, into `gpu` (its vertex array bound).
  static void BuildGeometry(const Rig& r, List* gpu);
  const Rig* rig_ = nullptr;
  std::vector<List*> lists_;
  unsigned program_ = 0;
  int weights_at_ = -1, linear_at_ = -1, translation_at_ = -1, tints_at_ = -1, view_at_ = -1;
  std::uint32_t draw_calls_ = 0, texture_binds_ = 0;
};

}  // namespace posemorph::gl
