// SPDX-License-Identifier: MIT
// posemorph in an SDL2 + OpenGL 3.3 game: one character follows the mouse
// through pose space, or a crowd walks one of the rig's paths. The runtime
// hands over a draw list per character; this file only draws it.
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
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "posemorph/draw_list.h"
#include "posemorph/path.h"

using namespace posemorph;

namespace {

constexpr int K = 8;  // drawings blended per character (the shader has 8 uv inputs)

const char* kVertex = R"(#version 330 core
layout(location = 0) in vec2 position;      // rig units, from the draw list
layout(location = 1) in vec2 uv[8];         // each picked drawing's own uvs (locations 1..8)
uniform mat2 linear;                        // the character's Transform2D
uniform vec2 translation, view_scale, view_offset;
out vec2 v_uv[8];
void main() {
  vec2 world = linear * position + translation;
  gl_Position = vec4(world * view_scale + view_offset, 0.0, 1.0);
  for (int k = 0; k < 8; ++k) v_uv[k] = uv[k];
})";
// The exact cross-fade: the weighted sum of premultiplied drawings, times
// the draw list's colour (premultiplied: r a, g a, b a, a), then "over"
// (blend ONE, 1 - SRC_ALPHA).
const char* kFragment = R"(#version 330 core
uniform sampler2DArray drawings;
uniform float weights[8];
uniform int layers[8];
uniform vec4 tint;
in vec2 v_uv[8];
out vec4 colour;
void main() {
  colour = vec4(0.0);
  for (int k = 0; k < 8; ++k)
    if (weights[k] != 0.0) colour += weights[k] * texture(drawings, vec3(v_uv[k], float(layers[k])));
  colour *= tint;
})";

int Fail(const std::string& message) {
  std::fprintf(stderr, "sdl2_opengl: %s\n", message.c_str());
  return 1;
}

GLuint Compile(GLenum stage, const char* source) {
  const GLuint s = glCreateShader(stage);
  glShaderSource(s, 1, &source, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[1024];
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    std::fprintf(stderr, "sdl2_opengl: shader: %s\n", log);
  }
  return s;
}

// A drawing as premultiplied RGBA8, the way the cross-fade wants it.
bool ReadDrawing(const std::string& path, std::uint32_t width, std::uint32_t height, std::vector<unsigned char>* out,
                 std::string* error) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str())) return *error = path + ": cannot read the PNG", false;
  if (image.width != width || image.height != height) {
    *error = path + ": the drawing is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
             ", the rig was baked from " + std::to_string(width) + "x" + std::to_string(height);
    return png_image_free(&image), false;
  }
  image.format = PNG_FORMAT_RGBA;
  out->resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, out->data(), 0, nullptr)) return *error = path + ": bad PNG", false;
  for (std::size_t p = 0; p < out->size(); p += 4)
    for (int c = 0; c < 3; ++c) (*out)[p + c] = (unsigned char)(((*out)[p + c] * (*out)[p + 3] + 127) / 255);
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

// What the GPU holds for one rig: its drawings, every pose's uvs, the
// triangles, the characters' positions, and the program that draws them.
struct GpuRig {
  GLuint texture = 0, uvs = 0, positions = 0, indices = 0, vao = 0, program = 0;
  GLint weights_at = -1, layers_at = -1, linear_at = -1, translation_at = -1, tint_at = -1;
};

