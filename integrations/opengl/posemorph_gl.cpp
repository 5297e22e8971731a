// SPDX-License-Identifier: MIT
// posemorph's OpenGL renderer (posemorph_gl.h).
#define GL_GLEXT_PROTOTYPES 1
#include "posemorph_gl.h"

#include <GL/gl.h>
#include <GL/glext.h>

#include <cstdio>
#include <string>

namespace posemorph::gl {

namespace {

constexpr int K = 8;  // drawings blended per list (8 uv attributes)

// Shared by OpenGL 3.3 core and OpenGL ES 3.0 (one uv attribute per drawing:
// ES allows no arrays of vertex inputs).
const char* kVertex = R"(
layout(location = 0) in vec2 position;  // rig units, from the draw list
layout(location = 1) in vec2 uv0;       // each picked drawing's own uvs
layout(location = 2) in vec2 uv1;
layout(location = 3) in vec2 uv2;
layout(location = 4) in vec2 uv3;
layout(location = 5) in vec2 uv4;
layout(location = 6) in vec2 uv5;
layout(location = 7) in vec2 uv6;
layout(location = 8) in vec2 uv7;
uniform mat2 linear;  // the character's Transform2D
uniform vec2 translation;
uniform vec4 view;    // scale x, y; offset x, y: world -> clip
out vec2 v_uv[8];
void main() {
  vec2 world = linear * position + translation;
  gl_Position = vec4(world * view.xy + view.zw, 0.0, 1.0);
  v_uv[0] = uv0; v_uv[1] = uv1; v_uv[2] = uv2; v_uv[3] = uv3;
  v_uv[4] = uv4; v_uv[5] = uv5; v_uv[6] = uv6; v_uv[7] = uv7;
})";
// The exact cross-fade: the weighted sum of premultiplied drawings, times
// the colour (premultiplied: r a, g a, b a, a), then "over".
const char* kFragment = R"(
uniform highp sampler2DArray drawings;
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

GLuint Compile(GLenum stage, bool es, const char* body, std::string* error) {
  const std::string source =
      std::string(es ? "#version 300 es\nprecision highp float;\n" : "#version 330 core\n") + body;
  const char* text = source.c_str();
  const GLuint s = glCreateShader(stage);
  glShaderSource(s, 1, &text, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[1024] = {};
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    *error = std::string("posemorph_gl: the ") + (stage == GL_VERTEX_SHADER ? "vertex" : "fragment") +
             " shader does not compile: " + log;
  }
  return s;
}

const Rig& ListRig(const Rig& rig, std::uint32_t list) { return list == 0 ? rig : *rig.attachment(list - 1).rig; }

}  // namespace

// One list's GPU objects: its drawings (layer part x N + pose), uvs, triangles.
struct Renderer::List {
  GLuint texture = 0, uvs = 0, indices = 0, vao = 0;
  std::uint32_t poses = 0, vertices = 0;
};

Renderer::~Renderer() {
  for (List* l : lists_) {
    glDeleteTextures(1, &l->texture);
    glDeleteBuffers(1, &l->uvs);
    glDeleteBuffers(1, &l->indices);
    glDeleteVertexArrays(1, &l->vao);
    delete l;
  }
  if (positions_[0]) glDeleteBuffers(2, positions_);
  if (program_) glDeleteProgram(program_);
}

bool Renderer::Init(const Rig& rig, const ImageReader& read, const Settings& settings, std::string* error) {
  if (rig_) return *error = "posemorph_gl: the renderer is initialised already", false;
  rig_ = &rig;
  const std::uint32_t lists = 1 + rig.attachment_count();
  for (std::uint32_t l = 0; l < lists; ++l) {
    const Rig& r = ListRig(rig, l);
    const DrawingCanvas canvas = r.pose_canvas(0);
    if (canvas.width <= 0 || r.uvs(0).size == 0)
      return *error = "the rig was not baked from drawings (list " + std::to_string(l) + " has no canvas or uvs)",
             false;
    const auto w = std::uint32_t(canvas.width), h = std::uint32_t(canvas.height);
    const std::uint32_t N = r.pose_count(), V = r.vertex_count(), P = r.part_count();
    List* gpu = new List;
    lists_.push_back(gpu);
    gpu->poses = N, gpu->vertices = V;
    glGenTextures(1, &gpu->texture);
    glBindTexture(GL_TEXTURE_2D_ARRAY, gpu->texture);
    glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA8, GLsizei(w), GLsizei(h), GLsizei(P * N), 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 nullptr);
    for (std::uint32_t p = 0; p < P; ++p)
      for (std::uint32_t i = 0; i < N; ++i) {
        const StringView name = r.part_image(p, i);
        Pixels pixels;
        if (!read(std::string(name.data, name.size), &pixels, error)) return false;
        const std::string source = pixels.source.empty() ? std::string(name.data, name.size) : pixels.source;
        if (pixels.width != w || pixels.height != h || pixels.rgba.size() != std::size_t(w) * h * 4)
          return *error = source + ": the drawing is " + std::to_string(pixels.width) + "x" +
                          std::to_string(pixels.height) + ", the rig was baked from " + std::to_string(w) + "x" +
                          std::to_string(h),
                 false;
        glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, GLint(p * N + i), GLsizei(w), GLsizei(h), 1, GL_RGBA,
                        GL_UNSIGNED_BYTE, pixels.rgba.data());
      }
    const bool nearest = settings.filter < 0 ? r.texture_filter() == TextureFilter::kNearest : settings.filter == 1;
    const GLint f = nearest ? GL_NEAREST : GL_LINEAR;
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, f);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, f);
    const GLint wrap = settings.clamp_to_border && !settings.es ? GL_CLAMP_TO_BORDER : GL_CLAMP_TO_EDGE;
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, wrap);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, wrap);
    glGenVertexArrays(1, &gpu->vao);
    glBindVertexArray(gpu->vao);
    glGenBuffers(1, &gpu->uvs);
    glBindBuffer(GL_ARRAY_BUFFER, gpu->uvs);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(N) * V * 8, nullptr, GL_STATIC_DRAW);
    for (std::uint32_t i = 0; i < N; ++i) glBufferSubData(GL_ARRAY_BUFFER, GLintptr(i) * V * 8, V * 8, r.uvs(i).data);
    glGenBuffers(1, &gpu->indices);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gpu->indices);  // part of the vertex array's state
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(r.triangles().size * 4), r.triangles().data, GL_STATIC_DRAW);
    for (int a = 0; a <= K; ++a) glEnableVertexAttribArray(GLuint(a));
  }
  glGenBuffers(2, positions_);  // the body's characters; every attachment's
  program_ = glCreateProgram();
  const GLuint vs = Compile(GL_VERTEX_SHADER, settings.es, kVertex, error);
  const GLuint fs = Compile(GL_FRAGMENT_SHADER, settings.es, kFragment, error);
  if (!error->empty()) return false;
  glAttachShader(program_, vs);
  glAttachShader(program_, fs);
  glLinkProgram(program_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint linked = 0;
  glGetProgramiv(program_, GL_LINK_STATUS, &linked);
  if (!linked) return *error = "posemorph_gl: the program does not link", false;
  weights_at_ = glGetUniformLocation(program_, "weights");
  layers_at_ = glGetUniformLocation(program_, "layers");
  linear_at_ = glGetUniformLocation(program_, "linear");
  translation_at_ = glGetUniformLocation(program_, "translation");
  tint_at_ = glGetUniformLocation(program_, "tint");
  view_at_ = glGetUniformLocation(program_, "view");
  return true;
}

