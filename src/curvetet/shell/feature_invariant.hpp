#pragma once
// The feature rules as one entry of the star invariant list (paper App. B,
// §5; DESIGN.md §2 item 6). On a shell without features it always holds.
//
// Holds when plan_feature_edit(c) allows c (no flip of a feature edge;
// collapse only along a chain, from an interior chain vertex into its chain
// neighbour, keeping >= 1 edge per open chain and >= 3 per closed one;
// corners never move nor disappear; a chain vertex moves or is created only
// at an input vertex of its chain strictly between its chain neighbours)
// and every feature edge of the new faces keeps the arc-length
// correspondence within epsilon: each input chain vertex in its range is
// closer than epsilon to the middle edge (MiddleFit::evaluate) at its
// arc-length parameter. Runs after CurvedFit (it evaluates the fitted
// middle) and needs c.geoms.
#include "curvetet/shell/star_invariants.hpp"

#include <memory>

namespace curvetet::shell {

std::unique_ptr<StarInvariant> make_feature_invariant();

} // namespace curvetet::shell
