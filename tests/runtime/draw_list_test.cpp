// SPDX-License-Identifier: MIT
// Draw lists: the drawings picked, the positions (bit for bit what the morph
// jobs give), transforms, every failure case of DrawListJob::Validate, the
// buffers bundle, and the C API's form of the same.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>

#include "posemorph/draw_list.h"
#include "posemorph/path.h"
#include "posemorph/posemorph.h"
#include "runtime_support.h"

using namespace posemorph;
using namespace posemorph::test;

namespace {

std::vector<double> PointsOnPath(const Rig& rig, std::size_t count) {
  std::vector<double> p(2 * count);
  const PathView path = rig.path(0);
  const double t0 = path.start_time(), t1 = path.end_time();
  for (std::size_t k = 0; k < count; ++k)
    SamplePath(path, t0 + (t1 - t0) * double(k) / double(count), &p[2 * k], &p[2 * k + 1]);
  return p;
}

struct Lists {
  std::vector<double> workspace;
  std::vector<float> positions;
  std::vector<DrawList> out;
  DrawListJob job;
  Lists(const Rig& rig, const std::vector<double>& points, std::uint32_t k = kMaxBlendDrawings) {
    const std::size_t count = points.size() / 2;
    workspace.resize(DrawListWorkspaceSize(rig, count));
    positions.resize(count * 2 * rig.vertex_count());
    out.resize(count);
    job.rig = &rig;
    job.count = count;
    job.points = MakeSpan(points);
    job.max_drawings = k;
    job.workspace = MakeSpan(workspace);
    job.positions = MakeSpan(positions);
    job.output = MakeSpan(out);
  }
};

}  // namespace

TEST_CASE("draw lists: all drawings up to K, else the K most weighted, renormalised") {
  const double five[5] = {0.1, 0.4, 0.0, 0.3, 0.2};
  BlendedDrawing d[kMaxBlendDrawings];
  REQUIRE(PickDrawings(five, 8, d) == 5);
  double sum = 0;
  for (int k = 0; k < 5; ++k) sum += d[k].weight;
  CHECK(sum == doctest::Approx(1.0));
  CHECK(d[0].pose == 1);
  CHECK(d[0].weight == doctest::Approx(0.4));
  CHECK(d[3].pose == 0);
  CHECK(d[3].weight == doctest::Approx(0.1));
  CHECK(d[4].pose == 2);  // ties and zeros keep pose order after the larger ones

  double ten[10];
  for (int i = 0; i < 10; ++i) ten[i] = (i + 1) / 55.0;  // 1..10, sum 1
  REQUIRE(PickDrawings(ten, 8, d) == 8);
  CHECK(d[0].pose == 9);
  CHECK(d[7].pose == 2);
  CHECK(d[0].weight == doctest::Approx(10.0 / 52.0));  // poses 0 and 1 (weights 1, 2) dropped

  REQUIRE(PickDrawings(ten, 2, d) == 2);  // K = 2
  CHECK(d[0].pose == 9);
  CHECK(d[1].pose == 8);
  CHECK(d[0].weight == doctest::Approx(10.0 / 19.0));
  REQUIRE(PickDrawings(ten, 1, d) == 1);  // the dominant drawing only
  CHECK(d[0].pose == 9);
  CHECK(d[0].weight == 1.0f);

  const double ties[3] = {0.5, 0.5, 0.0};
  REQUIRE(PickDrawings(ties, 1, d) == 1);
  CHECK(d[0].pose == 0);  // ties to the lower pose

  const double nothing[3] = {0, -1, std::numeric_limits<double>::quiet_NaN()};
  REQUIRE(PickDrawings(nothing, 8, d) == 3);
  CHECK(d[0].weight == 1.0f);
  CHECK(d[1].weight == 0.0f);
  CHECK(d[2].weight == 0.0f);
  CHECK(PickDrawings(Span<const double>(), 8, d) == 0);
  CHECK(PickDrawings(five, 0, d) == 0);
  CHECK(PickDrawings(five, 8, Span<BlendedDrawing>(d, 2)) == 2);  // never past the output

  // Infinite weights count as 0 like NaN; finite weights whose sum overflows
  // keep their proportions: every weight written is finite, and they sum to 1.
  const double inf = std::numeric_limits<double>::infinity();
  const double wild[4] = {inf, 1e308, -inf, 1e308};
  REQUIRE(PickDrawings(wild, 8, d) == 4);
  CHECK(d[0].pose == 1);
  CHECK(d[1].pose == 3);
  CHECK(d[0].weight == 0.5f);
  CHECK(d[1].weight == 0.5f);
  CHECK(d[2].weight == 0.0f);
  CHECK(d[3].weight == 0.0f);
  const double huge[3] = {1.7e308, 1.7e308, 0.85e308};
  REQUIRE(PickDrawings(huge, 8, d) == 3);
  CHECK(d[0].weight == doctest::Approx(0.4));
  CHECK(d[2].weight == doctest::Approx(0.2));
  const double only_inf[2] = {inf, inf};
  REQUIRE(PickDrawings(only_inf, 8, d) == 2);
  CHECK(d[0].weight == 1.0f);  // every weight 0: the first drawing
  CHECK(d[1].weight == 0.0f);
}

