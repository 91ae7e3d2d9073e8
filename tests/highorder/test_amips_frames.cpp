// AmipsFrames: the frame form gives the max AMIPS and min scaled Jacobian
// of the quality convention (every sample: tet_quality's; the order-2P
// lattice first, the smoothing's trials), and a rank-one update equals
// recomputing the frames from moved nodes; node gradients are the chain
// rule through the frames.
#include "curvetet/highorder/amips_frames.hpp"
#include "curvetet/highorder/bernstein.hpp"
#include "curvetet/highorder/conforming_nodes.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/highorder/quality.hpp"

#include "element_fixtures.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

using namespace curvetet::highorder;
using namespace curvetet::highorder::testing;

namespace {

double frames_max_amips(int order, const std::vector<Eigen::Vector3d>& nodes) {
  const AmipsFrames& f = amips_frames(order);
  std::vector<Eigen::Matrix3d> k(f.num_points());
  f.frames(nodes.data(), k.data());
  return f.max_amips(k.data(), nullptr, Eigen::Vector3d::Zero(), std::numeric_limits<double>::infinity(),
                     f.num_lattice_points());
}

// The quality convention's measures on its order-2P lattice alone, point
// by point (quality.hpp's amips and scaled_jacobian).
TetQuality lattice_quality(int order, const std::vector<Eigen::Vector3d>& nodes) {
  TetQuality q{std::numeric_limits<double>::infinity(), 0, 0};
  Eigen::Matrix<double, 3, Eigen::Dynamic> x(3, nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) x.col(i) = nodes[i];
  for (int s = 0; s < quality_lattice_points(order); ++s) {
    const Eigen::Matrix3d j = x * lagrange_gradients(3, order, quality_samples(order)[s].data());
    q.max_amips = std::max(q.max_amips, amips(j));
    q.min_scaled_jacobian = std::min(q.min_scaled_jacobian, scaled_jacobian(j));
  }
  return q;
}

} // namespace

TEST(AmipsFrames, MatchesTetQuality) {
  for (int p = 1; p <= 5; ++p) {
    const auto nodes = mapped_tet(p, unit_tet(), gentle_bend);
    const TetQuality expected = lattice_quality(p, nodes);
    EXPECT_NEAR(frames_max_amips(p, nodes), expected.max_amips, 1e-12 * expected.max_amips) << "order " << p;
    const AmipsFrames& f = amips_frames(p);
    std::vector<Eigen::Matrix3d> k(f.num_points());
    f.frames(nodes.data(), k.data());
    EXPECT_NEAR(f.min_scaled_jacobian(k.data(), nullptr, Eigen::Vector3d::Zero(),
                                      -std::numeric_limits<double>::infinity(), f.num_lattice_points()),
                expected.min_scaled_jacobian, 1e-12)
        << "order " << p;
    EXPECT_EQ(f.num_lattice_points(), quality_lattice_points(p));
    EXPECT_EQ(f.num_points(), static_cast<int>(quality_samples(p).size()));
    // Every sample: what the report gives (tet_quality), which can only be
    // worse than the lattice's.
    const TetQuality all = tet_quality(p, nodes.data());
    EXPECT_NEAR(f.max_amips(k.data(), nullptr, Eigen::Vector3d::Zero()), all.max_amips, 1e-12 * all.max_amips);
    EXPECT_NEAR(f.min_scaled_jacobian(k.data(), nullptr, Eigen::Vector3d::Zero()), all.min_scaled_jacobian, 1e-12);
    EXPECT_GE(all.max_amips, expected.max_amips * (1 - 1e-12));
  }
  // The regular tet: AMIPS 3 (quality.hpp's convention), scaled Jacobian 1.
  const std::array<Eigen::Vector3d, 4> regular = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0),
                                                  Eigen::Vector3d(0.5, std::sqrt(3.0) / 2, 0),
                                                  Eigen::Vector3d(0.5, std::sqrt(3.0) / 6, std::sqrt(2.0 / 3.0))};
  for (int p = 1; p <= 4; ++p) {
    const auto nodes = straight_tet(p, regular);
    const AmipsFrames& f = amips_frames(p);
    std::vector<Eigen::Matrix3d> k(f.num_points());
    f.frames(nodes.data(), k.data());
    EXPECT_NEAR(f.max_amips(k.data(), nullptr, Eigen::Vector3d::Zero()), 3.0, 1e-9);
    EXPECT_NEAR(f.min_scaled_jacobian(k.data(), nullptr, Eigen::Vector3d::Zero()), 1.0, 1e-9);
  }
}

