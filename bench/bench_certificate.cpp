// Throughput of the Jacobian certificate (highorder/jacobian_certificate.hpp)
// on gently curved tets that are decided without subdivision (the common
// case in the pipeline). Target: >= 20,000 order-4 tets/s per core.
//   BM_Certify/<order>           one thread, one tet after another
//   BM_CertifyBatch/<threads>    order 4, tbb::parallel_for over the batch,
//                                threads capped with tbb::global_control
//   BM_CertifyInvalid            order 4 tets with one node pushed out
#include "curvetet/highorder/jacobian_certificate.hpp"

#include "../tests/common/curved_box.hpp"

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <atomic>

using namespace curvetet;

namespace {

// Node arrays of the tets of a curved box (6 * cells^3 tets).
std::vector<std::vector<Eigen::Vector3d>> batch(int order, int cells) {
  auto m = curvetet::testing::curved_box(order, cells, 0.3);
  std::vector<std::vector<Eigen::Vector3d>> out(m.num_tets());
  for (int t = 0; t < m.num_tets(); ++t)
    for (int i = 0; i < m.tet_nodes(); ++i) out[t].push_back(m.nodes[m.tet(t)[i]]);
  return out;
}

void BM_Certify(benchmark::State& state) {
  const int order = static_cast<int>(state.range(0));
  const auto tets = batch(order, 6);
  std::size_t i = 0, positive = 0, pieces = 0;
  for (auto _ : state) {
    auto c = highorder::certify_tet(order, tets[i].data());
    positive += c.validity == highorder::Validity::positive;
    pieces += c.pieces;
    benchmark::DoNotOptimize(c);
    i = (i + 1) % tets.size();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["positive_fraction"] = double(positive) / state.iterations();
  state.counters["pieces_per_tet"] = double(pieces) / state.iterations();
}
BENCHMARK(BM_Certify)->DenseRange(1, 8);

void BM_CertifyBatch(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  const auto tets = batch(4, 8); // 3072 tets
  std::atomic<std::size_t> positive = 0;
  for (auto _ : state) {
    tbb::parallel_for(std::size_t(0), tets.size(), [&](std::size_t t) {
      if (highorder::certify_tet(4, tets[t].data()).validity == highorder::Validity::positive) ++positive;
    });
  }
  state.SetItemsProcessed(state.iterations() * tets.size());
  state.counters["positive_fraction"] = double(positive) / (state.iterations() * tets.size());
  state.counters["threads"] = threads;
}
BENCHMARK(BM_CertifyBatch)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

void BM_CertifyInvalid(benchmark::State& state) {
  auto tets = batch(4, 4);
  for (auto& t : tets) t[4] += Eigen::Vector3d(0.5, 0.5, 0.5);
  std::size_t i = 0, invalid = 0;
  for (auto _ : state) {
    invalid += highorder::certify_tet(4, tets[i].data()).validity == highorder::Validity::invalid;
    i = (i + 1) % tets.size();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["invalid_fraction"] = double(invalid) / state.iterations();
}
BENCHMARK(BM_CertifyInvalid);

} // namespace

BENCHMARK_MAIN();
