// The curved optimizer's inner products (highorder/amips_frames.hpp): the
// frames of an order-P tet at every sample (X H) and the chain rule back to
// its nodes (G H^T), against the same products as one Eigen GEMM.
#include "curvetet/highorder/amips_frames.hpp"
#include "curvetet/highorder/bernstein.hpp"
#include "curvetet/highorder/quality.hpp"

#include <Eigen/Dense>
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

namespace {

using curvetet::highorder::AmipsFrames;
using curvetet::highorder::amips_frames;

constexpr int kOrder = 4;

std::vector<Eigen::Vector3d> random_nodes(int n) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Vector3d> x(n);
  for (auto& p : x) p = {u(rng), u(rng), u(rng)};
  return x;
}

// H as AmipsFrames builds it (nodes x 3 samples), for the GEMM reference.
Eigen::MatrixXd gradient_table(const AmipsFrames& f) {
  const auto& xis = curvetet::highorder::quality_samples(kOrder);
  const Eigen::Matrix3d w_inv = f.reference_to_regular().inverse();
  Eigen::MatrixXd h(f.num_nodes(), 3 * f.num_points());
  for (int q = 0; q < f.num_points(); ++q)
    h.middleCols<3>(3 * q) = curvetet::highorder::lagrange_gradients(3, kOrder, xis[q].data()) * w_inv;
  return h;
}

void BM_Frames(benchmark::State& state) {
  const AmipsFrames& f = amips_frames(kOrder);
  const auto x = random_nodes(f.num_nodes());
  std::vector<Eigen::Matrix3d> k(f.num_points());
  for (auto _ : state) {
    f.frames(x.data(), k.data(), f.num_lattice_points());
    benchmark::DoNotOptimize(k.data());
  }
}
BENCHMARK(BM_Frames);

void BM_FramesEigenGemm(benchmark::State& state) {
  const AmipsFrames& f = amips_frames(kOrder);
  const Eigen::MatrixXd h = gradient_table(f);
  const auto x = random_nodes(f.num_nodes());
  std::vector<Eigen::Matrix3d> k(f.num_points());
  const int columns = 3 * f.num_lattice_points();
  for (auto _ : state) {
    const Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>> xm(x[0].data(), 3, f.num_nodes());
    Eigen::Map<Eigen::Matrix<double, 3, Eigen::Dynamic>> km(k[0].data(), 3, columns);
    km.noalias() = xm * h.leftCols(columns);
    benchmark::DoNotOptimize(k.data());
  }
}
BENCHMARK(BM_FramesEigenGemm);

void BM_NodeGradients(benchmark::State& state) {
  const AmipsFrames& f = amips_frames(kOrder);
  std::vector<Eigen::Matrix3d> dk(f.num_points(), Eigen::Matrix3d::Constant(0.5));
  std::vector<Eigen::Vector3d> g(f.num_nodes());
  for (auto _ : state) {
    f.node_gradients(dk.data(), g.data(), f.num_lattice_points());
    benchmark::DoNotOptimize(g.data());
  }
}
BENCHMARK(BM_NodeGradients);

void BM_NodeGradientsEigenGemm(benchmark::State& state) {
  const AmipsFrames& f = amips_frames(kOrder);
  const Eigen::MatrixXd h = gradient_table(f);
  std::vector<Eigen::Matrix3d> dk(f.num_points(), Eigen::Matrix3d::Constant(0.5));
  std::vector<Eigen::Vector3d> g(f.num_nodes());
  const int columns = 3 * f.num_lattice_points();
  for (auto _ : state) {
    const Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>> gm(dk[0].data(), 3, columns);
    Eigen::Map<Eigen::Matrix<double, 3, Eigen::Dynamic>> xm(g[0].data(), 3, f.num_nodes());
    xm.noalias() = gm * h.leftCols(columns).transpose();
    benchmark::DoNotOptimize(g.data());
  }
}
BENCHMARK(BM_NodeGradientsEigenGemm);

} // namespace

BENCHMARK_MAIN();
