#include "curvetet/volume/edit/tet_shape.hpp"

#include "curvetet/highorder/amips_frames.hpp"
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

// Lagrange gradients (nodes x 3) at the reference tet's four corners.
const std::array<Eigen::MatrixXd, 4>& corner_gradients(int order) {
  static std::unique_ptr<std::array<Eigen::MatrixXd, 4>> cache[highorder::kMaxOrder + 1];
  static std::once_flag once[highorder::kMaxOrder + 1];
  std::call_once(once[order], [order] {
    auto g = std::make_unique<std::array<Eigen::MatrixXd, 4>>();
    const Eigen::Vector3d corners[4] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                        Eigen::Vector3d::UnitZ()};
    for (int c = 0; c < 4; ++c) (*g)[c] = highorder::lagrange_gradients(3, order, corners[c].data());
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
  if (straight) {
    Eigen::Matrix3d j;
    j << x[1] - x[0], x[2] - x[0], x[3] - x[0];
    const double e = highorder::amips(j);
    if (!(e < bound)) return std::nullopt;
    return TetShape{e, highorder::scaled_jacobian(j)};
  }
  // Most candidates fail at a corner: those first, then every sample at
  // once (one product for all frames).
  const Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>> nodes(x[0].data(), 3, n);
  for (const Eigen::MatrixXd& g : corner_gradients(order))
    if (!(highorder::amips(nodes * g) < bound)) return std::nullopt;
  const highorder::AmipsFrames& table = highorder::amips_frames(order);
  thread_local std::vector<Eigen::Matrix3d> frames;
  frames.resize(table.num_points());
  table.frames(x, frames.data());
  const double worst = table.max_amips(frames.data(), nullptr, Eigen::Vector3d::Zero(), bound);
  if (!(worst < bound)) return std::nullopt;
  return TetShape{worst, table.min_scaled_jacobian(frames.data(), nullptr, Eigen::Vector3d::Zero())};
}

} // namespace curvetet::volume::edit