// 2. GPU resources, once: the drawings as a texture array, every pose's uvs, the triangles.
bool UploadRig(const Rig& rig, const Options& o, GpuRig& gpu, std::string* problem) {
  const std::uint32_t N = rig.pose_count(), V = rig.vertex_count();
  const DrawingCanvas canvas = rig.pose_canvas(0);
  const auto w = std::uint32_t(canvas.width), h = std::uint32_t(canvas.height);
  glGenTextures(1, &gpu.texture);
  glBindTexture(GL_TEXTURE_2D_ARRAY, gpu.texture);
  glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA8, GLsizei(w), GLsizei(h), GLsizei(N), 0, GL_RGBA, GL_UNSIGNED_BYTE,
               nullptr);
  for (std::uint32_t i = 0; i < N; ++i) {
    const StringView name = rig.pose_image(i);
    std::vector<unsigned char> rgba;
    if (!ReadDrawing(o.images + "/" + std::string(name.data, name.size), w, h, &rgba, problem)) return false;
    glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, GLint(i), GLsizei(w), GLsizei(h), 1, GL_RGBA, GL_UNSIGNED_BYTE,
                    rgba.data());
  }
  // Nearest for pixel art: --filter, else the rig's hint (its description's "filter").
  const bool nearest = o.filter.empty() ? rig.texture_filter() == TextureFilter::kNearest : o.filter == "nearest";
  const GLint f = nearest ? GL_NEAREST : GL_LINEAR;
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, f);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, f);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);  // outside a drawing: nothing
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
  glGenVertexArrays(1, &gpu.vao);
  glBindVertexArray(gpu.vao);
  glGenBuffers(1, &gpu.uvs);
  glBindBuffer(GL_ARRAY_BUFFER, gpu.uvs);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(N) * V * 8, nullptr, GL_STATIC_DRAW);
  for (std::uint32_t i = 0; i < N; ++i) glBufferSubData(GL_ARRAY_BUFFER, GLintptr(i) * V * 8, V * 8, rig.uvs(i).data);
  glGenBuffers(1, &gpu.indices);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gpu.indices);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(rig.triangles().size * 4), rig.triangles().data, GL_STATIC_DRAW);
  glGenBuffers(1, &gpu.positions);
  gpu.program = glCreateProgram();
  glAttachShader(gpu.program, Compile(GL_VERTEX_SHADER, kVertex));
  glAttachShader(gpu.program, Compile(GL_FRAGMENT_SHADER, kFragment));
  glLinkProgram(gpu.program);
  glUseProgram(gpu.program);
  for (int a = 0; a <= K; ++a) glEnableVertexAttribArray(GLuint(a));
  gpu.weights_at = glGetUniformLocation(gpu.program, "weights");
  gpu.layers_at = glGetUniformLocation(gpu.program, "layers");
  gpu.linear_at = glGetUniformLocation(gpu.program, "linear");
  gpu.translation_at = glGetUniformLocation(gpu.program, "translation");
  gpu.tint_at = glGetUniformLocation(gpu.program, "tint");
  return true;
}

// 3. Where each character stands: a grid, alternate ones facing left, all
// of it fitted to the window (as posemorph-view frames one character).
void PlaceCharacters(const Rig& rig, const Options& o, const GpuRig& gpu, std::vector<Transform2D>& places) {
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
  glUniform2f(glGetUniformLocation(gpu.program, "view_scale"), float(2 * zoom / o.width), float(2 * zoom / o.height));
  glUniform2f(glGetUniformLocation(gpu.program, "view_offset"), float(-centre_x * 2 * zoom / o.width),
              float(-centre_y * 2 * zoom / o.height));
}

// 4. Pose-space points: the mouse over the window maps onto the weight grid; a crowd walks a path.
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

