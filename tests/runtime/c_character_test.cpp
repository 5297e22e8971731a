// SPDX-License-Identifier: MIT
// The C API's whole character (posemorph/posemorph_character.h): Pell with
// a face drawn from pm_character_draw_lists and pm_character_draw_steps
// alone gives DrawListJob's lists and CharacterDrawSteps' order bit for
// bit; the lists' parts, drawings, canvases and filters; every channel's
// names and sigma; the transform's composition; and each refusal.
#include <cstring>
#include <string>
#include <vector>

#include "posemorph/draw_list.h"
#include "posemorph/path.h"
#include "posemorph/posemorph.h"
#include "runtime_support.h"

using namespace posemorph;
using namespace posemorph::test;

namespace {

struct CRig {
  pm_rig* rig = nullptr;
  explicit CRig(const std::string& name) {
    const std::vector<unsigned char> bytes = TestRigBytes(name);
    pm_error err;
    REQUIRE(pm_rig_load(bytes.data(), bytes.size(), &rig, &err) == PM_OK);
  }
  ~CRig() { pm_rig_free(rig); }
};

// Buffers for pm_character_draw_lists.
struct CLists {
  pm_character_buffer_sizes sizes{};
  std::vector<double> work;
  std::vector<float> positions, attached_positions;
  std::vector<pm_draw_list> out, attached;
  CLists(const pm_rig* rig, std::size_t count) {
    REQUIRE(pm_character_buffers(rig, count, &sizes) == PM_OK);
    work.resize(sizes.workspace_doubles);
    positions.resize(sizes.position_floats);
    attached_positions.resize(sizes.attached_position_floats);
    out.resize(count);
    attached.resize(sizes.attached_lists);
  }
  int Run(const pm_rig* rig, const pm_draw_options* o, const pm_character_inputs& in) {
    return pm_character_draw_lists(rig, o, out.size(), &in, work.data(), work.size(), positions.data(),
                                   positions.size(), attached_positions.data(), attached_positions.size(), out.data(),
                                   out.size(), attached.data(), attached.size());
  }
};

// A C list (list `list` of the C rig) equals a C++ one field for field:
// its arrays are the C rig's own (the C++ list's are another load's, the
// same values); positions are compared by their bits by the caller.
void CheckSame(const pm_draw_list& c, const DrawList& cpp, const Rig& list_rig, const pm_rig* crig,
               std::uint32_t list) {
  CHECK(c.vertex_count == list_rig.vertex_count());
  CHECK(c.indices == (list == 0 ? pm_rig_triangles(crig) : pm_rig_attachment_triangles(crig, list - 1)));
  REQUIRE(c.index_count == cpp.indices.size);
  CHECK(std::memcmp(c.indices, cpp.indices.data, c.index_count * sizeof(std::uint32_t)) == 0);
  REQUIRE(c.drawing_count == cpp.drawing_count);
  for (std::uint32_t d = 0; d < c.drawing_count; ++d) {
    CHECK(c.drawings[d].pose == cpp.drawings[d].pose);
    CHECK(c.drawings[d].weight == cpp.drawings[d].weight);
    const std::uint32_t pose = c.drawings[d].pose;
    CHECK(c.drawings[d].uvs == (list == 0 ? pm_rig_uvs(crig, pose) : pm_rig_attachment_uvs(crig, list - 1, pose)));
    REQUIRE(c.drawings[d].uvs != nullptr);
    CHECK(std::memcmp(c.drawings[d].uvs, cpp.drawings[d].uvs, 2 * c.vertex_count * sizeof(float)) == 0);
  }
  CHECK(std::memcmp(&c.transform, &cpp.transform, sizeof(pm_transform)) == 0);
  CHECK(c.mirrored == (cpp.mirrored ? 1 : 0));
  REQUIRE(c.part_count == cpp.parts.size);
  CHECK(std::memcmp(c.parts, cpp.parts.data, c.part_count * sizeof(std::uint32_t)) == 0);
  CHECK(std::memcmp(&c.colour, &cpp.colour, sizeof(pm_colour)) == 0);
  CHECK(std::memcmp(c.part_opacity, cpp.part_opacity, sizeof(c.part_opacity)) == 0);
}

// Seven Pells with a face, the body and the face on their first paths.
struct Crowd {
  static constexpr std::size_t kCount = 7;
  std::vector<double> points, face_points;
  std::vector<pm_transform> transforms;
  std::vector<pm_colour> colours;
  std::vector<float> opacities;
  explicit Crowd(const Rig& rig) {
    for (std::size_t k = 0; k < kCount; ++k) {
      double bx, by, fx, fy;
      REQUIRE(SamplePath(rig, 0, 0.6 * double(k), &bx, &by));
      REQUIRE(SamplePath(*rig.channel_rig(1), 0, 0.35 * double(k), &fx, &fy));
      points.push_back(bx), points.push_back(by), face_points.push_back(fx), face_points.push_back(fy);
      pm_transform t;
      pm_transform_make(40.0 * double(k), -3.0 * double(k), 0.05 * double(k), 0.5, 0.5, int(k % 2), &t);
      transforms.push_back(t);
      colours.push_back({1, 0.5f + 0.05f * float(k), 1, 1 - 0.1f * float(k)});
      for (std::uint32_t p = 0; p < rig.part_count(); ++p) opacities.push_back(float((k + p) % 3) / 2);
    }
  }
};

}  // namespace

