// Shell construction time against input size (issue 4): three real meshes
// of ~7k, ~52k and ~100k faces. Target: n log n; the largest under 30 s on
// 2 cores. Run: build/bench/bench_shell [--benchmark_filter=...]
// Counters: faces, singular vertices, minimum thickness / bbox diagonal,
// thickening rounds.
#include "curvetet/io/read_surface.hpp"
#include "curvetet/shell/build.hpp"

#include <benchmark/benchmark.h>

#include <string>

namespace {

void BM_BuildShell(benchmark::State& state, const std::string& name) {
  using namespace curvetet;
  const auto input = mesh::to_surface_mesh(io::read_surface(std::string(CURVETET_SHARED_DATA) + "/good/" + name));
  const double diag = mesh::bbox_diagonal(input.vertices);
  shell::ShellBuildStats stats;
  for (auto _ : state) {
    auto b = shell::build_shell(input);
    stats = b.stats;
    benchmark::DoNotOptimize(b.shell.top.data());
  }
  state.counters["faces"] = input.num_faces();
  state.counters["singular"] = stats.singular_vertices;
  state.counters["min_thickness_rel"] = stats.min_thickness / diag;
  state.counters["mean_thickness_rel"] = stats.mean_thickness / diag;
  state.counters["rounds"] = stats.rounds;
  state.counters["faces_per_s"] = benchmark::Counter(input.num_faces(), benchmark::Counter::kIsIterationInvariantRate);
}

BENCHMARK_CAPTURE(BM_BuildShell, bunny_7k, std::string("bunny_libigl.off"))->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_BuildShell, armadillo_52k, std::string("armadillo_cgal.off"))
    ->Unit(benchmark::kSecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(BM_BuildShell, nefertiti_100k, std::string("nefertiti.off"))
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

} // namespace

BENCHMARK_MAIN();