// 6. Draw: positions up once, then one draw per character with its drawings' uvs bound.
void DrawCharacters(const DrawListJob& job, std::size_t count, std::uint32_t V, const GpuRig& gpu, const Options& o) {
  glViewport(0, 0, o.width, o.height);
  glClearColor(0.93f, 0.94f, 0.95f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // premultiplied "over"
  glBindBuffer(GL_ARRAY_BUFFER, gpu.positions);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(job.positions.size * 4), job.positions.data, GL_STREAM_DRAW);
  for (std::size_t k = 0; k < count; ++k) {
    const DrawList& d = job.output[k];
    glBindBuffer(GL_ARRAY_BUFFER, gpu.positions);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, reinterpret_cast<void*>(k * V * 8));
    glBindBuffer(GL_ARRAY_BUFFER, gpu.uvs);
    float weights[K] = {};
    GLint layers[K] = {};
    for (std::uint32_t s = 0; s < K; ++s) {
      const std::uint32_t pose = d.drawings[s < d.drawing_count ? s : 0].pose;
      weights[s] = s < d.drawing_count ? d.drawings[s].weight : 0.0f;
      layers[s] = GLint(pose);
      glVertexAttribPointer(1 + s, 2, GL_FLOAT, GL_FALSE, 0, reinterpret_cast<void*>(std::size_t(pose) * V * 8));
    }
    glUniform1fv(gpu.weights_at, K, weights);
    glUniform1iv(gpu.layers_at, K, layers);
    const float linear[4] = {d.transform.a, d.transform.b, d.transform.c, d.transform.d};
    glUniformMatrix2fv(gpu.linear_at, 1, GL_FALSE, linear);  // column-major
    glUniform2f(gpu.translation_at, d.transform.tx, d.transform.ty);
    const Colour c = PartColour(d, 0);  // a rig without parts: one part
    glUniform4f(gpu.tint_at, c.r * c.a, c.g * c.a, c.b * c.a, c.a);
    glDrawElements(GL_TRIANGLES, GLsizei(d.indices.size), GL_UNSIGNED_INT, nullptr);  // mirrored: no culling
  }
}

// 7. The test's frame, read back into a PNG.
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
  const std::uint32_t N = rig.pose_count(), V = rig.vertex_count();
  if (N > K)
    std::printf("%s has %u poses: each character blends its %d most weighted drawings\n", o.rig_path.c_str(), N, K);
  if (rig.pose_canvas(0).width <= 0 || rig.uvs(0).size == 0)
    return Fail(o.rig_path + ": the rig was not baked from drawings");

  SDL_Init(SDL_INIT_VIDEO);
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, 3);
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_MINOR_VERSION, 3);
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_PROFILE_MASK, SDL_GL_CONTEXT_PROFILE_CORE);
  SDL_Window* window = SDL_CreateWindow("posemorph + SDL2", SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED, o.width,
                                        o.height, SDL_WINDOW_OPENGL);
  if (!window || !SDL_GL_CreateContext(window)) return Fail(std::string("no OpenGL 3.3 window: ") + SDL_GetError());
  GpuRig gpu;
  std::string problem;
  if (!UploadRig(rig, o, gpu, &problem)) return Fail(problem);

  // 3. Per-character buffers, sized by the rig in one place; where each character stands.
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
  job.max_drawings = K;
  PlaceCharacters(rig, o, gpu, places);

  double eval_seconds = 0;
  int frame = 0;
  for (bool running = true; running && (o.frames == 0 || frame < o.frames); ++frame) {
    for (SDL_Event e; SDL_PollEvent(&e);) running &= e.type != SDL_QUIT;
    PosePoints(rig, o, frame, points);
    // 5. The runtime: every character's draw list (no allocation).
    const Uint64 start = SDL_GetPerformanceCounter();
    job.Run();
    eval_seconds += double(SDL_GetPerformanceCounter() - start) / double(SDL_GetPerformanceFrequency());
    DrawCharacters(job, count, V, gpu, o);
    if (o.frames > 0 && frame + 1 == o.frames && !o.screenshot.empty() &&
        !WriteScreenshot(o.screenshot, o.width, o.height))
      return Fail(o.screenshot + ": cannot write the PNG");
    SDL_GL_SwapWindow(window);
  }
  std::printf("%d frames of %zu character(s) on %s; the runtime took %.3f ms per frame for all of them\n", frame, count,
              reinterpret_cast<const char*>(glGetString(GL_RENDERER)), 1e3 * eval_seconds / std::max(frame, 1));
  SDL_Quit();
  return glGetError() == GL_NO_ERROR ? 0 : Fail("OpenGL reported an error");
}
