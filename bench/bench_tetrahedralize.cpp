// Boundary-preserving tetrahedralization time (issue 6): `volume::tetrahedralize`
// on real meshes from ~0.5k to ~100k faces, by whichever fill applies (the
// Delaunay fast path or the layered one: extrusion + exact insertion + layer
// + rounding/optimization), and on two CAD parts and a scan by each fill in
// turn.
// Target: within 5x of `tetgen -pYq` (bench/compare_tetgen.py measures both
// on every good mesh).
// Run: build/bench/bench_tetrahedralize [--benchmark_filter=...]
// Counters: faces, output tets, per-stage seconds (extrusion, insertion,
// layer, optimization), max AMIPS energy, direct (1: the fast path ran),
// offset_points and cones (the fast path's points inside the surface).
#include "curvetet/io/read_surface.hpp"
#include "curvetet/volume/tetrahedralize.hpp"

#include <benchmark/benchmark.h>

#include <string>

namespace {

void BM_Tetrahedralize(benchmark::State& state, const std::string& name, bool direct = true) {
  using namespace curvetet;
  const auto input = mesh::to_surface_mesh(io::read_surface(std::string(CURVETET_SHARED_DATA) + "/good/" + name));
  volume::TetrahedralizeOptions options;
  options.direct = direct;
  volume::TetrahedralizeResult r;
  for (auto _ : state) {
    r = volume::tetrahedralize(input, options);
    benchmark::DoNotOptimize(r.mesh.tets.data());
  }
  state.counters["faces"] = input.num_faces();
  state.counters["tets"] = r.mesh.num_tets();
  state.counters["s_extrusion"] = r.seconds_extrusion;
  state.counters["s_insert"] = r.interior.seconds_insert;
  state.counters["s_layer"] = r.interior.seconds_layer;
  state.counters["s_optimize"] = r.interior.seconds_optimize;
  state.counters["max_amips"] = r.interior.max_amips;
  state.counters["direct"] = r.interior.direct ? 1 : 0;
  state.counters["offset_points"] = r.interior.offset_points;
  state.counters["cones"] = r.interior.cones;
  state.counters["faces_per_s"] = benchmark::Counter(input.num_faces(), benchmark::Counter::kIsIterationInvariantRate);
}

// name, good mesh, fill (true: the Delaunay fast path where it applies).
struct Case {
  const char* name;
  const char* mesh;
  bool direct;
};
constexpr Case kCases[] = {
    {"thingi_552", "thingi10k_288351.off", true},
    {"bunny_7k", "bunny_libigl.off", true},
    {"fandisk_13k", "fandisk_cgal.off", true},
    {"armadillo_52k", "armadillo_cgal.off", true},
    {"nefertiti_100k", "nefertiti.off", true},
    // The same models by each fill: CAD parts, and a scan (cones).
    {"knot2_12k_direct", "knot2_two_components.off", true},
    {"knot2_12k_layered", "knot2_two_components.off", false},
    {"boolean_29k_direct", "cad_boolean.off", true},
    {"boolean_29k_layered", "cad_boolean.off", false},
    {"bunny_7k_layered", "bunny_libigl.off", false},
};
const int registered = [] {
  for (const Case& c : kCases)
    benchmark::RegisterBenchmark((std::string("BM_Tetrahedralize/") + c.name).c_str(), BM_Tetrahedralize,
                                 std::string(c.mesh), c.direct)
        ->Unit(benchmark::kSecond)
        ->Iterations(1);
  return 0;
}();

} // namespace

BENCHMARK_MAIN();
