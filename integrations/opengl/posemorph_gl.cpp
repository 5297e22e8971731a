// SPDX-License-Identifier: MIT
// posemorph's OpenGL renderer (posemorph_gl.h).
#define GL_GLEXT_PROTOTYPES 1
#include "posemorph_gl.h"

#include <GL/gl.h>
#include <GL/glext.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>

namespace posemorph::gl {

namespace {

constexpr int K = 8;  // drawings blended per list (8 uv attributes)

// Shared by OpenGL 3.3 core and OpenGL ES 3.0 (one uv attribute per drawing:
// ES allows no arrays of vertex inputs). The renderer's vertices are the
// rig's split per part (a glued joint's vertex belongs to two parts, whose
// drawings lie in different regions of the page): each carries, per pose,
// its uv on its part's page and that page's layer, and its part, whose
// colour it draws with.
const char* kVertex = R"(
layout(location = 0) in vec2 position;  // rig units, from the draw list
layout(location = 1) in vec3 uv0;       // each picked drawing's page uv and layer
layout(location = 2) in vec3 uv1;
layout(location = 3) in vec3 uv2;
layout(location = 4) in vec3 uv3;
layout(location = 5) in vec3 uv4;
layout(location = 6) in vec3 uv5;
layout(location = 7) in vec3 uv6;
layout(location = 8) in vec3 uv7;
layout(location = 9) in float part;
uniform mat2 linear;  // the character's Transform2D
uniform vec2 translation;
uniform vec4 view;    // scale x, y; offset x, y: world -> clip
uniform vec4 tints[64];  // each part's colour, premultiplied (PartColour)
out vec3 v_uv[8];
flat out vec4 v_tint;
void main() {
  vec2 world = linear * position + translation;
  gl_Position = vec4(world * view.xy + view.zw, 0.0, 1.0);
  v_uv[0] = uv0; v_uv[1] = uv1; v_uv[2] = uv2; v_uv[3] = uv3;
  v_uv[4] = uv4; v_uv[5] = uv5; v_uv[6] = uv6; v_uv[7] = uv7;
  v_tint = tints[int(part)];
})";
// The exact cross-fade: the weighted sum of premultiplied drawings, times
// the part's colour (premultiplied: r a, g a, b a, a), then "over".
const char* kFragment = R"(
uniform highp sampler2DArray drawings;
uniform float weights[8];
in vec3 v_uv[8];
flat in vec4 v_tint;
out vec4 colour;
void main() {
  colour = vec4(0.0);
  for (int k = 0; k < 8; ++k)
    if (weights[k] != 0.0) colour += weights[k] * texture(drawings, v_uv[k]);
  colour *= v_tint;
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

// One list's GPU objects: its pages (array layers: Rig::page; lists whose
// pages are the same files, a character's atlas, share one texture, which
// the first of them owns), its vertices split per part (`source`: the rig
// vertex each draws), each pose's page uvs and layers, each vertex's part,
// and the triangles in each draw sequence's order (one sequence, or one
// per pose when the order changes with the pose), where part `p` at place
// i of sequence s starts at index first[s][i].
struct Renderer::List {
  GLuint texture = 0, uvs = 0, parts = 0, indices = 0, vao = 0, positions = 0;
  bool owns_texture = true, per_pose_order = false;
  std::uint32_t poses = 0, vertices = 0, part_count = 0, triangles = 0;
  std::vector<std::uint32_t> source;
  std::vector<std::vector<std::uint32_t>> first, place;  // per sequence: index start per place; place of each part
  std::vector<float> staging;                            // the characters' positions, split, each frame
};

namespace {

// List `l` shows the same pages as list 0 (names and sizes).
bool SamePages(const Rig& a, const Rig& b) {
  if (!a.has_atlas() || !b.has_atlas() || a.page_count() != b.page_count()) return false;
  for (std::uint32_t k = 0; k < a.page_count(); ++k) {
    const TexturePage x = a.page(k), y = b.page(k);
    if (x.name.size != y.name.size || std::memcmp(x.name.data, y.name.data, x.name.size) != 0 || x.width != y.width ||
        x.height != y.height)
      return false;
  }
  return true;
}

}  // namespace

Renderer::~Renderer() {
  for (List* l : lists_) {
    if (l->owns_texture) glDeleteTextures(1, &l->texture);
    const GLuint buffers[] = {l->uvs, l->parts, l->indices, l->positions};
    glDeleteBuffers(4, buffers);
    glDeleteVertexArrays(1, &l->vao);
    delete l;
  }
  if (program_) glDeleteProgram(program_);
}

bool Renderer::Init(const Rig& rig, const ImageReader& read, const Settings& settings, std::string* error) {
  if (rig_) return *error = "posemorph_gl: the renderer is initialised already", false;
  rig_ = &rig;
  const std::uint32_t lists = 1 + rig.attachment_count();
  for (std::uint32_t l = 0; l < lists; ++l) {
    const Rig& r = ListRig(rig, l);
    const std::uint32_t N = r.pose_count(), V = r.vertex_count(), pages = r.page_count();
    const TexturePage first = r.page(0);
    if (first.width == 0 || r.uvs(0).size == 0)
      return *error = "the rig was not baked from drawings (list " + std::to_string(l) + " has no canvas or uvs)",
             false;
    const std::uint32_t w = first.width, h = first.height;
    List* gpu = new List;
    lists_.push_back(gpu);
    gpu->poses = N, gpu->vertices = V;
    if (l > 0 && SamePages(rig, r)) {
      gpu->texture = lists_[0]->texture, gpu->owns_texture = false;
    } else {
      glGenTextures(1, &gpu->texture);
      glBindTexture(GL_TEXTURE_2D_ARRAY, gpu->texture);
      glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA8, GLsizei(w), GLsizei(h), GLsizei(pages), 0, GL_RGBA,
                   GL_UNSIGNED_BYTE, nullptr);
      for (std::uint32_t k = 0; k < pages; ++k) {
        const TexturePage page = r.page(k);
        Pixels pixels;
        if (!read(page, &pixels, error)) return false;
        const std::string source = pixels.source.empty() ? std::string(page.name.data, page.name.size) : pixels.source;
        if (pixels.width != w || pixels.height != h || pixels.rgba.size() != std::size_t(w) * h * 4)
          return *error = source + ": the " + (page.atlas ? "atlas page" : "drawing") + " is " +
                          std::to_string(pixels.width) + "x" + std::to_string(pixels.height) + ", the rig was baked " +
                          (page.atlas ? "with " : "from ") + std::to_string(w) + "x" + std::to_string(h),
                 false;
        glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, GLint(k), GLsizei(w), GLsizei(h), 1, GL_RGBA, GL_UNSIGNED_BYTE,
                        pixels.rgba.data());
      }
    }
    glBindTexture(GL_TEXTURE_2D_ARRAY, gpu->texture);
    const bool nearest = settings.filter < 0 ? r.texture_filter() == TextureFilter::kNearest : settings.filter == 1;
    const GLint f = nearest ? GL_NEAREST : GL_LINEAR;
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, f);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, f);
    const GLint wrap = settings.clamp_to_border && !settings.es ? GL_CLAMP_TO_BORDER : GL_CLAMP_TO_EDGE;
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, wrap);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, wrap);
    glGenVertexArrays(1, &gpu->vao);
    glBindVertexArray(gpu->vao);
    BuildGeometry(r, gpu);
    for (int a = 0; a <= K + 1; ++a) glEnableVertexAttribArray(GLuint(a));
  }
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
  linear_at_ = glGetUniformLocation(program_, "linear");
  translation_at_ = glGetUniformLocation(program_, "translation");
  tints_at_ = glGetUniformLocation(program_, "tints");
  view_at_ = glGetUniformLocation(program_, "view");
  return true;
}

