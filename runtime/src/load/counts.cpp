// SPDX-License-Identifier: MIT
// META, bounded before its counts size anything, and the sections whose
// sizes the counts imply.
#include "loader.h"

#include <cmath>

namespace posemorph {

using namespace detail::load;  // NOLINT(google-build-using-namespace): the loader's own types

// META: counts, bounded before they size anything.
bool RigLoader::ReadCounts(Parser& parser, Counts* c, Error* err) {
  const unsigned char* p = nullptr;
  if (!parser.Get(fmt::kMeta, fmt::kMetaSize, &p)) return false;
  fmt::Meta& meta = c->meta;
  meta = fmt::DecodeRecord<fmt::Meta>(p);
  const std::uint64_t V = meta.vertex_count, T = meta.triangle_count, N = meta.pose_count, P = meta.path_count,
                      nnz = meta.factor_nonzeros;
  if (V < 3 || V > fmt::kMaxVertices)
    return Fail(err, V < 3 ? ErrorCode::kBadValue : ErrorCode::kTooLarge, "vertex count %llu outside 3..%u",
                (unsigned long long)V, fmt::kMaxVertices);
  if (T < 1 || T > fmt::kMaxTriangles)
    return Fail(err, T < 1 ? ErrorCode::kBadValue : ErrorCode::kTooLarge, "triangle count %llu outside 1..%u",
                (unsigned long long)T, fmt::kMaxTriangles);
  if (N < 2 || N > fmt::kMaxPoses)
    return Fail(err, N < 2 ? ErrorCode::kBadValue : ErrorCode::kTooLarge, "pose count %llu outside 2..%u",
                (unsigned long long)N, fmt::kMaxPoses);
  if (P > fmt::kMaxPaths)
    return Fail(err, ErrorCode::kTooLarge, "path count %llu above %u", (unsigned long long)P, fmt::kMaxPaths);
  if (meta.grid_cells_x < 1 || meta.grid_cells_y < 1 || meta.grid_cells_x > fmt::kMaxGridCells ||
      meta.grid_cells_y > fmt::kMaxGridCells)
    return Fail(err, ErrorCode::kTooLarge, "weight grid %ux%u outside 1..%u cells per axis", meta.grid_cells_x,
                meta.grid_cells_y, fmt::kMaxGridCells);
  if (nnz > fmt::kMaxFactorNonzeros)
    return Fail(err, ErrorCode::kTooLarge, "factor has %llu nonzeros, above %u", (unsigned long long)nnz,
                fmt::kMaxFactorNonzeros);
  if ((meta.flags &
       ~(fmt::kMetaFlagHasUVs | fmt::kMetaFlagGridCentres | fmt::kMetaFlagCompact | fmt::kMetaFlagNearestFilter |
         fmt::kMetaFlagDrawingFolder | fmt::kMetaFlagParts | fmt::kMetaFlagPartPoseOrders | fmt::kMetaFlagEvents)) != 0)
    return Fail(err, ErrorCode::kBadVersion, "unknown META flags 0x%x", meta.flags);
  if (!std::isfinite(meta.grid_origin_x) || !std::isfinite(meta.grid_origin_y) || !std::isfinite(meta.grid_cell_size) ||
      !(meta.grid_cell_size > 0) || !std::isfinite(meta.grid_cell_size * meta.grid_cells_x) ||
      !std::isfinite(meta.grid_cell_size * meta.grid_cells_y) ||
      !std::isfinite(meta.grid_origin_x + meta.grid_cell_size * meta.grid_cells_x) ||
      !std::isfinite(meta.grid_origin_y + meta.grid_cell_size * meta.grid_cells_y))
    return Fail(err, ErrorCode::kBadValue, "weight grid geometry is not finite and positive");
  if (!std::isfinite(meta.default_sigma) || meta.default_sigma < 0 || meta.default_sigma > 1)
    return Fail(err, ErrorCode::kBadValue, "default sigma %g outside [0, 1]", meta.default_sigma);
  if (!std::isfinite(meta.rig_size) || !(meta.rig_size > 0))
    return Fail(err, ErrorCode::kBadValue, "rig size %g is not finite and positive", meta.rig_size);
  c->V = V, c->T = T, c->N = N, c->P = P, c->nnz = nnz;
  c->n = V - 1;
  if (meta.flags & fmt::kMetaFlagParts) {
    const Section* parts = parser.table.Find(fmt::kParts);
    if (!parts) return Fail(err, ErrorCode::kBadLayout, "META says the rig has parts, but there is no PART section");
    if (parts->size % fmt::kPartEntrySize != 0 || parts->size < fmt::kPartEntrySize ||
        parts->size > std::uint64_t(fmt::kMaxParts) * fmt::kPartEntrySize)
      return Fail(err, ErrorCode::kBadLayout, "PART section of %llu bytes: 1..%u entries of %u bytes",
                  (unsigned long long)parts->size, fmt::kMaxParts, fmt::kPartEntrySize);
    c->parts = parts->size / fmt::kPartEntrySize;
  } else if (parser.table.Find(fmt::kParts)) {
    return Fail(err, ErrorCode::kBadLayout, "PART section present but META says the rig has no parts");
  }
  c->part_pose_orders = (meta.flags & fmt::kMetaFlagPartPoseOrders) != 0;
  if (c->part_pose_orders && !c->parts)
    return Fail(err, ErrorCode::kBadLayout, "META says the draw order changes with the pose, but the rig has no parts");
  if (!c->part_pose_orders && parser.table.Find(fmt::kPartPoseOrders))
    return Fail(err, ErrorCode::kBadLayout, "PORD section present but META says the draw order is fixed");
  if (meta.flags & fmt::kMetaFlagEvents) {
    const Section* events = parser.table.Find(fmt::kEvents);
    if (!events)
      return Fail(err, ErrorCode::kBadLayout, "META says the paths have events, but there is no EVNT section");
    if (events->size % fmt::kEventEntrySize != 0 || events->size < fmt::kEventEntrySize ||
        events->size > std::uint64_t(fmt::kMaxEvents) * fmt::kEventEntrySize)
      return Fail(err, ErrorCode::kBadLayout, "EVNT section of %llu bytes: 1..%u entries of %u bytes",
                  (unsigned long long)events->size, fmt::kMaxEvents, fmt::kEventEntrySize);
    if (P == 0) return Fail(err, ErrorCode::kBadLayout, "EVNT section present but the rig has no paths");
    c->events = events->size / fmt::kEventEntrySize;
  } else if (parser.table.Find(fmt::kEvents)) {
    return Fail(err, ErrorCode::kBadLayout, "EVNT section present but META says the paths have no events");
  }
  c->strings = 2 * N + P + ((meta.flags & fmt::kMetaFlagDrawingFolder) ? 1 : 0) + c->parts * (1 + N) + c->events;
  c->grid_corners = std::uint64_t(meta.grid_cells_x + 1) * (meta.grid_cells_y + 1);
  c->grid_centres = (meta.flags & fmt::kMetaFlagGridCentres) ? std::uint64_t(meta.grid_cells_x) * meta.grid_cells_y : 0;
  c->grid_vertices = c->grid_corners + c->grid_centres;
  c->has_uvs = (meta.flags & fmt::kMetaFlagHasUVs) != 0;
  c->compact = (meta.flags & fmt::kMetaFlagCompact) != 0;
  return true;
}

// Sections with sizes implied by the counts; the compact encoding's layout;
// the path table's key count; the string table.
bool RigLoader::FindSections(const unsigned char* bytes, const Header& h, Parser& parser, const Counts& c, Sources* s,
                             Error* err) {
  const std::uint64_t V = c.V, T = c.T, N = c.N, P = c.P, n = c.n, nnz = c.nnz;
  if (!c.compact &&
      (!parser.Get(fmt::kTriangles, T * 12, &s->tris) || !parser.Get(fmt::kPosePositions, N * V * 16, &s->poses) ||
       !parser.Get(fmt::kPoseCentroids, N * 16, &s->cents) || !parser.Get(fmt::kVertexMasses, V * 8, &s->masses) ||
       !parser.Get(fmt::kGradients, T * 48, &s->grads) || !parser.Get(fmt::kAngles, T * N * 8, &s->angles) ||
       !parser.Get(fmt::kStretches, T * N * 24, &s->stretches) || !parser.Get(fmt::kPermutation, n * 4, &s->perm) ||
       !parser.Get(fmt::kFactorColumns, (n + 1) * 4, &s->lcol) || !parser.Get(fmt::kFactorRows, nnz * 4, &s->lrow) ||
       !parser.Get(fmt::kFactorValues, nnz * 8, &s->lval) || !parser.Get(fmt::kFactorInvDiagonal, n * 8, &s->dinv) ||
       !parser.Get(fmt::kWeightGrid, c.grid_vertices * N * 8, &s->wgrid)))
    return false;
  if (!parser.Get(fmt::kPosePoints, N * 16, &s->points) || !parser.Get(fmt::kPaths, P * fmt::kPathEntrySize, &s->paths))
    return false;
  s->packed_counts = detail::CompactCounts{
      V, T, N, n, nnz, c.meta.grid_cells_x, c.meta.grid_cells_y, c.grid_centres > 0, h.file_size, h.minor};
  if (c.compact) {
    auto bytes_of = [&](std::uint32_t tag) {
      const Section* section = parser.table.Find(tag);
      return section ? detail::SectionBytes{bytes + section->offset, section->size} : detail::SectionBytes{};
    };
    if (!detail::ReadCompactLayout(bytes_of(fmt::kQuantPositions), bytes_of(fmt::kQuantTriangles),
                                   bytes_of(fmt::kQuantPermutation), bytes_of(fmt::kQuantTurns),
                                   bytes_of(fmt::kQuantGrid), bytes_of(fmt::kAffineUVs), s->packed_counts, &s->packed,
                                   err))
      return false;
    s->affine_uvs = s->packed.has_affine_uvs;
    if (s->affine_uvs && !c.has_uvs)
      return Fail(err, ErrorCode::kBadLayout, "QUVA section present but META says no uvs");
    if (s->affine_uvs && parser.table.Find(fmt::kUVs))
      return Fail(err, ErrorCode::kBadLayout, "both QUVA and UVS present; a rig stores its uvs once");
  }
  if (c.has_uvs && !s->affine_uvs && !parser.Get(fmt::kUVs, N * V * 8, &s->uvs)) return false;
  if (parser.table.Find(fmt::kCanvases) && !parser.Get(fmt::kCanvases, N * 32, &s->canvases)) return false;
  if (parser.table.Find(fmt::kPlacement) && !parser.Get(fmt::kPlacement, fmt::PlacementRecord::kSize, &s->placement))
    return false;
  if (c.parts && !parser.Get(fmt::kParts, c.parts * fmt::kPartEntrySize, &s->parts)) return false;
  if (c.part_pose_orders && !parser.Get(fmt::kPartPoseOrders, N * c.parts * 4, &s->pose_orders)) return false;
  if (c.events && !parser.Get(fmt::kEvents, c.events * fmt::kEventEntrySize, &s->events)) return false;
  if (!c.has_uvs && parser.table.Find(fmt::kUVs))
    return Fail(err, ErrorCode::kBadLayout, "UVS section present but META says none");
  std::uint64_t key_total = 0;
  for (std::uint64_t i = 0; i < P; ++i) {
    const auto entry = fmt::DecodeEntry<fmt::PathEntry>(s->paths, i);
    const std::uint32_t keys = entry.key_count, flags = entry.flags;
    if (keys < 1) return Fail(err, ErrorCode::kBadValue, "path %llu has no keys", (unsigned long long)i);
    if ((flags & ~(fmt::kPathFlagLoop | (0xFFu << fmt::kPathInterpolationShift))) != 0 ||
        (flags >> fmt::kPathInterpolationShift) > std::uint32_t(PathInterpolation::kCatmullRom))
      return Fail(err, ErrorCode::kBadValue, "path %llu has unknown flags 0x%x", (unsigned long long)i, flags);
    key_total += keys;
    if (key_total > fmt::kMaxPathKeys)
      return Fail(err, ErrorCode::kTooLarge, "paths hold more than %u keys", fmt::kMaxPathKeys);
  }
  s->key_total = key_total;
  if (!parser.Get(fmt::kPathKeys, key_total * 24, &s->pkeys)) return false;
  const Section* strings_section = parser.table.Find(fmt::kStrings);
  if (!strings_section) return Fail(err, ErrorCode::kBadLayout, "missing section STRS");
  if (strings_section->size > fmt::kMaxStringBytes)
    return Fail(err, ErrorCode::kTooLarge, "string table above %u bytes", fmt::kMaxStringBytes);
  s->strs = bytes + strings_section->offset;
  s->strings_size = strings_section->size;
  return true;
}

}  // namespace posemorph
