#include "curvetet/shell/tet_contact.hpp"

#include "curvetet/geometry/predicates.hpp"

#include <algorithm>
#include <array>
#include <vector>

namespace curvetet::shell {

using geometry::orient3d;

namespace {

bool point_in_closed_tet(const Vec3& p, const Vec3* t[4]) {
  return orient3d(p, *t[1], *t[2], *t[3]) >= 0 && orient3d(*t[0], p, *t[2], *t[3]) >= 0 &&
         orient3d(*t[0], *t[1], p, *t[3]) >= 0 && orient3d(*t[0], *t[1], *t[2], p) >= 0;
}

// Whether the triangle's and the tet's boxes are disjoint, or the triangle
// lies strictly outside one face plane of a positive tet: cheap exact
// proofs that the closed sets do not meet (most pairs a caller tries).
bool separated_quickly(const Vec3* tri[3], const Vec3* t[4]) {
  for (int a = 0; a < 3; ++a) {
    const double tri_lo = std::min({(*tri[0])[a], (*tri[1])[a], (*tri[2])[a]});
    const double tri_hi = std::max({(*tri[0])[a], (*tri[1])[a], (*tri[2])[a]});
    const double tet_lo = std::min({(*t[0])[a], (*t[1])[a], (*t[2])[a], (*t[3])[a]});
    const double tet_hi = std::max({(*t[0])[a], (*t[1])[a], (*t[2])[a], (*t[3])[a]});
    if (tri_hi < tet_lo || tet_hi < tri_lo) return true;
  }
  if (orient3d(*t[0], *t[1], *t[2], *t[3]) <= 0) return false;
  for (int l = 0; l < 4; ++l) {
    bool outside = true;
    for (int i = 0; i < 3 && outside; ++i) {
      const Vec3* q[4] = {t[0], t[1], t[2], t[3]};
      q[l] = tri[i];
      outside = orient3d(*q[0], *q[1], *q[2], *q[3]) < 0;
    }
    if (outside) return true;
  }
  return false;
}

// Candidate separating planes all pass through the allowed corners. Each
// one that weakly separates (the triangle's other corners on one closed side,
// the tet's other corners on the other) is oriented so the triangle is on
// its negative side. The sum of their normals separates too, strictly at
// every corner some candidate is strict on (signs add). It proves the
// contact confined to the allowed hull when it is strict on all of the
// tet's other corners (then the tet meets the triangle's closed side only in
// the plane, i.e. in the allowed hull) or on all of the triangle's other
// corners (then the triangle meets the tet's side only in the allowed hull).
// The generator pairs through the apex include the extreme rays of the cone
// of separating normals, so the sum finds a separator whenever one exists.
struct Separation {
  std::vector<const Vec3*> tri_other, tet_other;
  std::vector<char> tri_strict, tet_strict;

  void add_candidate(const Vec3& a, const Vec3& b, const Vec3& c) {
    std::vector<int> st(tri_other.size()), so(tet_other.size());
    for (std::size_t i = 0; i < st.size(); ++i) st[i] = orient3d(a, b, c, *tri_other[i]);
    for (std::size_t i = 0; i < so.size(); ++i) so[i] = orient3d(a, b, c, *tet_other[i]);
    for (int s : {1, -1}) {
      bool weak = true, any = false;
      for (int x : st) weak &= s * x <= 0, any |= x != 0;
      for (int x : so) weak &= s * x >= 0, any |= x != 0;
      if (!weak || !any) continue;
      for (std::size_t i = 0; i < st.size(); ++i) tri_strict[i] |= st[i] != 0;
      for (std::size_t i = 0; i < so.size(); ++i) tet_strict[i] |= so[i] != 0;
      return;
    }
  }
  bool proves() const {
    auto all = [](const std::vector<char>& v) { return std::all_of(v.begin(), v.end(), [](char c) { return c; }); };
    return all(tet_strict) || all(tri_strict);
  }
};

} // namespace

bool triangle_meets_tet(const Vec3* tri[3], const Vec3* tet[4]) {
  if (separated_quickly(tri, tet)) return false;
  for (int i = 0; i < 3; ++i)
    if (point_in_closed_tet(*tri[i], tet)) return true;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      if (geometry::segment_triangle_intersect(*tet[i], *tet[j], *tri[0], *tri[1], *tri[2])) return true;
  static const int faces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  for (const auto& fc : faces)
    for (int e = 0; e < 3; ++e)
      if (geometry::segment_triangle_intersect(*tri[e], *tri[(e + 1) % 3], *tet[fc[0]], *tet[fc[1]], *tet[fc[2]]))
        return true;
  return false;
}

namespace {

// Whether a separating plane proves the triangle meets the tet only within
// conv(tet[i] : in_mask[i]) (one corner or an edge).
bool provably_confined(const Vec3* tri[3], const Vec3* tet[4], const std::array<bool, 4>& in_mask) {
  std::vector<const Vec3*> in;
  Separation sep;
  for (int i = 0; i < 4; ++i) (in_mask[i] ? in : sep.tet_other).push_back(tet[i]);
  for (int i = 0; i < 3; ++i) {
    bool is_allowed = false;
    for (const Vec3* x : in) is_allowed |= *tri[i] == *x;
    if (!is_allowed) sep.tri_other.push_back(tri[i]);
  }
  sep.tri_strict.assign(sep.tri_other.size(), 0);
  sep.tet_strict.assign(sep.tet_other.size(), 0);
  std::vector<const Vec3*> span = sep.tet_other;
  span.insert(span.end(), sep.tri_other.begin(), sep.tri_other.end());
  if (in.size() == 2) {
    for (const Vec3* p : span) sep.add_candidate(*in[0], *in[1], *p);
  } else {
    for (std::size_t i = 0; i < span.size(); ++i)
      for (std::size_t j = i + 1; j < span.size(); ++j) sep.add_candidate(*in[0], *span[i], *span[j]);
  }
  return sep.proves();
}

} // namespace

bool triangle_meets_tet_outside(const Vec3* tri[3], const Vec3* tet[4], const bool allowed[4]) {
  if (!triangle_meets_tet(tri, tet)) return false;
  std::vector<int> ids;
  for (int i = 0; i < 4; ++i)
    if (allowed[i]) ids.push_back(i);
  if (ids.empty() || ids.size() > 2) return true;
  // Contact at one allowed corner, or (with two) along their edge.
  for (int i : ids) {
    std::array<bool, 4> one{};
    one[i] = true;
    if (provably_confined(tri, tet, one)) return false;
  }
  if (ids.size() == 2) {
    std::array<bool, 4> both{};
    both[ids[0]] = both[ids[1]] = true;
    if (provably_confined(tri, tet, both)) return false;
  }
  return true;
}

std::array<bool, 4> section_allowed_corners(const SlabTet& tet, bool middle_is_upper) {
  std::array<bool, 4> out{};
  for (int i = 0; i < 4; ++i) {
    const int c = tet.corners[i];
    out[i] = (c >= 3) == middle_is_upper && c % 3 != tet.pillar;
  }
  return out;
}

} // namespace curvetet::shell
