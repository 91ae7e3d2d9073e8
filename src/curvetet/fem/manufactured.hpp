#pragma once
// Manufactured (fabricated) solutions for -Δu = f: the exact u, used as
// Dirichlet data g = u on the boundary and for the L2 error, and its
// Laplacian, from which f = -Δu.
#include "curvetet/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <functional>

namespace curvetet::fem {

struct ManufacturedSolution {
  std::function<double(const Eigen::Vector3d&)> value;
  std::function<double(const Eigen::Vector3d&)> laplacian;
};

// Axis-aligned box normalisation x_hat = (x - origin) / scale, scale = the
// longest side, so the box maps into [0,1]^3 with its longest side = 1.
struct BoxScaling {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double scale = 1;
};
// Bounding box of the nodes used by the tets (unused nodes are ignored).
// Throws Error(io) for a mesh without tets or of zero extent.
BoxScaling tet_bounding_box(const mesh::TetMesh& mesh);

// The paper's §6.4 solution (the 3D Franke function, Salari & Knupp style
// fabricated solution) evaluated at x_hat = (x - origin) / scale:
//   u = 3/4 exp(-((9x-2)^2 + (9y-2)^2 + (9z-2)^2) / 4)
//     + 3/4 exp(-(9x+1)^2/49 - (9y+1)/10 - (9z+1)/10)
//     + 1/2 exp(-((9x-7)^2 + (9y-3)^2 + (9z-5)^2) / 4)
//     - 1/5 exp(-(9x-4)^2 - (9y-7)^2 - (9z-5)^2).
// The Laplacian is exact (analytic), in the unscaled coordinates x.
ManufacturedSolution franke_solution(const BoxScaling& box = {});

} // namespace curvetet::fem