TEST_CASE("C API: Pell with a face from pm_character_draw_lists alone, DrawListJob's lists bit for bit") {
  const Rig rig = LoadTestRig("pell-face.compact");
  const CRig c("pell-face.compact");
  const std::size_t count = Crowd::kCount, A = rig.attachment_count();
  REQUIRE(A == 3);
  const Crowd crowd(rig);

  // C++: one DrawListJob with the attachments, and each character's steps.
  const CharacterBuffers sizes = CharacterBuffers::For(rig, count);
  std::vector<double> block((sizes.bytes + sizeof(double) - 1) / sizeof(double));
  DrawListJob job;
  REQUIRE(sizes.Bind(rig, block.data(), block.size() * sizeof(double), &job));
  job.points = MakeSpan(crowd.points);
  job.channel_points = MakeSpan(crowd.face_points);
  job.transforms = {reinterpret_cast<const Transform2D*>(crowd.transforms.data()), count};
  job.colours = {reinterpret_cast<const Colour*>(crowd.colours.data()), count};
  job.part_opacities = MakeSpan(crowd.opacities);
  job.sigma = 0.3;
  job.max_drawings = 4;
  REQUIRE(job.Run());

  // C: the same inputs.
  CLists l(c.rig, count);
  CHECK(l.sizes.workspace_doubles == sizes.workspace);
  CHECK(l.sizes.position_floats == sizes.positions);
  CHECK(l.sizes.attached_position_floats == sizes.attached_positions);
  CHECK(l.sizes.attached_lists == sizes.attached_lists);
  pm_draw_options o;
  pm_draw_options_default(&o);
  o.sigma = 0.3;
  o.max_drawings = 4;
  o.colours = crowd.colours.data();
  o.part_opacities = crowd.opacities.data();
  pm_character_inputs in{};
  in.points = crowd.points.data();
  in.channel_points = crowd.face_points.data();
  in.transforms = crowd.transforms.data();
  REQUIRE(l.Run(c.rig, &o, in) == PM_OK);

  REQUIRE(l.positions.size() == job.positions.size);
  CHECK(std::memcmp(l.positions.data(), job.positions.data, l.positions.size() * sizeof(float)) == 0);
  REQUIRE(l.attached_positions.size() == job.attached_positions.size);
  CHECK(std::memcmp(l.attached_positions.data(), job.attached_positions.data,
                    l.attached_positions.size() * sizeof(float)) == 0);
  for (std::size_t k = 0; k < count; ++k) {
    CAPTURE(k);
    CheckSame(l.out[k], job.output[k], rig, c.rig, 0);
    CHECK(l.out[k].positions == l.positions.data() + k * 2 * rig.vertex_count());
    for (std::size_t a = 0; a < A; ++a) {
      const pm_draw_list& ca = l.attached[k * A + a];
      CheckSame(ca, job.attached_output[k * A + a], *rig.attachment(std::uint32_t(a)).rig, c.rig, std::uint32_t(a + 1));
      CHECK(ca.positions == l.attached_positions.data() +
                                (job.attached_output[k * A + a].positions.data - job.attached_positions.data));
    }
    DrawStep expected[16];
    pm_draw_step steps[16];
    const std::uint32_t total = CharacterDrawSteps(rig, job.output[k], &job.attached_output[k * A], {expected, 16});
    REQUIRE(total == 7);
    REQUIRE(pm_character_draw_steps(c.rig, &l.out[k], &l.attached[k * A], steps, 16) == total);
    for (std::uint32_t s = 0; s < total; ++s) {
      CHECK(steps[s].list == expected[s].list);
      CHECK(steps[s].part == expected[s].part);
    }
    CHECK(pm_character_draw_steps(c.rig, &l.out[k], nullptr, steps, 16) == 4);            // the body alone
    CHECK(pm_character_draw_steps(c.rig, &l.out[k], &l.attached[k * A], steps, 2) == 7);  // counts all
    CHECK(pm_character_draw_steps(c.rig, &l.out[k], &l.attached[k * A], nullptr, 0) == 7);
  }

  // An animator's weights (here each channel's at the same points, in
  // pm_animator_update's layouts) give the same lists as the points.
  const std::uint32_t N = rig.pose_count(), NW = rig.attached_weight_count();
  std::vector<double> raw(count * N), limited(count * N), texture(count * N);
  std::vector<double> araw(count * NW), alimited(count * NW), atexture(count * NW);
  for (std::size_t k = 0; k < count; ++k) {
    REQUIRE(pm_channel_weights(c.rig, 0, crowd.points[2 * k], crowd.points[2 * k + 1], 0.3, 1, &raw[k * N],
                               &limited[k * N], &texture[k * N], N) == PM_OK);
    const std::size_t at = count * pm_rig_channel_weight_offset(c.rig, 1) + k * rig.channel_rig(1)->pose_count();
    REQUIRE(pm_channel_weights(c.rig, 1, crowd.face_points[2 * k], crowd.face_points[2 * k + 1], 0.3, 1, &araw[at],
                               &alimited[at], &atexture[at], NW) == PM_OK);
  }
  CLists w(c.rig, count);
  pm_character_inputs win{};
  win.weights = raw.data(), win.limited_weights = limited.data(), win.texture_weights = texture.data();
  win.attached_weights = araw.data(), win.attached_limited_weights = alimited.data();
  win.attached_texture_weights = atexture.data();
  win.transforms = crowd.transforms.data();
  REQUIRE(w.Run(c.rig, &o, win) == PM_OK);
  CHECK(w.positions == l.positions);
  CHECK(w.attached_positions == l.attached_positions);
  for (std::size_t k = 0; k < count * A; ++k) CHECK(w.attached[k].drawings[0].pose == l.attached[k].drawings[0].pose);

  // The body's lists are pm_draw_lists' (one rig, the first channel).
  std::size_t work_size = 0, position_size = 0;
  REQUIRE(pm_draw_list_buffers(c.rig, count, &work_size, &position_size) == PM_OK);
  std::vector<double> work(work_size);
  std::vector<float> positions(position_size);
  std::vector<pm_draw_list> body(count);
  REQUIRE(pm_draw_lists(c.rig, &o, count, crowd.points.data(), crowd.transforms.data(), work.data(), work.size(),
                        positions.data(), positions.size(), body.data(), count) == PM_OK);
  CHECK(positions == l.positions);
}

