#pragma once
// The shape of an order-P tet in the quality convention (highorder/quality.hpp:
// max AMIPS and min scaled Jacobian over the order-2P lattice with corners),
// evaluated with an early exit: the operations' previews only need to know
// whether a new tet beats a bound, and most candidates fail at a corner.
#include <Eigen/Core>

#include <limits>
#include <optional>

namespace curvetet::volume::edit {

struct TetShape {
  double max_amips = 0;
  double min_scaled_jacobian = 0;
};

// The shape of a tet with a sample whose Jacobian is not positive.
inline constexpr TetShape kInvertedShape{std::numeric_limits<double>::infinity(),
                                         -std::numeric_limits<double>::infinity()};

// The shape, or nullopt as soon as a sample's AMIPS reaches `bound`
// (corners first). Straight tets (nodes on their corners' affine map to
// 1e-12 of the size, as tet_quality decides) take one evaluation.
std::optional<TetShape> tet_shape(int order, const Eigen::Vector3d* nodes,
                                  double bound = std::numeric_limits<double>::infinity());

} // namespace curvetet::volume::edit
