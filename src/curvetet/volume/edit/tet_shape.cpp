#include "curvetet/volume/edit/tet_shape.hpp"

#include "curvetet/highorder/bernstein.hpp"
#include "curvetet/highorder/conforming_nodes.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/highorder/quality.hpp"

#include <algorithm>
#include <array>
#include <memory>
#include <mutex>
#include <vector>

namespace curvetet::volume::edit {
namespace {

// Lagrange gradients (nodes x 3) at the convention's samples, the four
// corners first.
const std::vector<Eigen::MatrixXd>& sample_gradients(int order) {
  static std::unique_ptr<std::vector<Eigen::MatrixXd>> cache[highorder::kMaxOrder + 1];
  static std::once_flag once[highorder::kMaxOrder + 1];
  std::call_once(once[order], [order] {
    auto g = std::make_unique<std::vector<Eigen::MatrixXd>>();
    std::vector<Eigen::Vector3d> samples = highorder::quality_samples(order);
    const auto is_corner = [](const Eigen::Vector3d& p) {
      const double s = p.sum();
      return (p.array() == 0).count() == 3 || ((p.array() == 0).count() == 2 && s == 1);
    };
    std::stable_partition(samples.begin(), samples.end(), is_corner);
    for (const auto& p : samples) g->push_back(highorder::lagrange_gradients(3, order, p.data()));
    cache[order] = std::move(g);
  });
  return *cache[order];
}

} // namespace

std::optional<TetShape> tet_shape(int order, const Eigen::Vector3d* x, double bound) {
  const int n = highorder::tet_node_count(order);
  const double scale = std::max({(x[1] - x[0]).cwiseAbs().maxCoeff(), (x[2] - x[0]).cwiseAbs().maxCoeff(),
                                 (x[3] - x[0]).cwiseAbs().maxCoeff()});
  bool straight = true;
  for (int i = 4; i < n && straight; ++i) {
    const auto w = highorder::tet_node_barycentric(order, i);
    const Eigen::Vector3d affine = w[0] * x[0] + w[1] * x[1] + w[2] * x[2] + w[3] * x[3];
    straight = (x[i] - affine).cwiseAbs().maxCoeff() <= 1e-12 * scale;
  }
  const auto at = [&](const Eigen::Matrix3d& j, TetShape& s) {
    const double e = highorder::amips(j);
    if (!(e < bound)) return false;
    s.max_amips = std::max(s.max_amips, e);
    s.min_scaled_jacobian = std::min(s.min_scaled_jacobian, highorder::scaled_jacobian(j));
    return true;
  };
  TetShape s{0, std::numeric_limits<double>::infinity()};
  if (straight) {
    Eigen::Matrix3d j;
    j << x[1] - x[0], x[2] - x[0], x[3] - x[0];
    if (!at(j, s)) return std::nullopt;
    return s;
  }
  Eigen::Matrix<double, 3, Eigen::Dynamic> nodes(3, n);
  for (int i = 0; i < n; ++i) nodes.col(i) = x[i];
  for (const Eigen::MatrixXd& g : sample_gradients(order))
    if (!at(nodes.lazyProduct(g), s)) return std::nullopt;
  return s;
}

} // namespace curvetet::volume::edit