void Renderer::Draw(const DrawListJob& job, const View& view) {
  draw_calls_ = 0;
  if (!rig_ || job.rig != rig_) return;
  const Rig& rig = *rig_;
  const std::uint32_t A = rig.attachment_count();
  const bool attached = A > 0 && job.attached_output.size >= job.count * A;
  glUseProgram(program_);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // premultiplied "over"
  glUniform4f(view_at_, view.scale_x, view.scale_y, view.offset_x, view.offset_y);
  glActiveTexture(GL_TEXTURE0);
  // Every character's positions up once per frame: the body's, and the attachments' in one buffer.
  glBindBuffer(GL_ARRAY_BUFFER, positions_[0]);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(job.positions.size * 4), job.positions.data, GL_STREAM_DRAW);
  if (attached) {
    glBindBuffer(GL_ARRAY_BUFFER, positions_[1]);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(job.attached_positions.size * 4), job.attached_positions.data,
                 GL_STREAM_DRAW);
  }
  DrawStep steps[1 + format::kMaxParts * (1 + format::kMaxAttachments)];
  for (std::size_t k = 0; k < job.count; ++k) {
    const DrawList& body = job.output[k];
    const DrawList* lists = attached ? &job.attached_output[k * A] : nullptr;
    const std::uint32_t n = CharacterDrawSteps(rig, body, lists, {steps, sizeof steps / sizeof steps[0]});
    for (std::uint32_t s = 0; s < n && s < sizeof steps / sizeof steps[0]; ++s) {
      const std::uint32_t l = steps[s].list;
      const DrawList& d = l == 0 ? body : lists[l - 1];
      const List& gpu = *lists_[l];
      const PartView part = ListRig(rig, l).part(steps[s].part);
      glBindVertexArray(gpu.vao);
      glBindTexture(GL_TEXTURE_2D_ARRAY, gpu.texture);
      const float* base = l == 0 ? job.positions.data : job.attached_positions.data;
      glBindBuffer(GL_ARRAY_BUFFER, positions_[l == 0 ? 0 : 1]);
      glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0,
                            reinterpret_cast<void*>(std::size_t(d.positions.data - base) * sizeof(float)));
      glBindBuffer(GL_ARRAY_BUFFER, gpu.uvs);
      float weights[K] = {};
      GLint layers[K] = {};
      for (std::uint32_t i = 0; i < std::uint32_t(K); ++i) {
        const std::uint32_t pose = d.drawings[i < d.drawing_count ? i : 0].pose;
        weights[i] = i < d.drawing_count ? d.drawings[i].weight : 0.0f;
        layers[i] = GLint(steps[s].part * gpu.poses + pose);
        glVertexAttribPointer(1 + i, 2, GL_FLOAT, GL_FALSE, 0,
                              reinterpret_cast<void*>(std::size_t(pose) * gpu.vertices * 8));
      }
      glUniform1fv(weights_at_, K, weights);
      glUniform1iv(layers_at_, K, layers);
      const float linear[4] = {d.transform.a, d.transform.b, d.transform.c, d.transform.d};
      glUniformMatrix2fv(linear_at_, 1, GL_FALSE, linear);  // column-major
      glUniform2f(translation_at_, d.transform.tx, d.transform.ty);
      const Colour c = PartColour(d, steps[s].part);
      glUniform4f(tint_at_, c.r * c.a, c.g * c.a, c.b * c.a, c.a);
      glDrawElements(GL_TRIANGLES, GLsizei(3 * part.triangle_count), GL_UNSIGNED_INT,
                     reinterpret_cast<void*>(std::size_t(part.first_triangle) * 12));  // mirrored: no culling
      ++draw_calls_;
    }
  }
}

}  // namespace posemorph::gl
