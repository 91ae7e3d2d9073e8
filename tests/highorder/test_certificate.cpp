// Jacobian certificate: positive on straight and gently curved tets, invalid
// on a tet with an edge node pushed across the opposite face, never positive
// when a dense sample of det J is <= 0 (thousands of random elements), radii
// bound the distance to the exact coefficients, and the coefficients equal
// the ones obtained by sampling det J on the degree-3(P-1) lattice and
// converting to Bernstein. Slabs: the same properties on prism slabs.
#include "curvetet/highorder/bernstein.hpp"
#include "curvetet/highorder/element_map.hpp"
#include "curvetet/highorder/jacobian_certificate.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/highorder/simplex_lattice.hpp"

#include "element_fixtures.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <random>

using namespace curvetet::highorder;
using namespace curvetet::highorder::testing;

namespace {

// min det J over a lattice of the given density plus the node points.
double sampled_min_det(int order, const std::vector<Eigen::Vector3d>& nodes, int density) {
  double m = HUGE_VAL;
  for (int a = 0; a <= density; ++a)
    for (int b = 0; a + b <= density; ++b)
      for (int c = 0; a + b + c <= density; ++c) {
        Eigen::Vector3d xi(a, b, c);
        xi /= density;
        m = std::min(m, tet_jacobian(order, nodes.data(), xi).determinant());
      }
  return m;
}

} // namespace

TEST(Certificate, StraightTetsArePositiveWithExactBounds) {
  for (int p = 1; p <= kMaxOrder; ++p) {
    auto nodes = straight_tet(p, {Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Vector3d(2, 0, 0.1),
                                  Eigen::Vector3d(0.3, 1.5, 0), Eigen::Vector3d(0.2, 0.1, 1.7)});
    auto cert = certify_tet(p, nodes.data());
    EXPECT_EQ(cert.validity, Validity::positive) << "order " << p;
    EXPECT_EQ(cert.pieces, 1);
    const double det = tet_jacobian(p, nodes.data(), Eigen::Vector3d(0.25, 0.25, 0.25)).determinant();
    EXPECT_LE(cert.min_det_lower, det);
    EXPECT_GE(cert.min_det_upper, det * (1 - 1e-12));
    EXPECT_GT(cert.min_det_lower, det * (1 - 1e-6));
  }
  // An inverted straight tet (two vertices swapped) is invalid.
  auto inv = straight_tet(3, {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 1, 0),
                              Eigen::Vector3d(0, 0, 1)});
  EXPECT_EQ(certify_tet(3, inv.data()).validity, Validity::invalid);
}

TEST(Certificate, GentlyCurvedTetsArePositive) {
  for (int p = 2; p <= kMaxOrder; ++p) {
    auto nodes = mapped_tet(p, unit_tet(), gentle_bend);
    auto cert = certify_tet(p, nodes.data());
    EXPECT_EQ(cert.validity, Validity::positive) << "order " << p;
    EXPECT_GT(cert.min_det_lower, 0);
    EXPECT_LE(cert.min_det_lower, sampled_min_det(p, nodes, 12));
  }
}

TEST(Certificate, EdgeNodePushedAcrossOppositeFaceIsInvalid) {
  for (int p = 2; p <= 5; ++p) {
    auto nodes = straight_tet(p);
    // Gmsh order: nodes 4.. are on edge 0-1; push the first one through the
    // face opposite vertex 0 (x + y + z = 1) and far beyond.
    nodes[4] = Eigen::Vector3d(0.7, 0.9, 0.9);
    auto cert = certify_tet(p, nodes.data());
    EXPECT_EQ(cert.validity, Validity::invalid) << "order " << p;
    EXPECT_LE(cert.min_det_upper, 0);
    EXPECT_LT(sampled_min_det(p, nodes, 12), 0);
    ASSERT_EQ(cert.region.size(), 4u);
  }
}

TEST(Certificate, DegenerateCornerIsInvalidExactly) {
  // A flat corner: node of edge 0-1 placed so det J at vertex 0 is exactly 0.
  auto nodes = straight_tet(2);
  nodes[4] = Eigen::Vector3d(0, 0, 0.25); // dx/du at vertex 0 = 4 n4 - 3 v0 - v1 = (-1, 0, 1)
  // columns at vertex 0: (-1,0,1), (0,1,0), (0,0,1) -> det = -1: invalid
  EXPECT_EQ(certify_tet(2, nodes.data()).validity, Validity::invalid);
  nodes[4] = Eigen::Vector3d(0.25, 0, 0); // dx/du at vertex 0 = (0,0,0): det exactly 0 there
  auto cert = certify_tet(2, nodes.data());
  EXPECT_EQ(cert.validity, Validity::invalid);
  EXPECT_LE(cert.min_det_upper, 0);
}

