#pragma once
// Exact sign of ((b - a) x (c - a)) . (q - p): the side of the plane of
// triangle (a, b, c) the vector q - p points to. Floating filter, GMP
// rational fallback (inputs are doubles, so the result is exact).
//
// orient3d_value: det[b - a, c - a, d - a] (the signed volume x 6 of tet
// a, b, c, d, same sign convention as geometry::orient3d) with a small
// RELATIVE error (<= 1e-12), exactly 0 iff the four points are coplanar
// (barring underflow below 1e-308).
// Plain double evaluation loses all relative accuracy near coplanarity (a
// point 1e-19 off a plane may come out on the wrong side); this one falls
// back to exact arithmetic there. For measures that must stay accurate on
// nearly degenerate data (shell image areas), not for decisions.
#include <Eigen/Core>

namespace curvetet::shell {

int normal_dot_sign(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                    const Eigen::Vector3d& p, const Eigen::Vector3d& q);

double orient3d_value(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                      const Eigen::Vector3d& d);

// Exact sign of ((b - a) x (c - a)) . ((e - d) x (f - d)): whether two
// triangles' normals point to the same side (rationals; for the few
// triangles a feature straightening reshapes).
int normals_dot_sign(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                     const Eigen::Vector3d& d, const Eigen::Vector3d& e, const Eigen::Vector3d& f);

} // namespace curvetet::shell