TEST_CASE("draw lists: positions bit for bit as the morph jobs give them, drawings as WeightsJob's texture weights") {
  for (const char* name : {"snake", "gingerbread"}) {
    CAPTURE(name);
    const Rig rig = LoadTestRig(name);
    const std::size_t N = rig.pose_count(), v2 = 2 * std::size_t(rig.vertex_count());
    for (std::size_t count : {1u, 5u, 19u}) {
      CAPTURE(count);
      const std::vector<double> points = PointsOnPath(rig, count);
      Lists l(rig, points, 3);
      l.job.sigma = 0.3;
      REQUIRE(l.job.Validate());
      REQUIRE(l.job.Run());
      for (std::size_t k = 0; k < count; ++k) {
        const Weights w = WeightsAt(rig, points[2 * k], points[2 * k + 1], 0.3);
        const std::vector<double> x = Morph(rig, w.raw, w.limited);
        std::vector<float> xf(v2);
        for (std::size_t i = 0; i < v2; ++i) xf[i] = float(x[i]);
        const DrawList& d = l.out[k];
        REQUIRE(d.positions.size == v2);
        CHECK(d.positions.data == l.positions.data() + k * v2);
        CHECK(std::memcmp(d.positions.data, xf.data(), v2 * sizeof(float)) == 0);
        CHECK(d.indices.data == rig.triangles().data);
        CHECK(d.indices.size == rig.triangles().size);
        BlendedDrawing expected[kMaxBlendDrawings];
        const std::uint32_t n = PickDrawings(MakeSpan(w.texture), 3, expected);
        REQUIRE(d.drawing_count == n);
        CHECK(n == std::min<std::size_t>(3, N));
        for (std::uint32_t i = 0; i < n; ++i) {
          CHECK(d.drawings[i].pose == expected[i].pose);
          CHECK(d.drawings[i].weight == expected[i].weight);
          const Span<const float> uv = rig.uvs(d.drawings[i].pose);
          CHECK(d.drawings[i].uvs == (uv.size ? uv.data : nullptr));
        }
        CHECK(!d.mirrored);
      }
    }
  }
}

