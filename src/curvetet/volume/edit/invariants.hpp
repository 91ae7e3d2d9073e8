#pragma once
// The invariants every operation of the curved optimization must keep, as
// one list of named checks (STYLE.md 2), and the reasons an operation is
// rejected (counted per reason in the report, STYLE.md 4).
//
// Topological reasons are decided by the operations (operations.hpp) before
// anything is built; the checks here run on the tets a transaction added:
//   energy           max AMIPS of every new tet < StarLimits::max_amips
//   scaled_jacobian  min scaled Jacobian of every new tet >= StarLimits::min_scaled_jacobian
//   certificate      highorder::certify_tet proves det J > 0 (undecided = rejected)
// in that order (cheapest first). The boundary and feature curves are kept
// structurally: their vertices are frozen and their nodes pinned (tet_editor.hpp).
#include "curvetet/volume/edit/tet_editor.hpp"

#include <array>
#include <optional>
#include <string>

namespace curvetet::volume::edit {

enum class Reject { frozen, region, boundary_edge, link_condition, duplicate_entity, energy, scaled_jacobian, certificate };
constexpr int kRejectReasons = 8;
std::string to_string(Reject r);

using RejectCounts = std::array<long, kRejectReasons>;

struct StarLimits {
  double max_amips = 0;           // strict upper bound
  double min_scaled_jacobian = 0; // inclusive lower bound
};

// The first invariant a new tet of the open transaction breaks, if any.
std::optional<Reject> check_new_tets(const TetEditor& editor, const StarLimits& limits);

} // namespace curvetet::volume::edit
