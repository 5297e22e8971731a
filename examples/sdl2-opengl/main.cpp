// SPDX-License-Identifier: MIT
// posemorph in an SDL2 + OpenGL 3.3 game: one character follows the mouse
// through pose space, or a crowd walks one of the rig's paths. The runtime
// hands over the draw lists of every character (the body and its
// attachments); integrations/opengl (posemorph_gl.h) draws them. What is
// left here is the game's own: the window, the PNG decoding, where the
// characters stand and which pose-space points they take.
//
//   sdl2_opengl RIG.pmrig --images DIR [--crowd K] [--filter nearest|linear]
//               [--size WxH] [--at X,Y] [--tint R,G,B,A] [--frames N --screenshot OUT.png]
#define GL_GLEXT_PROTOTYPES 1
#include <SDL.h>
#include <SDL_opengl.h>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "posemorph/draw_list.h"
#include "posemorph/image_reference.h"
#include "posemorph/path.h"
#include "posemorph_gl.h"

using namespace posemorph;

namespace {

int Fail(const std::string& message) {
  std::fprintf(stderr, "sdl2_opengl: %s\n", message.c_str());
  return 1;
}

// A texture page as premultiplied RGBA8, the way the cross-fade wants it
// (the renderer's ImageReader): an atlas page is premultiplied already.
bool ReadPage(const std::string& path, bool premultiplied, gl::Pixels* out, std::string* error) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  out->source = path;
  if (!png_image_begin_read_from_file(&image, path.c_str())) return *error = path + ": cannot read the PNG", false;
  image.format = PNG_FORMAT_RGBA;
  out->width = image.width, out->height = image.height;
  out->rgba.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, out->rgba.data(), 0, nullptr)) return *error = path + ": bad PNG", false;
  std::vector<unsigned char>& p = out->rgba;
  for (std::size_t i = 0; i < p.size() && !premultiplied; i += 4)
    for (int c = 0; c < 3; ++c) p[i + c] = (unsigned char)((p[i + c] * p[i + 3] + 127) / 255);
  return true;
}

struct Options {
  std::string rig_path, images, screenshot, filter;  // filter: empty = as the rig asks
  int crowd = 1, frames = 0, width = 640, height = 640;
  double at_x = NAN, at_y = NAN;
  Colour tint;  // every character's (DrawListJob::colours)
};

// The command line; what is wrong with it, or "".
std::string ParseOptions(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const char* v = i + 1 < argc ? argv[i + 1] : nullptr;
    if (a[0] != '-')
      o.rig_path = a;
    else if (!v)
      return "usage: sdl2_opengl RIG.pmrig --images DIR [--crowd K] [--filter nearest|linear] "
             "[--size WxH] [--at X,Y] [--tint R,G,B,A] [--frames N --screenshot OUT.png]";
    else if (a == "--images")
      o.images = v, ++i;
    else if (a == "--crowd")
      o.crowd = std::clamp(std::atoi(v), 1, 10000), ++i;
    else if (a == "--frames")
      o.frames = std::max(0, std::atoi(v)), ++i;
    else if (a == "--screenshot")
      o.screenshot = v, ++i;
    else if (a == "--filter")
      o.filter = v, ++i;
    else if (a == "--size" && std::sscanf(v, "%dx%d", &o.width, &o.height) == 2)
      ++i;
    else if (a == "--at" && std::sscanf(v, "%lf,%lf", &o.at_x, &o.at_y) == 2)
      ++i;
    else if (a == "--tint" && std::sscanf(v, "%f,%f,%f,%f", &o.tint.r, &o.tint.g, &o.tint.b, &o.tint.a) == 4)
      ++i;
    else
      return "unknown or bad option " + a;
  }
  return "";
}