TEST_CASE("draw lists: linear interpolation and the rig's default sigma") {
  const Rig rig = LoadTestRig("gingerbread");
  const std::vector<double> points = PointsOnPath(rig, 3);
  Lists l(rig, points);
  l.job.interpolation = Interpolation::kLinear;
  REQUIRE(l.job.Run());
  const std::size_t v2 = 2 * std::size_t(rig.vertex_count());
  for (std::size_t k = 0; k < 3; ++k) {
    const Weights w = WeightsAt(rig, points[2 * k], points[2 * k + 1], rig.default_sigma());
    const std::vector<double> x = Morph(rig, w.raw, w.limited, Interpolation::kLinear);
    for (std::size_t i = 0; i < v2; ++i) CHECK(l.positions[k * v2 + i] == float(x[i]));
    BlendedDrawing expected[kMaxBlendDrawings];
    PickDrawings(MakeSpan(w.texture), 8, expected);
    CHECK(l.out[k].drawings[0].weight == expected[0].weight);  // sigma -1: the rig's default
  }
}

TEST_CASE("draw lists: transforms pass through, a mirrored one is flagged") {
  const Rig rig = LoadTestRig("snake");
  const std::vector<double> points = PointsOnPath(rig, 3);
  Lists l(rig, points);
  const Transform2D t[3] = {Transform2D::Make(10, 20), Transform2D::Make(0, 0, 0.5, 2, 2, true),
                            Transform2D::Make(-5, 1, 1.0, 1, -1)};
  l.job.transforms = t;
  REQUIRE(l.job.Run());
  CHECK(!l.out[0].mirrored);
  CHECK(l.out[1].mirrored);
  CHECK(l.out[2].mirrored);  // a negative y scale mirrors too
  for (int k = 0; k < 3; ++k) CHECK(std::memcmp(&l.out[k].transform, &t[k], sizeof(Transform2D)) == 0);
}

TEST_CASE("draw lists: colours and part opacities pass through clamped, NaN as drawn, attachments take the colour") {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  CHECK(ClampColour({0.25f, 2, -1, nan}).r == 0.25f);
  CHECK(ClampColour({0.25f, 2, -1, nan}).g == 1);
  CHECK(ClampColour({0.25f, 2, -1, nan}).b == 0);
  CHECK(ClampColour({0.25f, 2, -1, nan}).a == 1);
  CHECK(ClampColour({-inf, inf, 0.5f, 0}).r == 0);
  CHECK(ClampColour({-inf, inf, 0.5f, 0}).g == 1);
  CHECK(ClampColour({-inf, inf, 0.5f, 0}).a == 0);

  const Rig rig = LoadTestRig("pell-face.compact");  // layered: parts and attachments
  const std::uint32_t P = rig.part_count(), A = rig.attachment_count();
  REQUIRE(P > 1);
  REQUIRE(A > 0);
  const std::size_t count = 3;
  const std::vector<double> points = PointsOnPath(rig, count);
  Lists plain(rig, points);
  std::vector<DrawList> plain_attached(count * A);
  std::vector<float> plain_attached_positions(count * 2 * rig.attached_vertex_count());
  plain.job.attached_output = MakeSpan(plain_attached);
  plain.job.attached_positions = MakeSpan(plain_attached_positions);
  REQUIRE(plain.job.Run());
  for (const DrawList& d : plain.out) {  // no colours given: as drawn
    CHECK(d.colour.r == 1);
    CHECK(d.colour.a == 1);
    for (float o : d.part_opacity) CHECK(o == 1);
  }

  const Colour colours[count] = {{1, 0.5f, 0.25f, 0.75f}, {nan, 3, -2, nan}, {0, 0, 0, 0}};
  std::vector<float> opacity(count * P);
  for (std::size_t k = 0; k < count; ++k)
    for (std::uint32_t p = 0; p < P; ++p) opacity[k * P + p] = float(p) / float(P) - 0.1f * float(k);
  opacity[P + 1] = nan;
  Lists l(rig, points);
  std::vector<DrawList> attached(count * A);
  std::vector<float> attached_positions(count * 2 * rig.attached_vertex_count());
  l.job.attached_output = MakeSpan(attached);
  l.job.attached_positions = MakeSpan(attached_positions);
  l.job.colours = colours;
  l.job.part_opacities = MakeSpan(opacity);
  REQUIRE(l.job.Run());
  CHECK(l.positions == plain.positions);  // colour never changes a position
  CHECK(attached_positions == plain_attached_positions);
  for (std::size_t k = 0; k < count; ++k) {
    CAPTURE(k);
    const Colour want = ClampColour(colours[k]);
    CHECK(std::memcmp(&l.out[k].colour, &want, sizeof(Colour)) == 0);
    for (std::uint32_t p = 0; p < P; ++p) {
      const float o = opacity[k * P + p];
      CHECK(l.out[k].part_opacity[p] == (o >= 0 ? std::min(o, 1.0f) : (o < 0 ? 0.0f : 1.0f)));
      CHECK(PartColour(l.out[k], p).a == want.a * l.out[k].part_opacity[p]);
      CHECK(PartColour(l.out[k], p).g == want.g);
    }
    for (std::uint32_t p = P; p < format::kMaxParts; ++p) CHECK(l.out[k].part_opacity[p] == 1);
    CHECK(PartColour(l.out[k], format::kMaxParts).a == want.a);  // out of range: the character's alone
    for (std::uint32_t a = 0; a < A; ++a) {
      const DrawList& d = attached[k * A + a];
      CHECK(std::memcmp(&d.colour, &want, sizeof(Colour)) == 0);
      for (float o : d.part_opacity) CHECK(o == 1);
    }
  }
  CHECK(l.out[1].part_opacity[1] == 1);  // NaN: as drawn
  CHECK(l.out[2].colour.a == 0);         // a character faded out
}

