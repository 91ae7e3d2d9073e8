#pragma once
// 1-to-3 refinement of every triangle with more than one feature edge (paper
// §5): a new vertex at the triangle's centroid splits it into three, each
// holding at most one of the old feature edges. The original vertices keep
// their ids; new vertices are appended.
//
// `parent` and `barycentric` let the map go back to the original input: new
// vertex i (id num_original + i) lies at barycentric (1/3, 1/3, 1/3) of
// original face parent_of_new_vertex[i]; refined face f came from original face
// parent_face[f]. The centroid is rounded to doubles, so it lies on the parent
// face only up to rounding: the refined mesh is the surface the shell is built
// on, and its map to the original is this piecewise-affine correspondence.
#include "curvetet/mesh/surface_mesh.hpp"

#include <array>
#include <vector>

namespace curvetet::features {

struct RefinedSurface {
  mesh::SurfaceMesh mesh;
  std::vector<int> parent_face;          // per refined face
  std::vector<int> parent_of_new_vertex; // per appended vertex
};

RefinedSurface refine_multi_feature_faces(const mesh::SurfaceMesh& m, const std::vector<std::array<int, 2>>& edges);

} // namespace curvetet::features