// 2. Where each character stands: a grid, alternate ones facing left, all
// of it fitted to the window (as posemorph-view frames one character).
gl::View PlaceCharacters(const Rig& rig, const Options& o, std::vector<Transform2D>& places) {
  const std::size_t count = places.size();
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;  // one character's bounds over its poses
  for (std::uint32_t i = 0; i < rig.pose_count(); ++i)
    for (std::size_t v = 0; v < 2 * std::size_t(rig.vertex_count()); v += 2) {
      const double* p = rig.pose_positions(i).data + v;
      x0 = std::min(x0, p[0]), x1 = std::max(x1, p[0]), y0 = std::min(y0, p[1]), y1 = std::max(y1, p[1]);
    }
  const double margin = 0.06 * std::max(x1 - x0, y1 - y0), cw = x1 - x0 + 2 * margin, ch = y1 - y0 + 2 * margin;
  const int columns = int(std::ceil(std::sqrt(double(count))));
  for (std::size_t k = 0; k < count; ++k)
    places[k] = Compose(Transform2D::Make(cw * double(k % columns), -ch * double(k / columns), 0, 1, 1, k % 2 == 1),
                        Transform2D::Make(-(x0 + x1) / 2, -(y0 + y1) / 2));
  const int rows = int((count + columns - 1) / columns);
  const double zoom = std::min(o.width / (cw * columns), o.height / (ch * rows));
  const double centre_x = cw * (columns - 1) / 2, centre_y = -ch * (rows - 1) / 2;
  return gl::View::Fit(o.width, o.height, centre_x, centre_y, zoom);
}

// 3. Pose-space points: the mouse over the window maps onto the weight grid; a crowd walks a path.
void PosePoints(const Rig& rig, const Options& o, int frame, std::vector<double>& points) {
  const std::size_t count = points.size() / 2;
  const int path = rig.path_count() > 0 ? 0 : -1;
  int mx = 0, my = 0;
  SDL_GetMouseState(&mx, &my);
  const PoseSpaceGrid& g = rig.grid();
  for (std::size_t k = 0; k < count; ++k) {
    double* p = &points[2 * k];
    if (count > 1 && path >= 0) {
      const PathView pv = rig.path(std::uint32_t(path));
      const double t0 = pv.start_time(), t1 = pv.end_time();
      SamplePath(pv, t0 + std::fmod(frame / 60.0 + (t1 - t0) * double(k) / double(count), t1 - t0), &p[0], &p[1]);
    } else if (!std::isnan(o.at_x)) {
      p[0] = o.at_x, p[1] = o.at_y;
    } else {
      p[0] = g.origin_x + g.cell * g.cells_x * mx / o.width;
      p[1] = g.origin_y + g.cell * g.cells_y * (1 - double(my) / o.height);
    }
  }
}

