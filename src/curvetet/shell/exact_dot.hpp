#pragma once
// Exact sign of ((b - a) x (c - a)) . (q - p): the side of the plane of
// triangle (a, b, c) the vector q - p points to. Floating filter, GMP
// rational fallback (inputs are doubles, so the result is exact).
#include <Eigen/Core>

namespace curvetet::shell {

int normal_dot_sign(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                    const Eigen::Vector3d& p, const Eigen::Vector3d& q);

} // namespace curvetet::shell