TEST(Certificate, RadiiBoundTheExactCoefficients) {
  std::mt19937 rng(1234);
  std::normal_distribution<double> noise(0, 1);
  for (int p = 1; p <= 4; ++p)
    for (int trial = 0; trial < 40; ++trial) {
      auto nodes = straight_tet(p, {Eigen::Vector3d(100.1, 50.2, -3), Eigen::Vector3d(101.3, 50.1, -3.2),
                                    Eigen::Vector3d(100.4, 51.5, -2.9), Eigen::Vector3d(100.2, 50.3, -1.8)});
      for (auto& x : nodes) x += 0.08 * Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
      auto f = tet_jacobian_coefficients(p, nodes.data());
      auto e = exact_tet_jacobian_coefficients(p, nodes.data());
      ASSERT_EQ(f.value.size(), e.size());
      for (std::size_t i = 0; i < e.size(); ++i) {
        // e is the exact value within one ulp.
        EXPECT_LE(std::abs(f.value[i] - e[i]), f.radius[i] + 2.3e-16 * std::abs(e[i])) << p << " " << i;
        EXPECT_LT(f.radius[i], 1e-9 * (1 + std::abs(e[i])));
      }
    }
}

TEST(Certificate, CoefficientsEqualSampledAndConvertedDeterminant) {
  std::mt19937 rng(99);
  std::normal_distribution<double> noise(0, 0.05);
  for (int p = 2; p <= 3; ++p) {
    auto nodes = straight_tet(p);
    for (auto& x : nodes) x += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    const int deg = 3 * (p - 1);
    const auto& lat = lattice(3, deg);
    // M[i][j] = B_j(x_i) on the degree-3(P-1) lattice; solve M c = det J(x).
    Eigen::MatrixXd m(lat.size(), lat.size());
    Eigen::VectorXd samples(lat.size());
    for (int i = 0; i < lat.size(); ++i) {
      const auto& a = lat[i];
      const double lambda[4] = {double(a[0]) / deg, double(a[1]) / deg, double(a[2]) / deg, double(a[3]) / deg};
      auto b = bernstein_basis(3, deg, lambda);
      for (int j = 0; j < lat.size(); ++j) m(i, j) = b[j];
      samples[i] = tet_jacobian(p, nodes.data(), Eigen::Vector3d(lambda[1], lambda[2], lambda[3])).determinant();
    }
    Eigen::VectorXd converted = m.fullPivLu().solve(samples);
    auto f = tet_jacobian_coefficients(p, nodes.data());
    for (int i = 0; i < lat.size(); ++i) EXPECT_NEAR(f.value[i], converted[i], 1e-10) << p << " " << i;
  }
}

// Randomized: perturbed elements of orders 2..4; the certificate must never
// claim positive when a dense sample finds det J <= 0, and the mix must
// contain both outcomes (so the test can fail).
TEST(Certificate, NeverPositiveWhenASampleIsNegative) {
  std::mt19937 rng(2024);
  int positive = 0, invalid = 0, undecided = 0, sampled_negative = 0, positive_after_subdivision = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int p = 2 + trial % 3;
    std::uniform_real_distribution<double> amp(0.0, 0.35);
    std::normal_distribution<double> noise(0, 1);
    auto nodes = straight_tet(p);
    const double a = amp(rng);
    for (std::size_t i = 4; i < nodes.size(); ++i) nodes[i] += a * Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    CertificateOptions o;
    o.max_depth = 12;
    o.max_pieces = 400;
    auto cert = certify_tet(p, nodes.data(), o);
    const double smin = sampled_min_det(p, nodes, 8);
    if (smin <= 0) {
      ++sampled_negative;
      ASSERT_NE(cert.validity, Validity::positive) << "trial " << trial << " sampled min " << smin;
    }
    if (cert.validity == Validity::positive) {
      ++positive;
      positive_after_subdivision += cert.pieces > 1;
      EXPECT_LE(cert.min_det_lower, smin);
    }
    if (cert.validity == Validity::invalid) {
      ++invalid;
      // An invalid verdict comes with a point where det J <= 0: its upper bound.
      EXPECT_LE(cert.min_det_upper, 0);
    }
    if (cert.validity == Validity::undecided) ++undecided;
  }
  EXPECT_GT(positive, 300);
  EXPECT_GT(sampled_negative, 300);
  EXPECT_GT(invalid, 300);
  EXPECT_GT(positive_after_subdivision, 10); // the heap subdivision is exercised
  RecordProperty("positive", positive);
  RecordProperty("positive_after_subdivision", positive_after_subdivision);
  RecordProperty("invalid", invalid);
  RecordProperty("undecided", undecided);
}