TEST(AmipsFrames, RankOneUpdateEqualsRecomputedFrames) {
  const int p = 4;
  const AmipsFrames& f = amips_frames(p);
  const auto nodes = mapped_tet(p, unit_tet(), gentle_bend);
  std::vector<Eigen::Matrix3d> k(f.num_points());
  f.frames(nodes.data(), k.data());
  const Eigen::Vector3d d(0.03, -0.02, 0.05);

  // One high-order node, then a corner with its star's barycentric weights.
  for (int local : {7, 20, 34}) {
    std::vector<Eigen::Vector3d> c(f.num_points(), Eigen::Vector3d::Zero());
    f.add_direction(local, 1.0, c.data());
    auto moved = nodes;
    moved[local] += d;
    const TetQuality expected = tet_quality(p, moved.data());
    EXPECT_NEAR(f.max_amips(k.data(), c.data(), d), expected.max_amips, 1e-10) << "node " << local;
    EXPECT_NEAR(f.min_scaled_jacobian(k.data(), c.data(), d), expected.min_scaled_jacobian, 1e-10);
  }
  std::vector<Eigen::Vector3d> c(f.num_points(), Eigen::Vector3d::Zero());
  auto moved = nodes;
  for (int i = 0; i < f.num_nodes(); ++i) {
    const double w = tet_node_barycentric(p, i)[2];
    if (w == 0) continue;
    f.add_direction(i, w, c.data());
    moved[i] += w * d;
  }
  EXPECT_NEAR(f.max_amips(k.data(), c.data(), d), tet_quality(p, moved.data()).max_amips, 1e-10);
}

// The trials' rank-one terms give the lattice's max AMIPS of the moved tet
// (the determinant lemma and the expanded norm), +inf once the move inverts
// a point, and stop at the bound like the direct form.
TEST(AmipsFrames, RankOneTermsEqualTheDirectForm) {
  const int p = 4;
  const AmipsFrames& f = amips_frames(p);
  const auto nodes = mapped_tet(p, unit_tet(), gentle_bend);
  const int lattice = f.num_lattice_points();
  std::vector<Eigen::Matrix3d> k(f.num_points());
  f.frames(nodes.data(), k.data());
  std::vector<Eigen::Vector3d> c(f.num_points(), Eigen::Vector3d::Zero());
  f.add_direction(0, 1.0, c.data());
  f.add_direction(20, 0.5, c.data());
  std::vector<AmipsFrames::RankOneTerms> terms(lattice);
  f.rank_one_terms(k.data(), c.data(), terms.data(), lattice);
  for (const Eigen::Vector3d& d : {Eigen::Vector3d(0.03, -0.02, 0.05), Eigen::Vector3d(-0.05, 0.02, 0.04), Eigen::Vector3d(0, 0, 0)}) {
    const double direct = f.max_amips(k.data(), c.data(), d, std::numeric_limits<double>::infinity(), lattice);
    EXPECT_NEAR(f.max_amips(terms.data(), d, std::numeric_limits<double>::infinity(), lattice), direct, 1e-12 * direct);
    EXPECT_GE(f.max_amips(terms.data(), d, 0.5 * direct, lattice), 0.5 * direct);
  }
  // Corner 0 pushed through the opposite face: some point inverts.
  const Eigen::Vector3d through(2, 2, 2);
  EXPECT_EQ(f.max_amips(k.data(), c.data(), through, std::numeric_limits<double>::infinity(), lattice),
            std::numeric_limits<double>::infinity());
  EXPECT_EQ(f.max_amips(terms.data(), through, std::numeric_limits<double>::infinity(), lattice),
            std::numeric_limits<double>::infinity());
}

TEST(AmipsFrames, InvertedIsInfiniteAndBoundStopsEarly) {
  const int p = 3;
  const AmipsFrames& f = amips_frames(p);
  auto v = unit_tet();
  std::swap(v[0], v[1]);
  const auto inverted = straight_tet(p, v);
  EXPECT_TRUE(std::isinf(frames_max_amips(p, inverted)));

  const auto nodes = mapped_tet(p, unit_tet(), gentle_bend);
  std::vector<Eigen::Matrix3d> k(f.num_points());
  f.frames(nodes.data(), k.data());
  const double full = f.max_amips(k.data(), nullptr, Eigen::Vector3d::Zero());
  EXPECT_GE(f.max_amips(k.data(), nullptr, Eigen::Vector3d::Zero(), 3.0), 3.0); // AMIPS >= 3 everywhere
  EXPECT_EQ(f.max_amips(k.data(), nullptr, Eigen::Vector3d::Zero(), 2 * full), full);
}

