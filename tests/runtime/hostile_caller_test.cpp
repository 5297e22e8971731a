// SPDX-License-Identifier: MIT
// What a hostile or careless caller finds: moved-from rigs, empty batches,
// numbers that are finite but huge, a C handle loaded twice. Every misuse
// gets an error, never undefined behaviour (the debug preset runs this under
// ASan + UBSan), and a rig that loads gives finite positions for every
// input a job accepts.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "c_api_internal.h"
#include "posemorph/image_reference.h"
#include "posemorph/path.h"
#include "posemorph/posemorph.h"
#include "posemorph/rig_format.h"
#include "runtime_support.h"

using namespace posemorph;
using namespace posemorph::test;

namespace {

bool AllFinite(const std::vector<double>& v) {
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

}  // namespace

TEST_CASE("a moved-from rig is empty, not a view into its new owner's memory") {
  Rig a = LoadTestRig("snake");
  Rig b = std::move(a);
  CHECK_FALSE(a.loaded());
  CHECK(a.triangles().empty());
  CHECK(a.pose_positions(0).empty());
  CHECK(a.grid().weights.empty());
  CHECK(a.factor().value.empty());
  CHECK(a.arena_bytes() == 0);
  CHECK(b.loaded());
  {
    Rig c;
    c = std::move(b);  // move assignment, then the new owner dies
    CHECK(c.loaded());
  }
  CHECK_FALSE(b.loaded());
  // Jobs refuse the emptied rigs instead of reading freed memory.
  std::vector<double> w(5, 0.2), work(4 * 205), x(2 * 205);
  MorphJob job;
  job.rig = &b, job.weights = MakeSpan(w), job.limited_weights = MakeSpan(w);
  job.workspace = MakeSpan(work), job.positions = MakeSpan(x);
  CHECK_FALSE(job.Run());
  WeightsJob wj;
  wj.rig = &a, wj.raw = MakeSpan(w);
  CHECK_FALSE(wj.Run());
  double px, py;
  CHECK_FALSE(SamplePath(a, 0, 0.5, &px, &py));
  // A rig with channels: its attachments live in its arena and move with
  // it; the moved-from rig has none.
  Rig face = LoadTestRig("pell-face.compact");
  REQUIRE(face.attachment_count() == 3);
  const Rig* nested = face.attachment(0).rig;
  Rig moved = std::move(face);
  CHECK(face.attachment_count() == 0);
  CHECK(face.channel_count() == 1);
  CHECK(face.channel_rig(1) == nullptr);
  CHECK(face.attached_vertex_count() == 0);
  CHECK(moved.attachment(0).rig == nested);
  CHECK(moved.channel_rig(1) == nested);
  AttachJob attach;
  attach.rig = &face;
  CHECK_FALSE(attach.Run());
}

TEST_CASE("an empty batch does nothing, whatever its spans") {
  const Rig rig = LoadTestRig("snake");
  MorphBatchJob job;
  job.rig = &rig;
  job.count = 0;  // no weights, no workspace, no output: nothing to touch
  CHECK(job.Validate());
  CHECK(job.Run());
}

TEST_CASE("finite but huge stored numbers are refused at load, naming the section") {
  const std::vector<unsigned char> bytes = TestRigBytes("small");
  struct Case {
    std::uint32_t tag;
    double value;
    const char* expect;
  };
  const Case cases[] = {
      {format::kAngles, 1e53, "angles[0]"},          {format::kStretches, -1e30, "stretches[0]"},
      {format::kWeightGrid, 1e20, "weight grid[0]"}, {format::kPathKeys, 1e308, "path key[0]"},
      {format::kGradients, 1e200, "gradients[0]"},
  };
  for (const Case& c : cases) {
    const std::size_t at = SectionOffset(bytes, c.tag);
    REQUIRE(at != 0);
    const std::vector<unsigned char> bad = WithValue(bytes, at, c.value);
    Rig rig;
    Error err;
    CAPTURE(std::string(c.expect));
    CHECK_FALSE(LoadRig(bad.data(), bad.size(), &rig, &err));
    CHECK(err.code == ErrorCode::kBadValue);
    CHECK(std::string(err.message).find(c.expect) != std::string::npos);
    CHECK(std::string(err.message).find("beyond the limit") != std::string::npos);
  }
  // At the limits themselves the rig loads, and still evaluates to finite positions.
  std::vector<unsigned char> edge = WithValue(bytes, SectionOffset(bytes, format::kAngles), format::kMaxAngle);
  edge = WithValue(edge, SectionOffset(edge, format::kWeightGrid), -format::kMaxGridWeight);
  Rig rig;
  Error err;
  REQUIRE_MESSAGE(LoadRig(edge.data(), edge.size(), &rig, &err), err.message);
  for (double px : {-1e300, -3.0, 0.0, 0.01, 0.5, 7.0, 1e300}) {
    const Weights w = WeightsAt(rig, px, 0.25);
    CHECK(AllFinite(Morph(rig, w.raw, w.limited)));
  }
}

TEST_CASE("the factor's inverse diagonal is held to the limit on stored values") {
  // Issue 38, F1: DINV was checked for > 0 and finite only, not against the
  // 1e15 FORMAT.md states for every other stored value.
  const std::vector<unsigned char> bytes = TestRigBytes("snake");
  const std::size_t dinv = SectionOffset(bytes, format::kFactorInvDiagonal);
  REQUIRE(dinv != 0);
  Rig rig;
  Error err;
  const std::vector<unsigned char> big = WithValue(bytes, dinv, 1e20);
  CHECK_FALSE(LoadRig(big.data(), big.size(), &rig, &err));
  CHECK(err.code == ErrorCode::kBadValue);
  CHECK(std::string(err.message).find("factor diagonal 0 is not positive and at most 1e+15") != std::string::npos);
  const std::vector<unsigned char> edge = WithValue(bytes, dinv, format::kMaxMagnitude);
  CHECK_MESSAGE(LoadRig(edge.data(), edge.size(), &rig, &err), err.message);
}

// The rig with every factor value 1e3: each stored value within its limit.
std::vector<unsigned char> AmplifyingFactor(const std::vector<unsigned char>& bytes) {
  Rig honest;
  REQUIRE(LoadRig(bytes.data(), bytes.size(), &honest, nullptr));
  const std::size_t nnz = honest.factor().value.size;
  const std::size_t at = SectionOffset(bytes, format::kFactorValues);
  REQUIRE(at != 0);
  std::vector<unsigned char> bad = bytes;
  const double thousand = 1e3;
  for (std::size_t q = 1; q < nnz; ++q) std::memcpy(bad.data() + at + 8 * q, &thousand, 8);
  return WithValue(bad, at, thousand);  // the first value, and the checksum
}

TEST_CASE("a factor that amplifies the solve is refused at load, in C++ and C") {
  // Issue 38, F1: every stored value within its limit, the factor's values
  // all 1e3, and the rig loaded and gave positions near 7.9e303 (infinite
  // in float). The loader now bounds the solve for every weight the jobs
  // accept (solve_bound.cpp); the honest snake's bound is about 2e10.
  const std::vector<unsigned char> bad = AmplifyingFactor(TestRigBytes("snake"));
  Rig rig;
  Error err;
  CHECK_FALSE(LoadRig(bad.data(), bad.size(), &rig, &err));
  CHECK(err.code == ErrorCode::kBadValue);
  CHECK_MESSAGE(std::string(err.message).find("the factor can amplify the solve beyond 1e+30") != std::string::npos,
                err.message);
  CHECK_FALSE(rig.loaded());
  std::size_t needed = 0;
  REQUIRE(RigMemorySize(bad.data(), bad.size(), &needed, &err));  // sizing reads no values
  // Memory on a kRigMemoryAlignment boundary (WebAssembly's vectors align to 8).
  std::vector<double> memory(needed / sizeof(double) + 8);
  const std::uintptr_t start = reinterpret_cast<std::uintptr_t>(memory.data());
  void* aligned =
      reinterpret_cast<void*>((start + kRigMemoryAlignment - 1) / kRigMemoryAlignment * kRigMemoryAlignment);
  CHECK_FALSE(LoadRigInPlace(bad.data(), bad.size(), aligned, needed, &rig, &err));
  CHECK(err.code == ErrorCode::kBadValue);
  pm_rig* handle = nullptr;
  pm_error perr;
  CHECK(pm_rig_load(bad.data(), bad.size(), &handle, &perr) == PM_ERROR_BAD_VALUE);
  CHECK(handle == nullptr);
  CHECK(std::string(perr.message).find("amplify") != std::string::npos);
}

TEST_CASE("an attachment whose factor amplifies the solve is refused with the whole character") {
  // Issue 38, F1: "an attachment's factor does the same". The nested rig is
  // a rig file inside CHAN with its own checksum; poisoned, then both
  // checksums made right again.
  const std::vector<unsigned char> bytes = TestRigBytes("pell-face");
  Rig face;
  Error err;
  REQUIRE(LoadRig(bytes.data(), bytes.size(), &face, &err));
  REQUIRE(face.attachment_count() > 0);
  const std::size_t chan = SectionOffset(bytes, format::kChannels);
  REQUIRE(chan != 0);
  format::AttachmentEntry e{};
  REQUIRE(format::ReadRecord(bytes.data() + chan, bytes.size() - chan, format::ChannelsHeader::kSize, &e));
  std::vector<unsigned char> nested(bytes.begin() + std::ptrdiff_t(chan + e.offset),
                                    bytes.begin() + std::ptrdiff_t(chan + e.offset + e.size));
  nested = AmplifyingFactor(nested);
  std::vector<unsigned char> bad = bytes;
  std::copy(nested.begin(), nested.end(), bad.begin() + std::ptrdiff_t(chan + e.offset));
  bad = WithValue(bad, format::kOffChecksum, std::uint32_t(0));  // placeholder; WithValue writes the real checksum
  Rig rig;
  CHECK_FALSE(LoadRig(bad.data(), bad.size(), &rig, &err));
  CHECK(err.code == ErrorCode::kBadValue);
  const std::string message = err.message;
  CHECK_MESSAGE(message.find("attachment 0: ") != std::string::npos, message);
  CHECK_MESSAGE(message.find("the factor can amplify the solve") != std::string::npos, message);
  LoadOptions unbounded;
  unbounded.bound_solve = false;
  CHECK_MESSAGE(LoadRig(bad.data(), bad.size(), &rig, &err, unbounded), err.message);  // only the bound refused it
}

TEST_CASE("a factor that amplifies the solve, loaded past the bound: the jobs write zeros and fail") {
  // Defence in depth: with the load's bound off (a test-only option), every
  // job still refuses to return success with a position beyond kMaxPosition.
  const Rig honest = LoadTestRig("snake");
  const std::vector<unsigned char> bad = AmplifyingFactor(TestRigBytes("snake"));
  Error err;
  LoadOptions unbounded;
  unbounded.bound_solve = false;
  Rig rig;
  REQUIRE_MESSAGE(LoadRig(bad.data(), bad.size(), &rig, &err, unbounded), err.message);
  const std::size_t N = rig.pose_count(), v2 = 2 * std::size_t(rig.vertex_count());
  std::vector<double> w(N, 0.0), work(rig.morph_workspace_size()), x(v2, 1.0);
  std::vector<float> x32(v2, 1.0f);
  w[0] = 1;
  MorphJob job;
  job.rig = &rig, job.weights = MakeSpan(w), job.limited_weights = MakeSpan(w);
  job.workspace = MakeSpan(work), job.positions = MakeSpan(x), job.positions_f32 = MakeSpan(x32);
  CHECK(job.Validate());
  CHECK_FALSE(job.Run());
  CHECK(std::all_of(x.begin(), x.end(), [](double v) { return v == 0; }));
  CHECK(std::all_of(x32.begin(), x32.end(), [](float v) { return v == 0; }));
  // The honest rig at the same weights is within the bound and succeeds.
  job.rig = &honest;
  CHECK(job.Run());
  CHECK(AllFinite(x));

  // A batch: every character of the tampered rig fails, zeros written.
  const std::size_t count = 11;
  std::vector<double> bw(count * N, 0.0), bwork(rig.batch_workspace_size()), bx(count * v2, 1.0);
  for (std::size_t k = 0; k < count; ++k) bw[k * N + k % N] = 1;
  MorphBatchJob batch;
  batch.rig = &rig, batch.count = count, batch.weights = MakeSpan(bw), batch.limited_weights = MakeSpan(bw);
  batch.workspace = MakeSpan(bwork), batch.positions = MakeSpan(bx);
  CHECK_FALSE(batch.Run());
  CHECK(std::all_of(bx.begin(), bx.end(), [](double v) { return v == 0; }));

  // The C API says PM_ERROR_BAD_VALUE (not a bad argument).
  pm_rig* handle = new pm_rig{std::move(rig), false};
  CHECK(pm_morph(handle, w.data(), w.data(), 0, work.data(), work.size(), x.data(), nullptr, x.size()) ==
        PM_ERROR_BAD_VALUE);
  CHECK(pm_morph_batch(handle, count, bw.data(), bw.data(), bwork.data(), bwork.size(), bx.data(), nullptr,
                       bx.size()) == PM_ERROR_BAD_VALUE);
  pm_rig_free(handle);
}

TEST_CASE("jobs take weights up to kMaxJobWeight and give finite positions, larger ones are refused") {
  const Rig rig = LoadTestRig("snake");
  const std::size_t N = rig.pose_count();
  std::vector<double> w(N, 0.0), ws(N, 0.0);
  w[1] = kMaxJobWeight, w[3] = -kMaxJobWeight, ws[2] = kMaxJobWeight;
  CHECK(AllFinite(Morph(rig, w, ws)));
  std::vector<double> work(rig.morph_workspace_size()), x(2 * rig.vertex_count());
  MorphJob job;
  job.rig = &rig, job.limited_weights = MakeSpan(ws), job.workspace = MakeSpan(work), job.positions = MakeSpan(x);
  w[1] = 2 * kMaxJobWeight;
  job.weights = MakeSpan(w);
  CHECK_FALSE(job.Validate());
  w[1] = std::nan("");
  CHECK_FALSE(job.Validate());
}

TEST_CASE("the C API refuses to load over a live handle instead of leaking it") {
  const std::vector<unsigned char> bytes = TestRigBytes("small");
  pm_rig* rig = nullptr;
  pm_error err;
  REQUIRE(pm_rig_load(bytes.data(), bytes.size(), &rig, &err) == PM_OK);
  pm_rig* const first = rig;
  CHECK(pm_rig_load(bytes.data(), bytes.size(), &rig, &err) == PM_ERROR_INVALID_ARGUMENT);
  CHECK(std::string(err.message).find("not NULL") != std::string::npos);
  CHECK(rig == first);  // untouched, still usable
  pm_rig_info info;
  pm_rig_get_info(rig, &info);
  CHECK(info.vertex_count == 4);
  pm_rig_free(rig);
}

TEST_CASE("drawn rigs carry each pose's canvas, a negative canvas is refused") {
  const Rig pip = LoadTestRig("pip");
  for (std::uint32_t i = 0; i < pip.pose_count(); ++i) {
    const DrawingCanvas c = pip.pose_canvas(i);
    CHECK(c.width == 256);  // the PNGs rasterised from Pip's SVGs
    CHECK(c.height == 256);
    CHECK(c.pivot_x == 0);  // rig units are PNG pixels, y up, from its corner
    CHECK(c.pivot_y == 0);
  }
  // The uvs follow: u = (x + pivot_x) / width, v = (pivot_y - y) / height.
  const Span<const float> uv = pip.uvs(0);
  const Span<const double> xy = pip.pose_positions(0);
  CHECK(std::fabs(uv[0] - float(xy[0] / 256)) < 1e-6);
  CHECK(std::fabs(uv[1] - float(-xy[1] / 256)) < 1e-6);
  const Rig snake = LoadTestRig("snake");  // a mesh rig: no drawings
  CHECK(snake.pose_canvas(0).width == 0);

  std::vector<unsigned char> bytes = TestRigBytes("pip");
  const std::size_t at = SectionOffset(bytes, format::kCanvases);
  REQUIRE(at != 0);
  bytes = WithValue(bytes, at + 8, -1.0);  // pose 0's height
  Rig rig;
  Error err;
  CHECK_FALSE(LoadRig(bytes.data(), bytes.size(), &rig, &err));
  CHECK(std::string(err.message).find("canvas of pose 0") != std::string::npos);
}

TEST_CASE("the drawings' folder is read where META says it is, and refused where it is not") {
  const Rig pip = LoadTestRig("pip");  // baked by the CLI from build/<preset>/assets/pip
  CHECK(std::string(pip.drawing_folder().data, pip.drawing_folder().size).find("assets/pip") != std::string::npos);
  Rig moved = LoadTestRig("pip");
  Rig owner = std::move(moved);
  CHECK(moved.drawing_folder().size == 0);
  CHECK(owner.drawing_folder().size == pip.drawing_folder().size);
  // META's flags word is its eighth u32.
  auto with_flags = [](const char* name, std::uint32_t set, std::uint32_t clear) {
    std::vector<unsigned char> bytes = TestRigBytes(name);
    const std::size_t at = SectionOffset(bytes, format::kMeta) + 28;
    std::uint32_t flags = 0;
    std::memcpy(&flags, bytes.data() + at, 4);
    return WithValue(bytes, at, (flags | set) & ~clear);
  };
  Rig rig;
  Error err;
  std::vector<unsigned char> bytes = with_flags("pip", 0, format::kMetaFlagDrawingFolder);
  CHECK_FALSE(LoadRig(bytes.data(), bytes.size(), &rig, &err));
  CHECK(std::string(err.message).find("string table has trailing bytes") != std::string::npos);
  bytes = with_flags("snake", format::kMetaFlagDrawingFolder, 0);  // no folder stored
  CHECK_FALSE(LoadRig(bytes.data(), bytes.size(), &rig, &err));
  CHECK(std::string(err.message).find("string table truncated at string 12") != std::string::npos);  // 2 x 5 + 2
}

TEST_CASE("a format 1.0 rig (no CANV section) still loads") {
  std::vector<unsigned char> bytes = TestRigBytes("snake");  // a mesh rig: written without CANV
  REQUIRE(SectionOffset(bytes, format::kCanvases) == 0);
  const std::uint16_t minor_zero = 0;
  std::memcpy(bytes.data() + format::kOffVersionMinor, &minor_zero, 2);  // the header is outside the checksum
  Rig rig;
  Error err;
  REQUIRE_MESSAGE(LoadRig(bytes.data(), bytes.size(), &rig, &err), err.message);
  CHECK(rig.format_minor() == 0);
  CHECK(rig.pose_canvas(0).width == 0);
}

TEST_CASE("image references from a rig file must stay inside the folder of drawings") {
  auto inside = [](const char* s) {
    return posemorph::ImageReferenceStaysInside(posemorph::StringView{s, std::strlen(s)});
  };
  for (const char* bad : {"", "/etc/passwd", "..", "../a.png", "a/../../b.png", "x/..", "a\\b.png", "c:/x.png",
                          "https://example.com/a.png", "a\x1b[31m.png", "a\x7f.png"})
    CHECK_FALSE(inside(bad));
  for (const char* good : {"rest.png", "poses/rest.png", "a..b.png", "..a.png", "./rest.png", "a/b/c.png"})
    CHECK(inside(good));
  CHECK_FALSE(posemorph::ImageReferenceStaysInside(posemorph::StringView{nullptr, 3}));
  // A reference is its bytes, not a C string: an embedded NUL is a control character.
  CHECK_FALSE(posemorph::ImageReferenceStaysInside(posemorph::StringView{"a\0b.png", 7}));
}