TEST_CASE("transforms: scale, flip, rotate, move, in that order, composition") {
  const Transform2D t = Transform2D::Make(5, -3, 3.14159265358979323846 / 2, 2, 3, true);
  double x = 0, y = 0;
  t.Apply(1, 0, &x, &y);  // (1,0) -scale-> (2,0) -flip-> (-2,0) -rotate 90-> (0,-2) -move-> (5,-5)
  CHECK(x == doctest::Approx(5));
  CHECK(y == doctest::Approx(-5));
  t.Apply(0, 1, &x, &y);  // (0,3) -> (0,3) -> (-3,0) -> (2,-3)
  CHECK(x == doctest::Approx(2));
  CHECK(y == doctest::Approx(-3));
  CHECK(t.mirrors());
  const Transform2D camera = Transform2D::Make(100, 0, 0, 0.5, 0.5);
  const Transform2D both = Compose(camera, t);
  both.Apply(1, 0, &x, &y);
  CHECK(x == doctest::Approx(100 + 2.5));
  CHECK(y == doctest::Approx(-2.5));
  const Transform2D bad = Transform2D::Make(std::numeric_limits<double>::infinity(), 0);
  CHECK(bad.a == 1.0f);
  CHECK(bad.tx == 0.0f);  // non-finite: the identity
  // Finite inputs whose fields would not fit a float: the identity too, so
  // that every field of every transform is finite.
  for (const Transform2D& f :
       {Transform2D::Make(1e300, 0), Transform2D::Make(0, 0, 0, 1e300), Transform2D::Make(0, 0, 0, 1, -1e39),
        Compose(Transform2D::Make(0, 0, 0, 1e30, 1e30), Transform2D::Make(0, 0, 0, 1e30, 1e30))}) {
    for (float v : {f.a, f.b, f.c, f.d, f.tx, f.ty}) CHECK(std::isfinite(v));
    CHECK(f.a == 1.0f);
    CHECK(f.d == 1.0f);
    CHECK(f.tx == 0.0f);
  }
  const Transform2D big = Transform2D::Make(3e38, -3e38, 0, 3e38);  // within float: kept
  CHECK(big.tx == 3e38f);
  CHECK(big.a == 3e38f);
}