void Renderer::BuildGeometry(const Rig& r, List* gpu) {
  const std::uint32_t N = r.pose_count(), V = r.vertex_count(), M = r.part_count(), T = r.triangle_count();
  const Span<const std::uint32_t> tris = r.triangles();
  // Each part's vertices get vertices of their own (a joint, shared by two parts, gets two).
  std::vector<std::uint32_t> split(std::size_t(M) * V, ~0u);
  std::vector<float> part_of;
  for (std::uint32_t p = 0; p < M; ++p) {
    const PartView pv = r.part(p);
    for (std::size_t k = 3 * std::size_t(pv.first_triangle); k < 3 * std::size_t(pv.first_triangle + pv.triangle_count);
         ++k) {
      std::uint32_t& e = split[std::size_t(p) * V + tris[k]];
      if (e == ~0u) {
        e = std::uint32_t(gpu->source.size());
        gpu->source.push_back(tris[k]);
        part_of.push_back(float(p));
      }
    }
  }
  const std::uint32_t E = std::uint32_t(gpu->source.size());
  gpu->vertices = E, gpu->part_count = M, gpu->triangles = T;
  // Per pose, each vertex's uv on its part's page and the page's layer.
  std::vector<float> uvs(std::size_t(N) * E * 3);
  for (std::uint32_t i = 0; i < N; ++i)
    for (std::uint32_t e = 0; e < E; ++e) {
      const TextureRegion g = r.part_region(std::uint32_t(part_of[e]), i);
      const float* uv = r.uvs(i).data + 2 * std::size_t(gpu->source[e]);
      float* out = &uvs[(std::size_t(i) * E + e) * 3];
      out[0] = uv[0] * g.scale_u + g.offset_u, out[1] = uv[1] * g.scale_v + g.offset_v, out[2] = float(g.page);
    }
  // The triangles in each sequence's order.
  gpu->per_pose_order = r.draw_order_changes();
  const std::uint32_t S = gpu->per_pose_order ? N : 1;
  std::vector<std::uint32_t> indices;
  gpu->first.assign(S, std::vector<std::uint32_t>(M + 1));
  gpu->place.assign(S, std::vector<std::uint32_t>(M));
  for (std::uint32_t q = 0; q < S; ++q) {
    const Span<const std::uint32_t> sequence = r.draw_sequence(q);
    for (std::uint32_t at = 0; at < M; ++at) {
      const std::uint32_t p = sequence[at];
      const PartView pv = r.part(p);
      gpu->first[q][at] = std::uint32_t(indices.size()) - q * 3 * T;
      gpu->place[q][p] = at;
      for (std::size_t k = 3 * std::size_t(pv.first_triangle);
           k < 3 * std::size_t(pv.first_triangle + pv.triangle_count); ++k)
        indices.push_back(split[std::size_t(p) * V + tris[k]]);
    }
    gpu->first[q][M] = 3 * T;
  }
  glGenBuffers(1, &gpu->uvs);
  glBindBuffer(GL_ARRAY_BUFFER, gpu->uvs);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(uvs.size() * 4), uvs.data(), GL_STATIC_DRAW);
  glGenBuffers(1, &gpu->parts);
  glBindBuffer(GL_ARRAY_BUFFER, gpu->parts);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(part_of.size() * 4), part_of.data(), GL_STATIC_DRAW);
  glVertexAttribPointer(GLuint(K + 1), 1, GL_FLOAT, GL_FALSE, 0, nullptr);
  glGenBuffers(1, &gpu->indices);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gpu->indices);  // part of the vertex array's state
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size() * 4), indices.data(), GL_STATIC_DRAW);
  glGenBuffers(1, &gpu->positions);
}

