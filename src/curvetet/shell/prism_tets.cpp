#include "curvetet/shell/prism_tets.hpp"

#include <algorithm>

namespace curvetet::shell {

namespace {

// Sign of the reference-slab volume of a tet (integer coordinates: exact).
int reference_orientation(const std::array<int, 4>& t) {
  std::array<std::array<double, 3>, 4> p;
  for (int i = 0; i < 4; ++i) p[i] = reference_corner(t[i]);
  double m[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m[i][j] = p[i + 1][j] - p[0][j];
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  return (det > 0) - (det < 0);
}

SlabTet oriented(std::array<int, 4> t) {
  if (reference_orientation(t) < 0) std::swap(t[2], t[3]);
  int pillar = -1;
  for (int k = 0; k < 3; ++k)
    if (std::find(t.begin(), t.end(), k) != t.end() && std::find(t.begin(), t.end(), k + 3) != t.end()) pillar = k;
  return {t, pillar};
}

std::array<SlabTet, 12> make_all_slab_tets() {
  std::array<SlabTet, 12> out;
  int n = 0;
  for (int a = 0; a < 6; ++a)
    for (int b = a + 1; b < 6; ++b)
      for (int c = b + 1; c < 6; ++c)
        for (int d = c + 1; d < 6; ++d) {
          std::array<int, 4> t{a, b, c, d};
          int pillars = 0;
          for (int k = 0; k < 3; ++k)
            pillars += std::count(t.begin(), t.end(), k) && std::count(t.begin(), t.end(), k + 3);
          if (pillars == 1) out[n++] = oriented(t);
        }
  return out;
}

} // namespace

std::array<double, 3> reference_corner(int c) {
  const int k = c % 3;
  return {k == 1 ? 1.0 : 0.0, k == 2 ? 1.0 : 0.0, c >= 3 ? 1.0 : 0.0};
}

const std::array<SlabTet, 12>& all_slab_tets() {
  static const std::array<SlabTet, 12> tets = make_all_slab_tets();
  return tets;
}

namespace {

// s0, s1, s2: local corners sorted by global id. Diagonals go from the
// lower corner of the smaller id to the upper corner of the larger one:
// tets {L0 L1 L2 U2}, {L0 L1 U1 U2}, {L0 U0 U1 U2} (in sorted order).
std::array<SlabTet, 3> split_for_order(const std::array<int, 3>& s) {
  return {oriented({s[0], s[1], s[2], s[2] + 3}), oriented({s[0], s[1], s[1] + 3, s[2] + 3}),
          oriented({s[0], s[0] + 3, s[1] + 3, s[2] + 3})};
}

} // namespace

std::array<SlabTet, 3> canonical_split(const std::array<int, 3>& global_ids) {
  // One split per order of the three ids (the prism checks ask millions of times).
  static const auto splits = [] {
    std::array<std::array<SlabTet, 3>, 9> table{}; // indexed by 3 s0 + s1
    std::array<int, 3> s{0, 1, 2};
    do table[3 * s[0] + s[1]] = split_for_order(s);
    while (std::next_permutation(s.begin(), s.end()));
    return table;
  }();
  std::array<int, 3> s{0, 1, 2};
  std::sort(s.begin(), s.end(), [&](int i, int j) { return global_ids[i] < global_ids[j]; });
  return splits[3 * s[0] + s[1]];
}

} // namespace curvetet::shell
