#pragma once
// Least-squares fit of a star of curved triangles (paper §4.1): the Lagrange
// nodes of degree-k triangles sharing their edge nodes, fitted so that the
// surface passes as close as possible (in the least-squares sense) to target
// points given at parameter positions.
//
//   minimize  sum_s | X_{t_s}(u_s, v_s) - target_s |^2
//
// over the free nodes, where X_t is triangle t's Lagrange map. Fixed: the
// corner nodes, and every node of the edges listed in `fixed_edges` (edges on
// the star boundary, shared with triangles that do not move). When the
// samples do not determine every free node, the minimum-norm change from the
// flat (linear) position is taken, so an unconstrained node stays on the
// plane of its triangle. A surface that is a polynomial of degree <= k on each
// triangle is reproduced exactly (up to rounding) once samples determine it.
#include <Eigen/Core>

#include <array>
#include <vector>

namespace curvetet::highorder {

struct PatchFitProblem {
  int degree = 1;                          // k, 1..8
  std::vector<std::array<int, 3>> triangles; // corner ids into `corners`
  std::vector<Eigen::Vector3d> corners;      // fixed corner positions

  struct FixedEdge {
    int a = -1, b = -1;                     // corner ids
    std::vector<Eigen::Vector3d> nodes;     // k-1 points from a towards b (a, b excluded)
  };
  std::vector<FixedEdge> fixed_edges;

  struct Sample {
    int triangle = -1;
    Eigen::Vector2d uv;     // reference coordinates in that triangle (corner 0 at (0,0), 1 at (1,0), 2 at (0,1))
    Eigen::Vector3d target;
  };
  std::vector<Sample> samples;
};

struct PatchFit {
  std::vector<std::vector<Eigen::Vector3d>> nodes; // per triangle: internal (Gmsh) order, triangle_node_count(k)
  int free_nodes = 0;
  double max_residual = 0; // max over samples of |X(u,v) - target|
};

PatchFit fit_patch_star(const PatchFitProblem& problem);

} // namespace curvetet::highorder
