// Precondition-check time (issue: < 2 s for 200k triangles, n log n).
// Sizes: bunny_libigl midpoint-subdivided 0..3 times (7k..446k faces, same
// shape, so only n changes) and the largest real mesh of ../shared/data.
// The self-intersection test is also timed on its own.
#include "curvetet/check/preconditions.hpp"
#include "curvetet/check/self_intersection.hpp"
#include "curvetet/io/read_surface.hpp"
#include "curvetet/mesh/edge_topology.hpp"

#include <benchmark/benchmark.h>

#include <map>

using namespace curvetet;

namespace {

// 1-to-4 split at edge midpoints: same surface, 4x the faces.
mesh::SurfaceMesh subdivide(const mesh::SurfaceMesh& m) {
  auto topo = mesh::build_edge_topology(m.faces);
  mesh::SurfaceMesh out;
  out.vertices = m.vertices;
  for (const auto& e : topo.edges) out.vertices.push_back(0.5 * (m.vertices[e[0]] + m.vertices[e[1]]));
  const int nv = m.num_vertices();
  for (int f = 0; f < m.num_faces(); ++f) {
    const auto& t = m.faces[f];
    const auto& fe = topo.face_edges[f]; // fe[k] opposite corner k
    int m0 = nv + fe[2], m1 = nv + fe[0], m2 = nv + fe[1]; // midpoints of (0,1), (1,2), (2,0)
    out.faces.push_back({t[0], m0, m2});
    out.faces.push_back({t[1], m1, m0});
    out.faces.push_back({t[2], m2, m1});
    out.faces.push_back({m0, m1, m2});
  }
  return out;
}

const mesh::SurfaceMesh& bunny(int level) {
  static std::map<int, mesh::SurfaceMesh> cache;
  auto it = cache.find(level);
  if (it != cache.end()) return it->second;
  mesh::SurfaceMesh m = level == 0
                            ? mesh::to_surface_mesh(io::read_surface(std::string(CURVETET_SHARED_DATA) + "/good/bunny_libigl.off"))
                            : subdivide(bunny(level - 1));
  return cache.emplace(level, std::move(m)).first->second;
}

void BM_Preconditions(benchmark::State& state) {
  const auto& m = bunny(static_cast<int>(state.range(0)));
  const auto soup = mesh::to_soup(m);
  check::PreconditionReport r;
  for (auto _ : state) {
    r = check::check_preconditions(soup);
    benchmark::DoNotOptimize(r);
  }
  if (!r.ok()) state.SkipWithError("subdivided bunny should be valid");
  state.SetComplexityN(m.num_faces());
  state.counters["faces"] = m.num_faces();
  state.counters["self_intersection_s"] = r.seconds_self_intersection;
  state.counters["topology_s"] = r.seconds_topology;
  state.counters["orientation_s"] = r.seconds_orientation;
}
BENCHMARK(BM_Preconditions)->DenseRange(0, 3)->Unit(benchmark::kMillisecond)->Complexity(benchmark::oNLogN);

void BM_SelfIntersection(benchmark::State& state) {
  const auto& m = bunny(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(check::self_intersections(m));
  state.SetComplexityN(m.num_faces());
  state.counters["faces"] = m.num_faces();
}
BENCHMARK(BM_SelfIntersection)->DenseRange(0, 3)->Unit(benchmark::kMillisecond)->Complexity(benchmark::oNLogN);

void BM_PreconditionsLargestDataMesh(benchmark::State& state) {
  static const auto soup = io::read_surface(std::string(CURVETET_SHARED_DATA) + "/good/cad_thicksolid_thin.off");
  check::PreconditionReport r;
  for (auto _ : state) r = check::check_preconditions(soup);
  state.counters["faces"] = static_cast<double>(soup.polygons.size());
  state.counters["self_intersection_s"] = r.seconds_self_intersection;
}
BENCHMARK(BM_PreconditionsLargestDataMesh)->Unit(benchmark::kMillisecond);

} // namespace

BENCHMARK_MAIN();