void Renderer::Draw(const DrawListJob& job, const View& view) {
  draw_calls_ = 0, texture_binds_ = 0;
  if (!rig_ || job.rig != rig_) return;
  const Rig& rig = *rig_;
  const std::uint32_t A = rig.attachment_count();
  const bool attached = A > 0 && job.attached_output.size >= job.count * A;
  const std::uint32_t lists = attached ? 1 + A : 1;
  glUseProgram(program_);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // premultiplied "over"
  glUniform4f(view_at_, view.scale_x, view.scale_y, view.offset_x, view.offset_y);
  glActiveTexture(GL_TEXTURE0);
  // Every character's positions up once per frame, list by list, each
  // vertex where the renderer split it (a joint's twice).
  for (std::uint32_t l = 0; l < lists; ++l) {
    List& gpu = *lists_[l];
    gpu.staging.resize(std::size_t(job.count) * gpu.vertices * 2);
    for (std::size_t k = 0; k < job.count; ++k) {
      const float* from = (l == 0 ? job.output[k] : job.attached_output[k * A + l - 1]).positions.data;
      float* to = gpu.staging.data() + k * gpu.vertices * 2;
      for (std::uint32_t e = 0; e < gpu.vertices; ++e)
        to[2 * e] = from[2 * gpu.source[e]], to[2 * e + 1] = from[2 * gpu.source[e] + 1];
    }
    glBindBuffer(GL_ARRAY_BUFFER, gpu.positions);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(gpu.staging.size() * 4), gpu.staging.data(), GL_STREAM_DRAW);
  }
  DrawStep steps[1 + format::kMaxParts * (1 + format::kMaxAttachments)];
  GLuint bound = 0;
  for (std::size_t k = 0; k < job.count; ++k) {
    const DrawList& body = job.output[k];
    const DrawList* others = attached ? &job.attached_output[k * A] : nullptr;
    const std::uint32_t n = std::min<std::uint32_t>(
        CharacterDrawSteps(rig, body, others, {steps, sizeof steps / sizeof steps[0]}), sizeof steps / sizeof steps[0]);
    // One draw call per run of steps of one list that follow each other in
    // its draw sequence: their triangles lie together in that sequence's order.
    for (std::uint32_t s = 0; s < n;) {
      const std::uint32_t l = steps[s].list;
      const DrawList& d = l == 0 ? body : others[l - 1];
      const List& gpu = *lists_[l];
      const std::uint32_t q = gpu.per_pose_order ? d.drawings[0].pose : 0;
      const std::uint32_t from = gpu.place[q][steps[s].part];
      std::uint32_t to = from + 1, next = s + 1;
      while (next < n && steps[next].list == l && gpu.place[q][steps[next].part] == to) ++to, ++next;
      glBindVertexArray(gpu.vao);
      if (gpu.texture != bound) {
        glBindTexture(GL_TEXTURE_2D_ARRAY, bound = gpu.texture);
        ++texture_binds_;
      }
      glBindBuffer(GL_ARRAY_BUFFER, gpu.positions);
      glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, reinterpret_cast<void*>(k * gpu.vertices * 8));
      glBindBuffer(GL_ARRAY_BUFFER, gpu.uvs);
      float weights[K] = {}, tints[4 * format::kMaxParts] = {};
      for (std::uint32_t i = 0; i < std::uint32_t(K); ++i) {
        const std::uint32_t pose = d.drawings[i < d.drawing_count ? i : 0].pose;
        weights[i] = i < d.drawing_count ? d.drawings[i].weight : 0.0f;
        glVertexAttribPointer(1 + i, 3, GL_FLOAT, GL_FALSE, 0,
                              reinterpret_cast<void*>(std::size_t(pose) * gpu.vertices * 12));
      }
      for (std::uint32_t p = 0; p < gpu.part_count && p < format::kMaxParts; ++p) {
        const Colour c = PartColour(d, p);
        tints[4 * p] = c.r * c.a, tints[4 * p + 1] = c.g * c.a, tints[4 * p + 2] = c.b * c.a, tints[4 * p + 3] = c.a;
      }
      glUniform1fv(weights_at_, K, weights);
      glUniform4fv(tints_at_, GLsizei(gpu.part_count), tints);
      const float linear[4] = {d.transform.a, d.transform.b, d.transform.c, d.transform.d};
      glUniformMatrix2fv(linear_at_, 1, GL_FALSE, linear);  // column-major
      glUniform2f(translation_at_, d.transform.tx, d.transform.ty);
      const std::uint32_t first = q * 3 * gpu.triangles + gpu.first[q][from];
      glDrawElements(GL_TRIANGLES, GLsizei(gpu.first[q][to] - gpu.first[q][from]), GL_UNSIGNED_INT,
                     reinterpret_cast<void*>(std::size_t(first) * 4));  // mirrored: no culling
      ++draw_calls_;
      s = next;
    }
  }
}

}  // namespace posemorph::gl
