// SPDX-License-Identifier: MIT
// What the arena holds, checked: strings, paths, indices, parts, the
// factor's structure, and every number finite and within the format's limits.
#include "loader.h"

#include <cmath>
#include <cstring>

namespace posemorph {

using namespace detail::load;  // NOLINT(google-build-using-namespace): the loader's own types

// Strings: u32 length + bytes, one after another, exactly filling STRS.
bool RigLoader::ReadStrings(const Counts& c, const Scratch& scratch, Rig* rig, Error* err) {
  const Span<const char> chars = scratch.chars;
  const std::uint64_t string_count = c.strings;
  std::uint64_t at = 0;
  for (std::uint64_t i = 0; i < string_count; ++i) {
    if (chars.size - at < 4)
      return Fail(err, ErrorCode::kBadValue, "string table truncated at string %llu", (unsigned long long)i);
    std::uint32_t len = 0;
    fmt::FieldDecoder{reinterpret_cast<const unsigned char*>(chars.data + at)}(len);
    at += 4;
    if (len > chars.size - at)
      return Fail(err, ErrorCode::kBadValue, "string %llu runs past the string table", (unsigned long long)i);
    scratch.strings[i] = StringView{chars.data + at, len};
    at += len;
  }
  if (at != chars.size) return Fail(err, ErrorCode::kBadValue, "string table has trailing bytes");
  rig->strings_ = {scratch.strings, std::size_t(string_count)};
  return true;
}

// Paths: finite keys, strictly increasing times.
bool RigLoader::ReadPaths(const Counts& c, const Sources& s, const Scratch& scratch, Rig* rig, Error* err) {
  std::uint64_t key_at = 0;
  for (std::uint64_t i = 0; i < c.P; ++i) {
    const auto entry = fmt::DecodeEntry<fmt::PathEntry>(s.paths, i);
    const std::uint32_t count = entry.key_count, flags = entry.flags;
    PathView& view = scratch.path_views[i];
    view.name = scratch.strings[2 * c.N + i];
    view.events = {};  // ReadEvents sets a path's run
    view.loop = (flags & fmt::kPathFlagLoop) != 0;
    view.interpolation = PathInterpolation(flags >> fmt::kPathInterpolationShift);
    view.keys = scratch.keys.subspan(std::size_t(key_at * 3), std::size_t(count) * 3);
    key_at += count;
    if (!CheckFinite(view.keys, "path key", err, fmt::kMaxPathValue)) return false;
    for (std::uint32_t k = 1; k < count; ++k)
      if (!(view.keys[3 * k] > view.keys[3 * (k - 1)]))
        return Fail(err, ErrorCode::kBadValue, "path %llu: key times not strictly increasing at key %u",
                    (unsigned long long)i, k);
  }
  rig->paths_ = {scratch.path_views, std::size_t(c.P)};
  return true;
}

// Events (format 1.8): each on a path, at a finite time within the path's
// keys, sorted by path then time; their names end STRS. Each path's run
// becomes its PathView::events.
bool RigLoader::ReadEvents(const Counts& c, const Sources& s, const Scratch& scratch, Rig* rig, Error* err) {
  if (!c.events) return true;
  const std::uint64_t first_name = c.strings - c.events;
  std::uint64_t run_start = 0;
  for (std::uint64_t i = 0; i < c.events; ++i) {
    const auto entry = fmt::DecodeEntry<fmt::EventEntry>(s.events, i);
    EventView& view = scratch.event_views[i];
    view.name = scratch.strings[first_name + i];
    view.path = entry.path;
    view.time = entry.time;
    if (entry.path >= c.P)
      return Fail(err, ErrorCode::kBadValue, "event %llu names path %u; the rig has %llu", (unsigned long long)i,
                  entry.path, (unsigned long long)c.P);
    if (entry.reserved != 0)
      return Fail(err, ErrorCode::kBadValue, "event %llu: reserved field is not zero", (unsigned long long)i);
    const PathView& path = scratch.path_views[entry.path];
    if (!std::isfinite(entry.time) || !(entry.time >= path.start_time() && entry.time <= path.end_time()))
      return Fail(err, ErrorCode::kBadValue, "event %llu at time %g, outside its path %u's keys [%g, %g]",
                  (unsigned long long)i, entry.time, entry.path, path.start_time(), path.end_time());
    if (view.name.size == 0) return Fail(err, ErrorCode::kBadValue, "event %llu has no name", (unsigned long long)i);
    if (i > 0) {
      const EventView& before = scratch.event_views[i - 1];
      if (entry.path < before.path || (entry.path == before.path && !(entry.time >= before.time)))
        return Fail(err, ErrorCode::kBadValue, "event %llu is out of order (events are sorted by path, then time)",
                    (unsigned long long)i);
      if (entry.path != before.path) run_start = i;
    }
    scratch.path_views[entry.path].events = {scratch.event_views + run_start, std::size_t(i - run_start + 1)};
  }
  rig->events_ = {scratch.event_views, std::size_t(c.events)};
  return true;
}

// Triangles name three distinct vertices in range; the permutation is one.
bool RigLoader::CheckIndices(const Counts& c, const Scratch& scratch, const Rig& rig, Error* err) {
  const std::uint64_t V = c.V, n = c.n;
  for (std::uint64_t t = 0; t < c.T; ++t) {
    const std::uint32_t a = rig.triangles_[3 * t], b = rig.triangles_[3 * t + 1], d = rig.triangles_[3 * t + 2];
    if (a >= V || b >= V || d >= V)
      return Fail(err, ErrorCode::kBadValue, "triangle %llu has a vertex index >= %llu", (unsigned long long)t,
                  (unsigned long long)V);
    if (a == b || b == d || a == d)
      return Fail(err, ErrorCode::kBadValue, "triangle %llu repeats a vertex", (unsigned long long)t);
  }
  std::memset(scratch.seen, 0, n);
  for (std::uint64_t k = 0; k < n; ++k) {
    const std::uint32_t v = rig.solve_.order[k];
    if (v >= n || scratch.seen[v])
      return Fail(err, ErrorCode::kBadValue, "permutation is not a permutation (entry %llu)", (unsigned long long)k);
    scratch.seen[v] = 1;
  }
  return true;
}

// Parts (format 1.6): they tile the triangles in order, none empty, no
// reserved bits; the draw sequence sorts them by draw order, then index.
bool RigLoader::ReadParts(const Counts& c, const Scratch& scratch, Rig* rig, Error* err) {
  if (!c.parts) return true;
  const Span<const std::uint32_t> table = rig->part_table_;
  std::uint64_t next = 0;
  for (std::uint64_t p = 0; p < c.parts; ++p) {
    const std::uint32_t first = table[4 * p], count = table[4 * p + 1];
    if (first != next || count == 0 || count > c.T - next)
      return Fail(err, ErrorCode::kBadValue, "part %llu covers triangles %u..+%u; parts must tile 0..%llu in order",
                  (unsigned long long)p, first, count, (unsigned long long)c.T);
    if (table[4 * p + 3] != 0)
      return Fail(err, ErrorCode::kBadValue, "part %llu: reserved field set", (unsigned long long)p);
    next += count;
  }
  if (next != c.T)
    return Fail(err, ErrorCode::kBadValue, "the parts cover %llu of %llu triangles", (unsigned long long)next,
                (unsigned long long)c.T);
  // Insertion sort (at most kMaxParts): stable, so ties keep the part order.
  // One sequence, or one per pose (PORD).
  const std::uint32_t M = std::uint32_t(c.parts);
  const std::uint64_t sequences = rig->part_pose_orders_.empty() ? 1 : c.N;
  for (std::uint64_t i = 0; i < sequences; ++i) {
    const auto order_of = [&](std::uint32_t p) {
      return std::int32_t(rig->part_pose_orders_.empty() ? table[4 * p + 2] : rig->part_pose_orders_[i * M + p]);
    };
    std::uint32_t* sequence = scratch.draw_sequence + i * M;
    for (std::uint32_t p = 0; p < M; ++p) {
      std::uint32_t at = p;
      const std::int32_t order = order_of(p);
      while (at > 0 && order_of(sequence[at - 1]) > order) {
        sequence[at] = sequence[at - 1];
        --at;
      }
      sequence[at] = p;
    }
  }
  if (!rig->part_pose_orders_.empty())
    for (std::uint32_t p = 0; p < M; ++p)
      if (rig->part_pose_orders_[p] != table[4 * p + 2])
        return Fail(err, ErrorCode::kBadValue, "part %u: PART's draw order %d is not pose 0's in PORD (%d)", p,
                    std::int32_t(table[4 * p + 2]), std::int32_t(rig->part_pose_orders_[p]));
  rig->draw_sequence_ = {scratch.draw_sequence, std::size_t(sequences * M)};
  return true;
}

// L strictly lower, columns in order, rows increasing within a column (the
// triangular solves then touch only rows j < i < n); D^-1 positive and finite.
bool RigLoader::CheckFactor(const Counts& c, const Rig& rig, Error* err) {
  const std::uint64_t n = c.n, nnz = c.nnz;
  const auto& col = rig.solve_.col_start;
  if (col[0] != 0 || col[n] != nnz)
    return Fail(err, ErrorCode::kBadValue, "factor column pointers do not span the nonzeros");
  for (std::uint64_t j = 0; j < n; ++j) {
    if (col[j] > col[j + 1])
      return Fail(err, ErrorCode::kBadValue, "factor column %llu has negative length", (unsigned long long)j);
    for (std::uint32_t q = col[j]; q < col[j + 1]; ++q) {
      const std::uint32_t r = rig.solve_.row[q];
      if (r <= j || r >= n || (q > col[j] && r <= rig.solve_.row[q - 1]))
        return Fail(err, ErrorCode::kBadValue, "factor entry %u (column %llu) has row %u out of order or range", q,
                    (unsigned long long)j, r);
    }
  }
  return true;
}

// Every number finite and within the format's limits.
bool RigLoader::CheckNumbers(const Rig& rig, Error* err) {
  for (std::size_t j = 0; j < rig.solve_.inv_diagonal.size; ++j)
    if (!(rig.solve_.inv_diagonal[j] > 0) || !(rig.solve_.inv_diagonal[j] <= fmt::kMaxMagnitude))
      return Fail(err, ErrorCode::kBadValue, "factor diagonal %llu is not positive and at most %g",
                  (unsigned long long)j, fmt::kMaxMagnitude);
  if (!CheckFinite(rig.pose_positions_, "pose positions", err) || !CheckFinite(rig.pose_points_, "pose points", err) ||
      !CheckFinite(rig.pose_centroids_, "pose centroids", err) ||
      !CheckFinite(rig.vertex_masses_, "vertex masses", err) || !CheckFinite(rig.gradients_, "gradients", err) ||
      !CheckFinite(rig.angles_, "angles", err, fmt::kMaxAngle) ||
      !CheckFinite(rig.stretches_, "stretches", err, fmt::kMaxStretch) ||
      !CheckFinite(rig.solve_.value, "factor values", err) ||
      !CheckFinite(rig.grid_.weights, "weight grid", err, fmt::kMaxGridWeight) ||
      !CheckFinite(rig.grid_.centre_weights, "weight grid centres", err, fmt::kMaxGridWeight) ||
      !CheckFinite(rig.canvases_, "canvases", err))
    return false;
  for (std::size_t i = 0; i < rig.canvases_.size; i += 4)
    if (rig.canvases_[i] < 0 || rig.canvases_[i + 1] < 0)
      return Fail(err, ErrorCode::kBadValue, "canvas of pose %zu has a negative size", i / 4);
  for (std::size_t i = 0; i < rig.uvs_.size; ++i)
    if (!std::isfinite(rig.uvs_[i])) return Fail(err, ErrorCode::kBadValue, "uv[%zu] is not finite", i);
  return true;
}

}  // namespace posemorph
