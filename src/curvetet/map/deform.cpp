#include "curvetet/map/deform.hpp"

#include "curvetet/map/transfer.hpp"

#include <Eigen/Geometry>

namespace curvetet::map {

Twist twist_for(const std::vector<mesh::Vec3>& points, double radians) {
  Eigen::AlignedBox3d box;
  for (const auto& p : points) box.extend(p);
  Twist t;
  t.radians = radians;
  box.sizes().maxCoeff(&t.axis);
  t.centre = box.center();
  t.low = box.min()[t.axis];
  t.high = box.max()[t.axis];
  return t;
}

mesh::Vec3 displacement(const Twist& t, const mesh::Vec3& x) {
  const double s = t.high > t.low ? (x[t.axis] - t.low) / (t.high - t.low) - 0.5 : 0.0;
  const Eigen::AngleAxisd rotation(t.radians * s, mesh::Vec3::Unit(t.axis));
  return t.centre + rotation * (x - t.centre) - x;
}

std::vector<mesh::Vec3> carry_to_input(const mesh::BoundaryMap& map, const std::vector<mesh::Vec3>& node_displacement) {
  Eigen::MatrixXd d(node_displacement.size(), 3);
  for (std::size_t j = 0; j < node_displacement.size(); ++j) d.row(j) = node_displacement[j].transpose();
  const Eigen::MatrixXd moved = boundary_to_input(map, d, {0, 0, 0});
  std::vector<mesh::Vec3> out(map.input.vertices.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = map.input.vertices[i] + moved.row(i).transpose();
  return out;
}

} // namespace curvetet::map