// The optimizer checks a step's lattice in its trial and the other samples
// on acceptance: the two ranges together give every sample's measures.
TEST(AmipsFrames, LatticeAndTheRestMakeEverySample) {
  for (int p = 2; p <= 4; ++p) {
    const AmipsFrames& f = amips_frames(p);
    const auto nodes = mapped_tet(p, unit_tet(), gentle_bend);
    std::vector<Eigen::Matrix3d> k(f.num_points());
    f.frames(nodes.data(), k.data());
    const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
    const double inf = std::numeric_limits<double>::infinity();
    const int n = f.num_lattice_points();
    if (p != 3) { // at P = 3 both lattices are of order 6
      ASSERT_LT(n, f.num_points()) << "order " << p;
    }
    EXPECT_EQ(std::max(f.max_amips(k.data(), nullptr, zero, inf, n), f.max_amips(k.data(), nullptr, zero, inf, -1, n)),
              f.max_amips(k.data(), nullptr, zero));
    EXPECT_EQ(std::min(f.min_scaled_jacobian(k.data(), nullptr, zero, -inf, n),
                       f.min_scaled_jacobian(k.data(), nullptr, zero, -inf, -1, n)),
              f.min_scaled_jacobian(k.data(), nullptr, zero));
    // The rest alone differs from the lattice alone (else the split is moot).
    if (n < f.num_points()) {
      EXPECT_NE(f.max_amips(k.data(), nullptr, zero, inf, -1, n), f.max_amips(k.data(), nullptr, zero, inf, n));
    }
  }
}

// The smoothing's descent directions: at the worst point of a bent tet,
// the gradients of AMIPS and of the scaled Jacobian along a node move
// agree with central differences of the measures themselves.
TEST(AmipsFrames, PointGradientsMatchFiniteDifferences) {
  const int p = 4;
  const AmipsFrames& f = amips_frames(p);
  const auto nodes = mapped_tet(p, unit_tet(), gentle_bend);
  std::vector<Eigen::Matrix3d> k(f.num_points());
  f.frames(nodes.data(), k.data());
  std::vector<Eigen::Vector3d> c(f.num_points(), Eigen::Vector3d::Zero());
  f.add_direction(7, 1.0, c.data()); // an edge node
  f.add_direction(1, 0.5, c.data()); // and half of a corner
  const int n = f.num_lattice_points();
  double worst_amips = 0, worst_sj = 0;
  const int qa = f.worst_amips_point(k.data(), n, &worst_amips), qs = f.worst_scaled_jacobian_point(k.data(), n, &worst_sj);
  ASSERT_GE(qa, 0);
  ASSERT_GE(qs, 0);
  EXPECT_EQ(worst_amips, f.max_amips(k.data(), nullptr, Eigen::Vector3d::Zero(), std::numeric_limits<double>::infinity(), n));
  EXPECT_EQ(worst_sj, f.min_scaled_jacobian(k.data(), nullptr, Eigen::Vector3d::Zero(), -std::numeric_limits<double>::infinity(), n));
  const Eigen::Vector3d ga = f.amips_gradient(k[qa], c[qa]), gs = f.scaled_jacobian_gradient(k[qs], c[qs]);
  const double h = 1e-6;
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3d d = h * Eigen::Vector3d::Unit(a);
    const auto amips_at = [&](const Eigen::Vector3d& x) { return f.max_amips(&k[qa], &c[qa], x, std::numeric_limits<double>::infinity(), 1); };
    const auto sj_at = [&](const Eigen::Vector3d& x) { return f.min_scaled_jacobian(&k[qs], &c[qs], x, -std::numeric_limits<double>::infinity(), 1); };
    EXPECT_NEAR(ga[a], (amips_at(d) - amips_at(-d)) / (2 * h), 1e-6 * (1 + ga.norm())) << "axis " << a;
    EXPECT_NEAR(gs[a], (sj_at(d) - sj_at(-d)) / (2 * h), 1e-6 * (1 + gs.norm())) << "axis " << a;
  }
  EXPECT_GT(ga.norm(), 0);
  EXPECT_GT(gs.norm(), 0);
}

// node_gradients is the chain rule through the frames: for f = sum over the
// lattice of |K_q|^2 (df/dK_q = 2 K_q), central differences of f by each
// coordinate of a few nodes agree with it.
TEST(AmipsFrames, NodeGradientsMatchFiniteDifferences) {
  const int p = 4;
  const AmipsFrames& f = amips_frames(p);
  const int n = f.num_lattice_points();
  const auto nodes = mapped_tet(p, unit_tet(), gentle_bend);
  const auto energy = [&](const std::vector<Eigen::Vector3d>& x) {
    std::vector<Eigen::Matrix3d> k(n);
    f.frames(x.data(), k.data(), n);
    double e = 0;
    for (const auto& m : k) e += m.squaredNorm();
    return e;
  };
  std::vector<Eigen::Matrix3d> k(n), dk(n);
  f.frames(nodes.data(), k.data(), n);
  for (int q = 0; q < n; ++q) dk[q] = 2 * k[q];
  std::vector<Eigen::Vector3d> grad(f.num_nodes());
  f.node_gradients(dk.data(), grad.data(), n);
  const double h = 1e-6;
  for (int local : {0, 7, 20, 34})
    for (int axis = 0; axis < 3; ++axis) {
      auto plus = nodes, minus = nodes;
      plus[local][axis] += h;
      minus[local][axis] -= h;
      const double fd = (energy(plus) - energy(minus)) / (2 * h);
      EXPECT_NEAR(grad[local][axis], fd, 1e-5 * std::max(1.0, std::abs(fd))) << "node " << local << " axis " << axis;
    }
}