TEST_CASE("DrawListJob::Validate refuses each listed failure case, and Run then does nothing") {
  const Rig rig = LoadTestRig("snake");
  const std::vector<double> points = PointsOnPath(rig, 4);
  Lists good(rig, points);
  REQUIRE(good.job.Validate());
  const Transform2D three[3];
  const Colour colours[3];
  const std::vector<float> opacities(4 * rig.part_count() - 1, 0.5f);
  Rig empty;
  struct Case {
    const char* what;
    std::function<void(DrawListJob&)> spoil;
  } cases[] = {
      {"no rig", [](DrawListJob& j) { j.rig = nullptr; }},
      {"a rig not loaded", [&](DrawListJob& j) { j.rig = &empty; }},
      {"count 0", [](DrawListJob& j) { j.count = 0; }},
      {"count above MaxDrawListCount", [&](DrawListJob& j) { j.count = MaxDrawListCount(rig) + 1; }},
      {"too few points", [](DrawListJob& j) { j.points.size = 7; }},
      {"transforms neither empty nor count long", [&](DrawListJob& j) { j.transforms = three; }},
      {"colours neither empty nor count long", [&](DrawListJob& j) { j.colours = colours; }},
      {"colours with no data",
       [](DrawListJob& j) {
         j.colours = {nullptr, 4};
       }},
      {"part_opacities shorter than count x parts", [&](DrawListJob& j) { j.part_opacities = MakeSpan(opacities); }},
      {"max_drawings 0", [](DrawListJob& j) { j.max_drawings = 0; }},
      {"max_drawings 9", [](DrawListJob& j) { j.max_drawings = 9; }},
      {"short workspace", [](DrawListJob& j) { j.workspace.size -= 1; }},
      {"short positions", [](DrawListJob& j) { j.positions.size -= 1; }},
      {"bad interpolation", [](DrawListJob& j) { j.interpolation = Interpolation(7); }},
      {"fewer output lists than characters", [](DrawListJob& j) { j.output.size = 3; }},
      {"no output", [](DrawListJob& j) { j.output = {}; }},
  };
  for (const Case& c : cases) {
    CAPTURE(c.what);
    Lists l(rig, points);
    c.spoil(l.job);
    CHECK(!l.job.Validate());
    const std::vector<float> before = l.positions;
    CHECK(!l.job.Run());
    CHECK(l.positions == before);
  }
  // Any point gives a finite frame.
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> wild = {inf, -inf, nan, nan, 1e308, -1e308, 0, 0};
  Lists w(rig, wild);
  REQUIRE(w.job.Run());
  for (float v : w.positions) CHECK(std::isfinite(v));
}

TEST_CASE("CharacterBuffers: every size from the rig, one block bound to a job") {
  const Rig rig = LoadTestRig("gingerbread");
  const CharacterBuffers b = CharacterBuffers::For(rig, 6);
  CHECK(b.workspace == DrawListWorkspaceSize(rig, 6));
  CHECK(b.positions == 6 * 2 * std::size_t(rig.vertex_count()));
  CHECK(b.draw_lists == 6);
  std::vector<double> block((b.bytes + sizeof(double) - 1) / sizeof(double) + 1);
  DrawListJob job;
  CHECK(!b.Bind(rig, block.data(), b.bytes - 1, &job));                                    // too short
  CHECK(!b.Bind(rig, reinterpret_cast<unsigned char*>(block.data()) + 4, b.bytes, &job));  // misaligned
  CHECK(!b.Bind(LoadTestRig("snake"), block.data(), b.bytes, &job));                       // sized for another rig
  REQUIRE(b.Bind(rig, block.data(), block.size() * sizeof(double), &job));
  const std::vector<double> points = PointsOnPath(rig, 6);
  job.points = MakeSpan(points);
  REQUIRE(job.Run());
  Lists reference(rig, points);
  REQUIRE(reference.job.Run());
  CHECK(std::memcmp(job.positions.data, reference.positions.data(), b.positions * sizeof(float)) == 0);
  CHECK(job.output[5].drawings[0].pose == reference.out[5].drawings[0].pose);
}