// ---- slabs -------------------------------------------------------------------

namespace {

// Middle triangle nodes of degree k: the flat triangle (0,0,0),(1,0,0),(0,1,0)
// with a bump of height h (normal +z).
std::vector<Eigen::Vector3d> middle_nodes(int k, double h) {
  std::vector<Eigen::Vector3d> m;
  for (int i = 0; i < triangle_node_count(k); ++i) {
    auto q = triangle_node(k, i);
    const double u = double(q[0]) / k, v = double(q[1]) / k;
    m.emplace_back(u, v, h * u * v * (1 - u - v) * 27);
  }
  return m;
}

double sampled_slab_min(int k, const std::vector<Eigen::Vector3d>& m, const std::array<Eigen::Vector3d, 3>& cap,
                        double sign) {
  double best = HUGE_VAL;
  const int d = 10;
  for (int a = 0; a <= d; ++a)
    for (int b = 0; a + b <= d; ++b)
      for (int c = 0; c <= d; ++c) {
        Eigen::Vector2d uv(double(a) / d, double(b) / d);
        const double t = double(c) / d;
        auto jm = triangle_jacobian(k, m.data(), uv);
        Eigen::Vector3d cu = cap[1] - cap[0], cv = cap[2] - cap[0];
        Eigen::Vector3d cp = cap[0] + uv[0] * cu + uv[1] * cv;
        Eigen::Matrix3d j;
        j.col(0) = (1 - t) * jm.col(0) + t * cu;
        j.col(1) = (1 - t) * jm.col(1) + t * cv;
        j.col(2) = cp - triangle_point(k, m.data(), uv);
        best = std::min(best, sign * j.determinant());
      }
  return best;
}

} // namespace

TEST(SlabCertificate, PositiveTopAndBottomAndInvalidWhenTheMiddleCrossesTheCap) {
  for (int k = 1; k <= 5; ++k) {
    auto m = middle_nodes(k, 0.05);
    std::array<Eigen::Vector3d, 3> top = {Eigen::Vector3d(0, 0, 0.3), Eigen::Vector3d(1, 0, 0.3),
                                          Eigen::Vector3d(0, 1, 0.3)};
    std::array<Eigen::Vector3d, 3> bottom = {Eigen::Vector3d(0, 0, -0.3), Eigen::Vector3d(1, 0, -0.3),
                                             Eigen::Vector3d(0, 1, -0.3)};
    auto ct = certify_slab(k, m.data(), top, SlabSide::top);
    auto cb = certify_slab(k, m.data(), bottom, SlabSide::bottom);
    EXPECT_EQ(ct.validity, Validity::positive) << k;
    EXPECT_EQ(cb.validity, Validity::positive) << k;
    EXPECT_LE(ct.min_det_lower, sampled_slab_min(k, m, top, 1));
    // The wrong side is invalid.
    EXPECT_EQ(certify_slab(k, m.data(), top, SlabSide::bottom).validity, Validity::invalid);
    if (k >= 3) {
      // A bump poking through the top cap: det J < 0 somewhere.
      auto high = middle_nodes(k, 0.6);
      auto c = certify_slab(k, high.data(), top, SlabSide::top);
      EXPECT_LT(sampled_slab_min(k, high, top, 1), 0);
      EXPECT_NE(c.validity, Validity::positive) << k;
    }
  }
}

TEST(SlabCertificate, CollapsedPillarAtASingularVertex) {
  for (int k = 1; k <= 4; ++k) {
    auto m = middle_nodes(k, 0.02);
    std::array<Eigen::Vector3d, 3> top = {m[0], Eigen::Vector3d(1, 0, 0.3), Eigen::Vector3d(0, 1, 0.3)};
    // Without declaring the collapse, det J = 0 on the pillar: invalid.
    EXPECT_EQ(certify_slab(k, m.data(), top, SlabSide::top).validity, Validity::invalid);
    auto c = certify_slab(k, m.data(), top, SlabSide::top, {true, false, false});
    EXPECT_EQ(c.validity, Validity::positive) << k;
  }
}