TEST_CASE("C API: every list's parts, drawings, canvases and filter, every channel's names and sigma") {
  const Rig rig = LoadTestRig("pell-face.compact");
  const CRig c("pell-face.compact");
  REQUIRE(pm_character_list_count(c.rig) == 4);
  CHECK(pm_character_list_count(nullptr) == 0);
  char name[256];
  std::size_t length = 0;
  for (std::uint32_t list = 0; list < 4; ++list) {
    CAPTURE(list);
    const Rig& r = list == 0 ? rig : *rig.attachment(list - 1).rig;
    pm_list_info info;
    REQUIRE(pm_character_list(c.rig, list, &info) == PM_OK);
    CHECK(info.vertex_count == r.vertex_count());
    CHECK(info.triangle_count == r.triangle_count());
    CHECK(info.pose_count == r.pose_count());
    CHECK(info.part_count == r.part_count());
    CHECK(info.channel == (list == 0 ? 0u : rig.attachment(list - 1).channel));
    for (std::uint32_t p = 0; p < info.part_count; ++p) {
      pm_part part;
      REQUIRE(pm_character_part(c.rig, list, p, &part) == PM_OK);
      CHECK(part.first_triangle == r.part(p).first_triangle);
      CHECK(part.triangle_count == r.part(p).triangle_count);
      REQUIRE(pm_character_part_name(c.rig, list, p, name, sizeof name, &length) == PM_OK);
      CHECK(std::string(name) == std::string(r.part(p).name.data, r.part(p).name.size));
      for (std::uint32_t pose = 0; pose < info.pose_count; ++pose) {
        REQUIRE(pm_character_part_image(c.rig, list, p, pose, name, sizeof name, &length) == PM_OK);
        CHECK(std::string(name) == std::string(r.part_image(p, pose).data, r.part_image(p, pose).size));
        CHECK(length > 0);  // Pell with a face is drawn: every part has a drawing
      }
    }
    pm_canvas canvas;
    REQUIRE(pm_character_canvas(c.rig, list, 0, &canvas) == PM_OK);
    CHECK(canvas.width == r.pose_canvas(0).width);
    CHECK(canvas.pivot_y == r.pose_canvas(0).pivot_y);
    CHECK(canvas.width > 0);
    CHECK(pm_character_texture_filter(c.rig, list) ==
          (r.texture_filter() == TextureFilter::kNearest ? PM_FILTER_NEAREST : PM_FILTER_LINEAR));
  }
  // An attachment's image is pm_rig_attachment_image's.
  char other[256];
  REQUIRE(pm_rig_attachment_image(c.rig, 1, 2, other, sizeof other, nullptr) == PM_OK);
  REQUIRE(pm_character_part_image(c.rig, 2, 0, 2, name, sizeof name, nullptr) == PM_OK);
  CHECK(std::string(name) == other);
  // Out of range: a list, a part, a pose; a short buffer says how long the name is.
  pm_part part;
  pm_list_info info;
  pm_canvas canvas;
  CHECK(pm_character_list(c.rig, 4, &info) == PM_ERROR_INVALID_ARGUMENT);
  CHECK(pm_character_part(c.rig, 1, 1, &part) == PM_ERROR_INVALID_ARGUMENT);
  CHECK(pm_character_part_image(c.rig, 1, 0, 99, name, sizeof name, nullptr) == PM_ERROR_INVALID_ARGUMENT);
  CHECK(pm_character_canvas(c.rig, 9, 0, &canvas) == PM_ERROR_INVALID_ARGUMENT);
  CHECK(pm_character_part_name(c.rig, 0, 0, name, 1, &length) == PM_ERROR_BUFFER_TOO_SMALL);
  CHECK(length == rig.part(0).name.size);

  // Channels: pose names, paths and sigma, channel 0 as the rig's own.
  for (std::uint32_t ch = 0; ch < rig.channel_count(); ++ch) {
    const Rig& r = *rig.channel_rig(ch);
    for (std::uint32_t p = 0; p < r.pose_count(); ++p) {
      REQUIRE(pm_channel_pose_name(c.rig, ch, p, name, sizeof name, nullptr) == PM_OK);
      CHECK(std::string(name) == std::string(r.pose_name(p).data, r.pose_name(p).size));
    }
    REQUIRE(pm_channel_path_count(c.rig, ch) == r.path_count());
    CHECK(r.path_count() > 0);
    for (std::uint32_t p = 0; p < r.path_count(); ++p) {
      REQUIRE(pm_channel_path_name(c.rig, ch, p, name, sizeof name, nullptr) == PM_OK);
      CHECK(pm_channel_path_find(c.rig, ch, name) == int(p));
    }
    double sigma = -1;
    REQUIRE(pm_channel_default_sigma(c.rig, ch, &sigma) == PM_OK);
    CHECK(sigma == r.default_sigma());
  }
  CHECK(pm_channel_pose_name(c.rig, 1, 99, name, sizeof name, nullptr) == PM_ERROR_INVALID_ARGUMENT);
  CHECK(pm_channel_path_count(c.rig, 2) == 0);
  double sigma = 0;
  CHECK(pm_channel_default_sigma(c.rig, 2, &sigma) == PM_ERROR_INVALID_ARGUMENT);

  // Composition: a camera after a character's place, as C++'s Compose.
  pm_transform camera, place, both;
  pm_transform_make(-100, 20, 0.3, 2, 2, 0, &camera);
  pm_transform_make(5, 6, -1.1, 0.5, 0.75, 1, &place);
  pm_transform_compose(&camera, &place, &both);
  const Transform2D expected =
      Compose(Transform2D::Make(-100, 20, 0.3, 2, 2, false), Transform2D::Make(5, 6, -1.1, 0.5, 0.75, true));
  CHECK(std::memcmp(&both, &expected, sizeof both) == 0);
  pm_transform_compose(&camera, &place, &place);  // in place
  CHECK(std::memcmp(&place, &expected, sizeof place) == 0);
}

