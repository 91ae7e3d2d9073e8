// Shell coarsening time against input size (issue 5): three real meshes of
// ~7k, ~9k and ~52k faces, each with 1 and 2 threads (the second argument).
// Target: linear in the input size; the bunny under 60 s on 2 cores.
// The shell is built once per benchmark outside the timed loop.
// Counters: faces before/after, reduction, operations tried and accepted per
// second, parallel_share (share of the pass time in the parallel check
// phase; the rest is serial), tried_per_batch, and a checksum of the coarse
// shell that must not depend on the thread count.
// Run: build/bench/bench_coarsen [--benchmark_filter=...]
#include "curvetet/core/threads.hpp"
#include "curvetet/io/read_surface.hpp"
#include "curvetet/shell/build.hpp"
#include "curvetet/shell/coarsen.hpp"

#include <benchmark/benchmark.h>

#include <cstring>
#include <string>

namespace {

// FNV-1a over the faces and the bits of every position (thread-count check).
double checksum(const curvetet::shell::Shell& s) {
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&](const void* p, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  };
  for (const auto& f : s.faces) mix(f.data(), sizeof(f));
  for (const auto* P : {&s.bottom, &s.middle, &s.top})
    for (const auto& p : *P) mix(p.data(), 3 * sizeof(double));
  return static_cast<double>(h % 1000000007ull);
}

void BM_Coarsen(benchmark::State& state, const std::string& name) {
  using namespace curvetet;
  const auto input = mesh::to_surface_mesh(io::read_surface(std::string(CURVETET_SHARED_DATA) + "/good/" + name));
  const auto built = shell::build_shell(input);
  ThreadLimit limit(static_cast<int>(state.range(0)));
  shell::CoarsenStats stats;
  double sum = 0;
  for (auto _ : state) {
    state.PauseTiming();
    shell::Shell s = built.shell;
    state.ResumeTiming();
    stats = shell::coarsen_shell(s, shell::CoarsenOptions{});
    sum = checksum(s);
  }
  long long tried = 0, accepted = 0;
  double pass_seconds = 0, check_seconds = 0, batches = 0;
  for (const auto& p : stats.passes) {
    tried += p.tried;
    accepted += p.accepted;
    pass_seconds += p.seconds;
    check_seconds += p.check_seconds;
    batches += static_cast<double>(p.batches);
  }
  // Share of the pass time spent in the parallel check phase (the rest:
  // batch assembly, commits, renewals, compaction: serial), and the mean
  // number of candidates checked per parallel batch.
  state.counters["parallel_share"] = pass_seconds > 0 ? check_seconds / pass_seconds : 0;
  state.counters["tried_per_batch"] = batches > 0 ? double(tried) / batches : 0;
  state.counters["faces_before"] = stats.faces_before;
  state.counters["faces_after"] = stats.faces_after;
  state.counters["reduction"] = double(stats.faces_before) / std::max(1, stats.faces_after);
  state.counters["ops_tried_per_s"] = benchmark::Counter(double(tried), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["ops_accepted_per_s"] =
      benchmark::Counter(double(accepted), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["checksum"] = sum;
}

BENCHMARK_CAPTURE(BM_Coarsen, bunny_7k, std::string("bunny_libigl.off"))
    ->Arg(1)->Arg(2)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK_CAPTURE(BM_Coarsen, fertility_9k, std::string("fertility.off"))
    ->Arg(1)->Arg(2)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK_CAPTURE(BM_Coarsen, armadillo_52k, std::string("armadillo_cgal.off"))
    ->Arg(1)->Arg(2)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

} // namespace

BENCHMARK_MAIN();