// 5. The test's frame, read back into a PNG.
bool WriteScreenshot(const std::string& path, int width, int height) {
  std::vector<unsigned char> rgba(std::size_t(width) * height * 4), rows_down(rgba.size());
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  for (int y = 0; y < height; ++y)  // OpenGL reads bottom-up
    std::memcpy(&rows_down[std::size_t(y) * width * 4], &rgba[std::size_t(height - 1 - y) * width * 4], width * 4u);
  png_image out{};
  out.version = PNG_IMAGE_VERSION, out.width = png_uint_32(width), out.height = png_uint_32(height);
  out.format = PNG_FORMAT_RGBA;
  return png_image_write_to_file(&out, path.c_str(), 0, rows_down.data(), 0, nullptr) != 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (const std::string problem = ParseOptions(argc, argv, o); !problem.empty()) return Fail(problem);

  // 1. The rig (shared by every character) and its drawings.
  std::ifstream in(o.rig_path, std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Rig rig;
  Error err;
  if (!in.good() && bytes.empty()) return Fail(o.rig_path + ": cannot read the file");
  if (!LoadRig(bytes.data(), bytes.size(), &rig, &err)) return Fail(o.rig_path + ": " + err.message);
  const std::uint32_t N = rig.pose_count();
  if (N > kMaxBlendDrawings)
    std::printf("%s has %u poses: each character blends its %u most weighted drawings\n", o.rig_path.c_str(), N,
                kMaxBlendDrawings);

  SDL_Init(SDL_INIT_VIDEO);
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, 3);
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_MINOR_VERSION, 3);
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_PROFILE_MASK, SDL_GL_CONTEXT_PROFILE_CORE);
  SDL_Window* window = SDL_CreateWindow("posemorph + SDL2", SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED, o.width,
                                        o.height, SDL_WINDOW_OPENGL);
  if (!window || !SDL_GL_CreateContext(window)) return Fail(std::string("no OpenGL 3.3 window: ") + SDL_GetError());
  // The renderer: the texture pages (the atlas beside the rig; or, for a rig
  // without one, every drawing of every list), the uvs, the triangles, the program.
  gl::Renderer renderer;
  gl::Settings settings;
  if (!o.filter.empty()) settings.filter = o.filter == "nearest" ? 1 : 0;  // else the rig's hint
  std::string problem;
  const std::string rig_folder = std::filesystem::path(o.rig_path).parent_path().string();
  const auto read = [&](const TexturePage& page, gl::Pixels* out, std::string* error) {
    if (!ImageReferenceStaysInside(page.name))  // a rig file is hostile input
      return *error = "a page's name leaves its folder", false;
    const std::string name(page.name.data, page.name.size);
    return ReadPage((page.atlas ? (rig_folder.empty() ? "." : rig_folder) : o.images) + "/" + name, page.premultiplied,
                    out, error);
  };
  if (!renderer.Init(rig, read, settings, &problem)) return Fail(o.rig_path + ": " + problem);

  // Per-character buffers (the attachments' too), sized by the rig in one place; where each character stands.
  const auto count = std::size_t(o.crowd);
  const CharacterBuffers sizes = CharacterBuffers::For(rig, count);
  std::vector<double> block(sizes.bytes / sizeof(double) + 1);
  DrawListJob job;
  sizes.Bind(rig, block.data(), block.size() * sizeof(double), &job);
  std::vector<double> points(2 * count);
  std::vector<Transform2D> places(count);
  const std::vector<Colour> colours(count, o.tint);
  job.points = {points.data(), points.size()};
  job.transforms = {places.data(), count};
  job.colours = {colours.data(), count};
  const gl::View view = PlaceCharacters(rig, o, places);

  double eval_seconds = 0;
  int frame = 0;
  for (bool running = true; running && (o.frames == 0 || frame < o.frames); ++frame) {
    for (SDL_Event e; SDL_PollEvent(&e);) running &= e.type != SDL_QUIT;
    PosePoints(rig, o, frame, points);
    // 4. The runtime: every character's draw lists (no allocation), then the renderer draws them.
    const Uint64 start = SDL_GetPerformanceCounter();
    job.Run();
    eval_seconds += double(SDL_GetPerformanceCounter() - start) / double(SDL_GetPerformanceFrequency());
    glViewport(0, 0, o.width, o.height);
    glClearColor(0.93f, 0.94f, 0.95f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    renderer.Draw(job, view);
    if (o.frames > 0 && frame + 1 == o.frames && !o.screenshot.empty() &&
        !WriteScreenshot(o.screenshot, o.width, o.height))
      return Fail(o.screenshot + ": cannot write the PNG");
    SDL_GL_SwapWindow(window);
  }
  std::printf(
      "%d frames of %zu character(s) on %s; the runtime took %.3f ms per frame for all of them; %u draw calls "
      "a frame (%u per character), %u texture(s) bound, %u page(s) (%s)\n",
      frame, count, reinterpret_cast<const char*>(glGetString(GL_RENDERER)), 1e3 * eval_seconds / std::max(frame, 1),
      renderer.draw_calls(), renderer.draw_calls() / std::uint32_t(count), renderer.texture_binds(), rig.page_count(),
      rig.has_atlas() ? "an atlas" : "one per drawing");
  SDL_Quit();
  return glGetError() == GL_NO_ERROR ? 0 : Fail("OpenGL reported an error");
}