TEST(SlabCertificate, RandomSlabsNeverPositiveWhenASampleIsNegative) {
  std::mt19937 rng(77);
  std::normal_distribution<double> noise(0, 1);
  std::uniform_real_distribution<double> amp(0, 0.3);
  int positive = 0, negative = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const int k = 1 + trial % 4;
    auto m = middle_nodes(k, 0);
    const double a = amp(rng);
    for (auto& x : m) x += a * Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    std::array<Eigen::Vector3d, 3> top = {Eigen::Vector3d(0, 0, 0.3), Eigen::Vector3d(1, 0, 0.3),
                                          Eigen::Vector3d(0, 1, 0.3)};
    CertificateOptions o;
    o.max_depth = 12;
    o.max_pieces = 300;
    auto c = certify_slab(k, m.data(), top, SlabSide::top, {false, false, false}, o);
    const double s = sampled_slab_min(k, m, top, 1);
    if (s <= 0) {
      ++negative;
      ASSERT_NE(c.validity, Validity::positive) << trial;
    }
    if (c.validity == Validity::positive) {
      ++positive;
      EXPECT_LE(c.min_det_lower, s);
    }
  }
  EXPECT_GT(positive, 60);
  EXPECT_GT(negative, 60);
}

// Nearly flat tets: the float coefficients are within their radius of zero,
// so the sign is decided by the exact rational path.
TEST(Certificate, NearlyFlatTetsAreDecidedExactly) {
  // Every node exactly representable (dyadic): a flat base at z = 0 and the
  // apex side at height 2^-61, far below the float radius of the coefficients.
  for (int p : {2, 3, 4}) {
    std::vector<Eigen::Vector3d> nodes;
    for (int i = 0; i < tet_node_count(p); ++i) {
      auto q = tet_node(p, i);
      nodes.emplace_back(double(q[0]) / p + 0.25 * q[2] / p, double(q[1]) / p, q[2] * 0x1p-61 / p);
    }
    // p = 3 has non-dyadic lattice points (thirds): the float nodes are then
    // not exactly straight, so only orders 2 and 4 are exactly affine.
    if (p == 3) continue;
    auto cert = certify_tet(p, nodes.data());
    EXPECT_EQ(cert.validity, Validity::positive) << p;
    EXPECT_TRUE(cert.exact) << p;
    EXPECT_GT(cert.min_det_lower, 0);
    auto flat = nodes;
    for (auto& x : flat) x.z() = 0;
    auto f = certify_tet(p, flat.data());
    EXPECT_EQ(f.validity, Validity::invalid) << p;
    EXPECT_LE(f.min_det_upper, 0);
    auto below = nodes;
    for (auto& x : below) x.z() = -x.z();
    EXPECT_EQ(certify_tet(p, below.data()).validity, Validity::invalid) << p;
  }
}

TEST(SlabCertificate, BezierMiddleGivesTheSameDeterminant) {
  for (int k = 1; k <= 6; ++k) {
    auto m = middle_nodes(k, 0.1);
    const auto& bc = basis_change(2, k);
    std::vector<Eigen::Vector3d> bezier(m.size(), Eigen::Vector3d::Zero());
    for (int i = 0; i < int(m.size()); ++i)
      for (int j = 0; j < int(m.size()); ++j) bezier[i] += bc.lagrange_to_bernstein(i, j) * m[j];
    std::array<Eigen::Vector3d, 3> bottom = {Eigen::Vector3d(0, 0, -0.3), Eigen::Vector3d(1, 0, -0.2),
                                             Eigen::Vector3d(0, 1, -0.25)};
    auto a = slab_jacobian_coefficients(k, m.data(), bottom, SlabSide::bottom);
    auto b = slab_jacobian_coefficients(k, bezier.data(), bottom, SlabSide::bottom, MiddleBasis::bezier);
    ASSERT_EQ(a.value.size(), b.value.size());
    for (std::size_t i = 0; i < a.value.size(); ++i) EXPECT_NEAR(a.value[i], b.value[i], 1e-12) << k << " " << i;
    EXPECT_EQ(certify_slab(k, bezier.data(), bottom, SlabSide::bottom, {false, false, false}, {}, MiddleBasis::bezier)
                  .validity,
              Validity::positive);
  }
}
