// The volume optimizer's inner kernel: AMIPS energy (and gradient) of a
// linear tet, closed form (volume/tet_amips.hpp) against the textbook
// J = E W⁻¹ formula with Eigen and std::cbrt it replaced.
#include "curvetet/volume/tet_amips.hpp"

#include <Eigen/Dense>
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace {

using curvetet::mesh::Vec3;

std::vector<std::array<Vec3, 4>> random_tets(int n) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<std::array<Vec3, 4>> out;
  while (static_cast<int>(out.size()) < n) {
    std::array<Vec3, 4> t;
    for (auto& p : t) p = Vec3(u(rng), u(rng), u(rng));
    if ((t[1] - t[0]).dot((t[2] - t[0]).cross(t[3] - t[0])) > 0) out.push_back(t);
  }
  return out;
}

double textbook_amips(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  static const Eigen::Matrix3d w_inv = [] {
    Eigen::Matrix3d w;
    w << 1, 0.5, 0.5, 0, std::sqrt(3.0) / 2, std::sqrt(3.0) / 6, 0, 0, std::sqrt(2.0 / 3.0);
    return Eigen::Matrix3d(w.inverse());
  }();
  Eigen::Matrix3d e;
  e << b - a, c - a, d - a;
  const Eigen::Matrix3d j = e * w_inv;
  const double det = j.determinant();
  if (!(det > 0)) return std::numeric_limits<double>::infinity();
  return j.squaredNorm() / (3 * std::cbrt(det * det));
}

void BM_TextbookAmips(benchmark::State& state) {
  const auto tets = random_tets(4096);
  for (auto _ : state)
    for (const auto& t : tets) benchmark::DoNotOptimize(textbook_amips(t[0], t[1], t[2], t[3]));
  state.SetItemsProcessed(state.iterations() * static_cast<long>(tets.size()));
}
BENCHMARK(BM_TextbookAmips);

void BM_TetAmips(benchmark::State& state) {
  const auto tets = random_tets(4096);
  for (auto _ : state)
    for (const auto& t : tets) benchmark::DoNotOptimize(curvetet::volume::tet_amips(t[0], t[1], t[2], t[3]));
  state.SetItemsProcessed(state.iterations() * static_cast<long>(tets.size()));
}
BENCHMARK(BM_TetAmips);

void BM_TetAmipsGradient(benchmark::State& state) {
  const auto tets = random_tets(4096);
  Vec3 g;
  for (auto _ : state)
    for (const auto& t : tets) {
      benchmark::DoNotOptimize(curvetet::volume::tet_amips_gradient(t[0], t[1], t[2], t[3], 2, g));
      benchmark::DoNotOptimize(g);
    }
  state.SetItemsProcessed(state.iterations() * static_cast<long>(tets.size()));
}
BENCHMARK(BM_TetAmipsGradient);

} // namespace

BENCHMARK_MAIN();
