// SPDX-License-Identifier: MIT
// Where the character stands and which way it faces (PLCE, format 1.11;
// loader.h): the section's anchor and facing, checked, or the default
// anchor (the bottom centre of pose 0's bounds, facing right).
#include <cmath>

#include "loader.h"
#include "posemorph/format/record_codec.h"

namespace posemorph {

using namespace detail::load;  // NOLINT(google-build-using-namespace): the loader's own types

bool RigLoader::ReadPlacement(const Sources& s, bool nested, Rig* rig, Error* err) {
  if (s.placement) {
    if (nested) return Fail(err, ErrorCode::kBadLayout, "PLCE in an attachment's rig; only the character has one");
    const auto p = fmt::DecodeRecord<fmt::PlacementRecord>(s.placement);
    if (!(std::fabs(p.anchor_x) <= fmt::kMaxAnchor) || !(std::fabs(p.anchor_y) <= fmt::kMaxAnchor))
      return Fail(err, ErrorCode::kBadValue, "PLCE: the anchor (%g, %g) is not finite or beyond +-1e9", p.anchor_x,
                  p.anchor_y);
    if ((p.flags & ~fmt::kPlacementFacingLeft) != 0 || p.reserved != 0)
      return Fail(err, ErrorCode::kBadValue, "PLCE: unknown flags 0x%x or a reserved field that is not zero", p.flags);
    rig->anchor_x_ = p.anchor_x, rig->anchor_y_ = p.anchor_y;
    rig->facing_left_ = (p.flags & fmt::kPlacementFacingLeft) != 0;
    rig->anchor_given_ = true;
    return true;
  }
  const Span<const double> p = rig->pose_positions(0);
  double x0 = HUGE_VAL, x1 = -HUGE_VAL, y0 = HUGE_VAL;
  for (std::size_t i = 0; i < p.size; i += 2)
    x0 = std::fmin(x0, p[i]), x1 = std::fmax(x1, p[i]), y0 = std::fmin(y0, p[i + 1]);
  rig->anchor_x_ = p.size ? (x0 + x1) / 2 : 0;
  rig->anchor_y_ = p.size ? y0 : 0;
  return true;
}

}  // namespace posemorph
