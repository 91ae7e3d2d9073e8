#pragma once
// Shared by the map tests: the whole pipeline (run_pipeline) on a small
// ellipsoid at two epsilons, computed once per test binary, and the map
// built from each result.
#include "shell/tiny_meshes.hpp"

#include "curvetet/core/report.hpp"
#include "curvetet/map/build_map.hpp"
#include "curvetet/pipeline/pipeline.hpp"

#include <map>

namespace curvetet::test {

// Octahedral sphere (3 subdivisions, 512 faces) scaled to radii 1, 0.7, 0.5.
inline mesh::SurfaceMesh ellipsoid() {
  auto m = shell::test::sphere(3);
  for (auto& p : m.vertices) p = mesh::Vec3(p.x(), 0.7 * p.y(), 0.5 * p.z());
  return m;
}

struct MappedResult {
  pipeline::PipelineResult result;
  mesh::BoundaryMap map;
  map::MapBuildStats stats;
  double diagonal = 0, epsilon_abs = 0;
};

inline const MappedResult& mapped_ellipsoid(double epsilon) {
  static std::map<double, MappedResult> cache;
  auto it = cache.find(epsilon);
  if (it != cache.end()) return it->second;
  MappedResult r;
  const auto input = ellipsoid();
  pipeline::PipelineOptions o;
  o.epsilon = epsilon;
  Report report;
  r.result = pipeline::run_pipeline(input, o, report);
  r.map = map::build_boundary_map(r.result.shell, r.result.mesh, &r.stats);
  r.diagonal = mesh::bbox_diagonal(input.vertices);
  r.epsilon_abs = epsilon * r.diagonal;
  return cache.emplace(epsilon, std::move(r)).first->second;
}

} // namespace curvetet::test
