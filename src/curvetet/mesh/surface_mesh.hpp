#pragma once
// Plain surface data passed between stages.
//
// PolygonSoup: what a file holds, unchecked (indices may be out of range,
// polygons may have any number of corners). SurfaceMesh: triangles only,
// indices in range; faces are oriented counter-clockwise seen from outside.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <vector>

namespace curvetet::mesh {

using Vec3 = Eigen::Vector3d;
using Tri = std::array<int, 3>;

struct PolygonSoup {
  std::vector<Vec3> points;
  std::vector<std::vector<std::int64_t>> polygons;
};

struct SurfaceMesh {
  std::vector<Vec3> vertices;
  std::vector<Tri> faces;

  int num_vertices() const { return static_cast<int>(vertices.size()); }
  int num_faces() const { return static_cast<int>(faces.size()); }
};

// Axis-aligned bounding box diagonal length of the referenced-or-not vertices.
double bbox_diagonal(const std::vector<Vec3>& points);

// Mean length of the face edges (an edge shared by two faces counts twice);
// 0 without faces.
double mean_edge_length(const SurfaceMesh& mesh);

// Copies a soup whose polygons are all triangles with in-range indices.
// Precondition (checked by check::soup defects first): both hold.
SurfaceMesh to_surface_mesh(const PolygonSoup& soup);
PolygonSoup to_soup(const SurfaceMesh& mesh);

} // namespace curvetet::mesh
