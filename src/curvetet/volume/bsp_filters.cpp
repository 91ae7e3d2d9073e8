#include "curvetet/volume/bsp_filters.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <limits>

namespace curvetet::volume::exact {
namespace {

constexpr double kUnit = std::numeric_limits<double>::epsilon() / 2;
constexpr double kTiny = std::numeric_limits<double>::denorm_min();

double max_abs(const Eigen::Vector3d& v) { return v.cwiseAbs().maxCoeff(); }

int sign_beyond(double value, double bound) {
  if (value > bound) return 1;
  if (value < -bound) return -1;
  return 0;
}

} // namespace

int side_filter(const Eigen::Vector3d& nd, double nd_l1, const Eigen::Vector3d& a, const Eigen::Vector3d& xd,
                double factor) {
  const double s = nd.dot(xd - a);
  const double m = std::max(max_abs(xd), max_abs(a));
  return sign_beyond(s, factor * kUnit * nd_l1 * m + 16 * kTiny * (nd_l1 + 1));
}

int orient_in_plane_filter(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& x,
                           const Eigen::Vector3d& nd, double nd_l1, double factor) {
  const Eigen::Vector3d u = q - p, w = x - p;
  const double value = u.cross(w).dot(nd);
  const double m = std::max({max_abs(p), max_abs(q), max_abs(x)});
  const double a = max_abs(u), b = max_abs(w);
  return sign_beyond(value, factor * kUnit * nd_l1 * (m * (a + b) + a * b) + 64 * kTiny * (nd_l1 + 1));
}

int not_collinear_filter(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& x,
                         double factor) {
  const Eigen::Vector3d u = q - p, w = x - p;
  const double m = std::max({max_abs(p), max_abs(q), max_abs(x)});
  const double a = max_abs(u), b = max_abs(w);
  return max_abs(u.cross(w)) > factor * kUnit * (m * (a + b) + a * b) + 64 * kTiny ? 1 : 0;
}

double approximation_pad(double max_abs_coordinate) { return 6 * kUnit * max_abs_coordinate + 4 * kTiny; }

} // namespace curvetet::volume::exact