TEST_CASE("C API: pm_character_draw_lists and pm_character_draw_steps refuse what they must") {
  const CRig c("pell-face.compact");
  const Rig rig = LoadTestRig("pell-face.compact");
  const Crowd crowd(rig);
  const std::size_t count = Crowd::kCount;
  CLists l(c.rig, count);
  pm_character_inputs in{};
  in.points = crowd.points.data();
  REQUIRE(l.Run(c.rig, nullptr, in) == PM_OK);
  auto run = [&](const pm_character_inputs& i, std::size_t shorter_work, std::size_t shorter_attached,
                 std::size_t shorter_lists) {
    return pm_character_draw_lists(c.rig, nullptr, count, &i, l.work.data(), l.work.size() - shorter_work,
                                   l.positions.data(), l.positions.size(), l.attached_positions.data(),
                                   l.attached_positions.size() - shorter_attached, l.out.data(), l.out.size(),
                                   l.attached.data(), l.attached.size() - shorter_lists);
  };
  CHECK(run(in, 1, 0, 0) == PM_ERROR_BUFFER_TOO_SMALL);
  CHECK(run(in, 0, 1, 0) == PM_ERROR_BUFFER_TOO_SMALL);
  CHECK(run(in, 0, 0, 1) == PM_ERROR_BUFFER_TOO_SMALL);
  CHECK(pm_character_draw_lists(c.rig, nullptr, count, &in, l.work.data(), l.work.size(), l.positions.data(),
                                l.positions.size(), nullptr, 0, l.out.data(), l.out.size(), nullptr,
                                0) == PM_ERROR_BUFFER_TOO_SMALL);  // the attachments need theirs
  pm_character_inputs none{};
  CHECK(run(none, 0, 0, 0) == PM_ERROR_INVALID_ARGUMENT);  // neither points nor weights
  std::vector<double> weights(count * rig.pose_count(), 0.2);
  pm_character_inputs both = in;
  both.weights = both.limited_weights = both.texture_weights = weights.data();
  CHECK(run(both, 0, 0, 0) == PM_ERROR_INVALID_ARGUMENT);  // points and weights
  pm_character_inputs body_weights_only{};
  body_weights_only.weights = body_weights_only.limited_weights = body_weights_only.texture_weights = weights.data();
  CHECK(run(body_weights_only, 0, 0, 0) == PM_ERROR_INVALID_ARGUMENT);  // the attachments' weights missing
  CHECK(pm_character_draw_lists(c.rig, nullptr, count, nullptr, l.work.data(), l.work.size(), l.positions.data(),
                                l.positions.size(), l.attached_positions.data(), l.attached_positions.size(),
                                l.out.data(), l.out.size(), l.attached.data(),
                                l.attached.size()) == PM_ERROR_INVALID_ARGUMENT);

  // Steps from lists that are not this rig's: a part or pose out of range.
  pm_draw_step steps[16];
  REQUIRE(pm_character_draw_steps(c.rig, &l.out[0], &l.attached[0], steps, 16) == 7);
  std::uint32_t bad_parts[4] = {0, 1, 2, 99};
  pm_draw_list bad = l.out[0];
  bad.parts = bad_parts;
  CHECK(pm_character_draw_steps(c.rig, &bad, &l.attached[0], steps, 16) == 0);
  bad = l.out[0];
  bad.part_count = 65;
  CHECK(pm_character_draw_steps(c.rig, &bad, nullptr, steps, 16) == 0);
  bad = l.attached[1];
  bad.drawings[0].pose = 1000;
  pm_draw_list attached[3] = {l.attached[0], bad, l.attached[2]};
  CHECK(pm_character_draw_steps(c.rig, &l.out[0], attached, steps, 16) == 0);
  CHECK(pm_character_draw_steps(nullptr, &l.out[0], nullptr, steps, 16) == 0);

  // A rig without attachments needs no attached buffers and gives pm_draw_lists' lists.
  const CRig snake("snake");
  const Rig snake_rig = LoadTestRig("snake");
  pm_character_buffer_sizes s;
  REQUIRE(pm_character_buffers(snake.rig, 3, &s) == PM_OK);
  CHECK(s.attached_position_floats == 0);
  CHECK(s.attached_lists == 0);
  std::vector<double> work(s.workspace_doubles), points = {0.1, 0.2, 0.5, 0.5, 0.9, 0.1};
  std::vector<float> positions(s.position_floats), expected(s.position_floats);
  pm_draw_list out[3], out2[3];
  pm_character_inputs sin{};
  sin.points = points.data();
  REQUIRE(pm_character_draw_lists(snake.rig, nullptr, 3, &sin, work.data(), work.size(), positions.data(),
                                  positions.size(), nullptr, 0, out, 3, nullptr, 0) == PM_OK);
  REQUIRE(pm_draw_lists(snake.rig, nullptr, 3, points.data(), nullptr, work.data(), work.size(), expected.data(),
                        expected.size(), out2, 3) == PM_OK);
  CHECK(positions == expected);
  CHECK(pm_character_draw_steps(snake.rig, &out[0], nullptr, steps, 16) == snake_rig.part_count());
  CHECK(pm_character_list_count(snake.rig) == 1);
}