TEST_CASE("C API: pm_draw_lists gives what DrawListJob gives") {
  const std::vector<unsigned char> bytes = TestRigBytes("gingerbread");
  pm_rig* rig = nullptr;
  pm_error err;
  REQUIRE(pm_rig_load(bytes.data(), bytes.size(), &rig, &err) == PM_OK);
  const Rig cpp = LoadTestRig("gingerbread");
  const std::vector<double> points = PointsOnPath(cpp, 5);
  std::size_t work_size = 0, position_size = 0;
  REQUIRE(pm_draw_list_buffers(rig, 5, &work_size, &position_size) == PM_OK);
  std::vector<double> work(work_size);
  std::vector<float> positions(position_size);
  pm_draw_list out[5];
  pm_transform t[5];
  for (int k = 0; k < 5; ++k) pm_transform_make(k * 10.0, 0, 0.1 * k, 1, 1, k % 2, &t[k]);
  pm_draw_options o;
  pm_draw_options_default(&o);
  o.max_drawings = 4;
  CHECK(pm_draw_lists(rig, &o, 5, points.data(), t, work.data(), work.size() - 1, positions.data(), positions.size(),
                      out, 5) == PM_ERROR_BUFFER_TOO_SMALL);
  CHECK(pm_draw_lists(rig, &o, 5, points.data(), t, work.data(), work.size(), positions.data(), positions.size(), out,
                      4) == PM_ERROR_BUFFER_TOO_SMALL);
  o.max_drawings = 9;
  CHECK(pm_draw_lists(rig, &o, 5, points.data(), t, work.data(), work.size(), positions.data(), positions.size(), out,
                      5) == PM_ERROR_INVALID_ARGUMENT);
  o.max_drawings = 4;
  REQUIRE(pm_draw_lists(rig, &o, 5, points.data(), t, work.data(), work.size(), positions.data(), positions.size(), out,
                        5) == PM_OK);
  Lists l(cpp, points, 4);
  REQUIRE(l.job.Run());
  CHECK(positions == l.positions);
  for (int k = 0; k < 5; ++k) {
    CHECK(out[k].vertex_count == cpp.vertex_count());
    CHECK(out[k].index_count == 3 * cpp.triangle_count());
    CHECK(out[k].positions == positions.data() + k * 2 * cpp.vertex_count());
    REQUIRE(out[k].drawing_count == l.out[k].drawing_count);
    for (std::uint32_t i = 0; i < out[k].drawing_count; ++i) {
      CHECK(out[k].drawings[i].pose == l.out[k].drawings[i].pose);
      CHECK(out[k].drawings[i].weight == l.out[k].drawings[i].weight);
      CHECK(out[k].drawings[i].uvs == l.out[k].drawings[i].uvs);
    }
    CHECK(out[k].mirrored == k % 2);
    CHECK(out[k].transform.tx == float(k * 10.0));
    CHECK(out[k].colour.r == 1);
    CHECK(out[k].colour.a == 1);
    CHECK(out[k].part_opacity[0] == 1);
  }
  // Colours and part opacities, as the C++ job clamps them.
  const std::uint32_t P = cpp.part_count();
  pm_colour colours[5] = {{0.5f, 0.25f, 1, 0.8f}, {2, -1, 0, 0}, {1, 1, 1, 1}, {0, 0, 0, 0.5f}, {1, 0.5f, 0.5f, 1}};
  std::vector<float> opacity(5 * P);
  for (std::size_t i = 0; i < opacity.size(); ++i) opacity[i] = float(i % 3) * 0.5f - 0.25f;
  o.colours = colours;
  o.part_opacities = opacity.data();
  REQUIRE(pm_draw_lists(rig, &o, 5, points.data(), t, work.data(), work.size(), positions.data(), positions.size(), out,
                        5) == PM_OK);
  CHECK(positions == l.positions);
  l.job.colours = {reinterpret_cast<const Colour*>(colours), 5};
  l.job.part_opacities = MakeSpan(opacity);
  REQUIRE(l.job.Run());
  for (int k = 0; k < 5; ++k) {
    CHECK(std::memcmp(&out[k].colour, &l.out[k].colour, sizeof(pm_colour)) == 0);
    CHECK(std::memcmp(out[k].part_opacity, l.out[k].part_opacity, sizeof(out[k].part_opacity)) == 0);
  }
  CHECK(out[1].colour.r == 1);
  CHECK(out[1].colour.g == 0);
  CHECK(out[0].part_opacity[0] == 0);  // -0.25 clamps to 0
  o.colours = nullptr;
  o.part_opacities = nullptr;
  double tex[8] = {0.1, 0.5, 0.4};
  pm_blended_drawing picked[8];
  CHECK(pm_pick_drawings(tex, 3, 2, picked, 8) == 2);
  CHECK(picked[0].pose == 1);
  CHECK(picked[1].pose == 2);
  pm_rig_free(rig);
}

