#include "curvetet/volume/descent_terms.hpp"

#include "curvetet/core/wide_vectors.hpp"
#include "curvetet/highorder/amips_frames.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace curvetet::volume {
namespace {

constexpr int kBlock = 8;
using Block = double[kBlock];

// x[j] = x[j]^p for p >= 1, by squarings.
[[gnu::always_inline]] inline void raise(Block x, int p) {
  Block r;
  for (int j = 0; j < kBlock; ++j) r[j] = 1;
  for (; p > 0; p >>= 1) {
    if (p & 1)
      for (int j = 0; j < kBlock; ++j) r[j] *= x[j];
    if (p > 1)
      for (int j = 0; j < kBlock; ++j) x[j] *= x[j];
  }
  for (int j = 0; j < kBlock; ++j) x[j] = r[j];
}

// The terms of points [0, count) of one block; m[e][j] = entry e
// (column-major) of point j's frame. Returns false if a det <= 0.
CURVETET_WIDE_VECTORS bool block_terms(const DescentTerms& s, const Block* m, int count, Block energy, Block* dk,
                                       double& worst_amips, double& worst_ratio) {
  Block det, norm2, det23;
  for (int j = 0; j < kBlock; ++j) {
    det[j] = m[0][j] * (m[4][j] * m[8][j] - m[7][j] * m[5][j]) - m[3][j] * (m[1][j] * m[8][j] - m[7][j] * m[2][j]) +
             m[6][j] * (m[1][j] * m[5][j] - m[4][j] * m[2][j]);
    norm2[j] = 0;
    for (int e = 0; e < 9; ++e) norm2[j] += m[e][j] * m[e][j];
  }
  for (int j = 0; j < count; ++j)
    if (!(det[j] > 0)) return false;
  for (int j = 0; j < kBlock; ++j) det23[j] = std::cbrt(det[j] * det[j]);
  Block a, amips_term;
  for (int j = 0; j < kBlock; ++j) {
    a[j] = norm2[j] / det23[j];
    amips_term[j] = a[j] / s.amips_ref;
  }
  for (int j = 0; j < count; ++j) worst_amips = std::max(worst_amips, amips_term[j]);
  raise(amips_term, s.power);
  // K u_i for the six edges, and |K u_i|^2.
  Block ku[6][3], length2[6];
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d& u = s.edges[i];
    for (int r = 0; r < 3; ++r)
      for (int j = 0; j < kBlock; ++j) ku[i][r][j] = m[r][j] * u[0] + m[3 + r][j] * u[1] + m[6 + r][j] * u[2];
    for (int j = 0; j < kBlock; ++j)
      length2[i][j] = ku[i][0][j] * ku[i][0][j] + ku[i][1][j] * ku[i][1][j] + ku[i][2][j] * ku[i][2][j];
  }
  // Corner c's term: r^(p/2), r = sJ0^2 prod |K u_i|^2 / (2 det J^2).
  Block scale, corner[4];
  for (int j = 0; j < kBlock; ++j) {
    const double det_j = det[j] * s.reference_det;
    scale[j] = s.sj_ref * s.sj_ref / (2 * det_j * det_j);
  }
  for (int c = 0; c < 4; ++c) {
    const auto& e = highorder::AmipsFrames::kCornerEdges[c];
    for (int j = 0; j < kBlock; ++j) corner[c][j] = scale[j] * length2[e[0]][j] * length2[e[1]][j] * length2[e[2]][j];
    for (int j = 0; j < count; ++j) worst_ratio = std::max(worst_ratio, corner[c][j]);
    raise(corner[c], s.power / 2);
  }
  for (int j = 0; j < kBlock; ++j) energy[j] = amips_term[j] + corner[0][j] + corner[1][j] + corner[2][j] + corner[3][j];
  if (!dk) return true;
  // dAMIPS-term/dK = (p t / a) / det^(2/3) (2 K - 2/3 |K|^2 K^-T); with
  // J = K W, d log sJ / dK = K^-T - sum_i (K u_i) u_i^T / |K u_i|^2 over
  // the corner's edges, so corner terms add -p t K^-T and, per edge,
  // p (sum of its two corners' terms) / |K u_i|^2 (K u_i) u_i^T.
  Block inv[9]; // K^-T = cof(K) / det, column-major
  for (int j = 0; j < kBlock; ++j) {
    const double d = det[j];
    inv[0][j] = (m[4][j] * m[8][j] - m[7][j] * m[5][j]) / d;
    inv[1][j] = (m[6][j] * m[5][j] - m[3][j] * m[8][j]) / d;
    inv[2][j] = (m[3][j] * m[7][j] - m[6][j] * m[4][j]) / d;
    inv[3][j] = (m[7][j] * m[2][j] - m[1][j] * m[8][j]) / d;
    inv[4][j] = (m[0][j] * m[8][j] - m[6][j] * m[2][j]) / d;
    inv[5][j] = (m[6][j] * m[1][j] - m[0][j] * m[7][j]) / d;
    inv[6][j] = (m[1][j] * m[5][j] - m[4][j] * m[2][j]) / d;
    inv[7][j] = (m[3][j] * m[2][j] - m[0][j] * m[5][j]) / d;
    inv[8][j] = (m[0][j] * m[4][j] - m[3][j] * m[1][j]) / d;
  }
  const double p = s.power;
  Block amips_factor, inv_factor, edge_factor[6];
  for (int j = 0; j < kBlock; ++j) {
    amips_factor[j] = (p * amips_term[j] / a[j]) / det23[j];
    inv_factor[j] = amips_factor[j] * (2.0 / 3.0) * norm2[j] + p * (corner[0][j] + corner[1][j] + corner[2][j] + corner[3][j]);
  }
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < kBlock; ++j) edge_factor[i][j] = 0;
  for (int c = 0; c < 4; ++c)
    for (int i : highorder::AmipsFrames::kCornerEdges[c])
      for (int j = 0; j < kBlock; ++j) edge_factor[i][j] += corner[c][j];
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < kBlock; ++j) edge_factor[i][j] = p * edge_factor[i][j] / length2[i][j];
  for (int col = 0; col < 3; ++col)
    for (int r = 0; r < 3; ++r) {
      const int e = 3 * col + r;
      for (int j = 0; j < kBlock; ++j) {
        double v = 2 * amips_factor[j] * m[e][j] - inv_factor[j] * inv[e][j];
        for (int i = 0; i < 6; ++i) v += edge_factor[i][j] * ku[i][r][j] * s.edges[i][col];
        dk[e][j] = v;
      }
    }
  return true;
}

} // namespace

double DescentTerms::operator()(const Eigen::Matrix3d* k, int n, Eigen::Matrix3d* dk, double& worst) const {
  double sum = 0, worst_amips = 0, worst_ratio = 0;
  for (int q0 = 0; q0 < n; q0 += kBlock) {
    const int count = std::min(kBlock, n - q0);
    Block m[9], energy, grad[9];
    for (int e = 0; e < 9; ++e)
      for (int j = 0; j < kBlock; ++j) m[e][j] = j < count ? k[q0 + j].data()[e] : (e % 4 == 0 ? 1.0 : 0.0);
    if (!block_terms(*this, m, count, energy, dk ? grad : nullptr, worst_amips, worst_ratio))
      return std::numeric_limits<double>::infinity();
    for (int j = 0; j < count; ++j) sum += energy[j];
    if (dk)
      for (int j = 0; j < count; ++j)
        for (int e = 0; e < 9; ++e) dk[q0 + j].data()[e] = grad[e][j];
  }
  worst = std::max({worst, worst_amips, std::sqrt(worst_ratio)});
  return sum;
}

} // namespace curvetet::volume