// Pell with a face channel: the attachments' draw lists, as AttachJob gives
// their positions and as the face channel's texture weights pick drawings.
TEST_CASE("draw lists: a rig with channels lists each character's attachments, the same bits as AttachJob") {
  const Rig rig = LoadTestRig("pell-face.compact");
  REQUIRE(rig.attachment_count() == 3);
  const Rig& face = *rig.channel_rig(1);
  const std::size_t count = 7, A = rig.attachment_count();
  const std::size_t v2 = 2 * std::size_t(rig.vertex_count()), a2 = 2 * std::size_t(rig.attached_vertex_count());
  std::vector<double> points, face_points;
  for (std::size_t k = 0; k < count; ++k) {
    double bx, by, fx, fy;
    REQUIRE(SamplePath(rig, 0, 0.6 * double(k), &bx, &by));
    REQUIRE(SamplePath(face, 0, 0.35 * double(k), &fx, &fy));
    points.push_back(bx), points.push_back(by), face_points.push_back(fx), face_points.push_back(fy);
  }
  const CharacterBuffers sizes = CharacterBuffers::For(rig, count);
  CHECK(sizes.attached_positions == count * a2);
  CHECK(sizes.attached_lists == count * A);
  std::vector<double> block((sizes.bytes + sizeof(double) - 1) / sizeof(double));
  DrawListJob job;
  REQUIRE(sizes.Bind(rig, block.data(), block.size() * sizeof(double), &job));
  job.points = MakeSpan(points);
  job.channel_points = MakeSpan(face_points);
  job.sigma = 0.4;
  REQUIRE(job.Validate());
  REQUIRE(job.Run());
  // The same characters one by one: the body with MorphJob, the face's
  // weights with WeightsJob, the attachments with AttachJob.
  for (std::size_t k = 0; k < count; ++k) {
    const Weights bw = WeightsAt(rig, points[2 * k], points[2 * k + 1], 0.4);
    const Weights fw = WeightsAt(face, face_points[2 * k], face_points[2 * k + 1], 0.4);
    std::vector<double> work(std::max(rig.morph_workspace_size(), rig.attach_workspace_size())), body(v2), att(a2);
    std::vector<float> att_f32(a2);
    MorphJob mj;
    mj.rig = &rig, mj.weights = MakeSpan(bw.raw), mj.limited_weights = MakeSpan(bw.limited);
    mj.workspace = MakeSpan(work), mj.positions = MakeSpan(body);
    REQUIRE(mj.Run());
    AttachJob aj;
    aj.rig = &rig, aj.body_positions = MakeSpan(body);
    aj.weights = MakeSpan(fw.raw), aj.limited_weights = MakeSpan(fw.limited);
    aj.workspace = MakeSpan(work), aj.positions = MakeSpan(att), aj.positions_f32 = MakeSpan(att_f32);
    REQUIRE(aj.Run());
    std::size_t at = 0;
    for (std::size_t a = 0; a < A; ++a) {
      const DrawList& list = job.attached_output[k * A + a];
      const Rig& part = *rig.attachment(std::uint32_t(a)).rig;
      const std::size_t p2 = 2 * std::size_t(part.vertex_count());
      REQUIRE(list.positions.size == p2);
      CHECK(std::memcmp(list.positions.data, att_f32.data() + at, p2 * sizeof(float)) == 0);
      CHECK(list.indices.data == part.triangles().data);
      BlendedDrawing expected[kMaxBlendDrawings];
      const std::uint32_t n = PickDrawings(MakeSpan(fw.texture), kMaxBlendDrawings, {expected, kMaxBlendDrawings});
      REQUIRE(list.drawing_count == n);
      for (std::uint32_t d = 0; d < n; ++d) {
        CHECK(list.drawings[d].pose == expected[d].pose);
        CHECK(list.drawings[d].weight == expected[d].weight);
        CHECK(list.drawings[d].uvs == part.uvs(expected[d].pose).data);
      }
      CHECK(list.transform.tx == job.output[k].transform.tx);
      at += p2;
    }
    // Drawn back to front: the body's four parts (the arms behind the body,
    // the head in front), then the face's three (order 3).
    DrawStep steps[16];
    const std::uint32_t total = CharacterDrawSteps(rig, job.output[k], &job.attached_output[k * A], {steps, 16});
    REQUIRE(total == 7);
    for (std::uint32_t s = 0; s < 4; ++s) CHECK(steps[s].list == 0);
    for (std::uint32_t s = 4; s < 7; ++s) CHECK(steps[s].list == s - 3);
    CHECK(CharacterDrawSteps(rig, job.output[k], nullptr, {steps, 16}) == 4);
    CHECK(CharacterDrawSteps(rig, job.output[k], &job.attached_output[k * A], {steps, 2}) == 7);  // counts all
  }
  // One character at a time gives the same bits as the batch.
  for (std::size_t k = 0; k < count; ++k) {
    const CharacterBuffers one = CharacterBuffers::For(rig, 1);
    std::vector<double> b1((one.bytes + sizeof(double) - 1) / sizeof(double));
    DrawListJob single;
    REQUIRE(one.Bind(rig, b1.data(), b1.size() * sizeof(double), &single));
    single.points = {points.data() + 2 * k, 2};
    single.channel_points = {face_points.data() + 2 * k, 2};
    single.sigma = 0.4;
    REQUIRE(single.Run());
    CHECK(std::memcmp(single.positions.data, job.positions.data + k * v2, v2 * sizeof(float)) == 0);
    std::size_t at = 0;
    for (std::size_t a = 0; a < A; ++a) {
      const std::size_t p2 = single.attached_output[a].positions.size;
      CHECK(std::memcmp(single.attached_output[a].positions.data, job.attached_output[k * A + a].positions.data,
                        p2 * sizeof(float)) == 0);
      at += p2;
    }
    CHECK(at == a2);
  }
  // Failure cases: too few attached lists or floats, too few channel points,
  // attached lists for a rig without attachments; the first channel alone
  // (no attached spans) still runs.
  auto refused = [&](auto change) {
    DrawListJob j = job;
    change(j);
    return !j.Validate() && !j.Run();
  };
  CHECK(refused([&](DrawListJob& j) { j.attached_output.size -= 1; }));
  CHECK(refused([&](DrawListJob& j) { j.attached_positions.size -= 1; }));
  CHECK(refused([&](DrawListJob& j) { j.attached_positions = {}; }));
  CHECK(refused([&](DrawListJob& j) { j.channel_points.size = 2 * count - 1; }));
  const Rig snake = LoadTestRig("snake");
  CHECK(refused([&](DrawListJob& j) {
    j.rig = &snake;
    j.attached_positions = {};
  }));
  DrawListJob body_only = job;
  body_only.attached_output = {};
  body_only.attached_positions = {};
  CHECK(body_only.Run());
}
