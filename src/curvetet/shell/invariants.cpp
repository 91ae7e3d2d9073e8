#include "curvetet/shell/invariants.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/geometry/box_pairs.hpp"
#include "curvetet/geometry/predicates.hpp"
#include "curvetet/shell/cap_view.hpp"
#include "curvetet/shell/exact_dot.hpp"
#include "curvetet/shell/prism_tets.hpp"
#include "curvetet/shell/tet_contact.hpp"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <numeric>

namespace curvetet::shell {

using geometry::orient3d;

std::string_view to_string(InvariantKind k) {
  switch (k) {
    case InvariantKind::prism_positivity: return "prism_positivity";
    case InvariantKind::section: return "section";
    case InvariantKind::caps_intersection_free: return "caps_intersection_free";
  }
  return "?";
}

const Vec3& slab_lower(const Shell& s, Slab slab, int v) { return slab == Slab::bottom ? s.bottom[v] : s.middle[v]; }
const Vec3& slab_upper(const Shell& s, Slab slab, int v) { return slab == Slab::bottom ? s.middle[v] : s.top[v]; }
bool zero_pillar(const Shell& s, Slab slab, int v) { return slab_lower(s, slab, v) == slab_upper(s, slab, v); }

namespace {

constexpr Slab kSlabs[2] = {Slab::bottom, Slab::top};

// Physical position of local slab corner c (0..5) of prism f.
const Vec3& corner(const Shell& s, Slab slab, const Tri& f, int c) {
  return c < 3 ? slab_lower(s, slab, f[c]) : slab_upper(s, slab, f[c - 3]);
}

// Runs `failing(i)` over items in parallel; returns the failing ones, sorted.
template <class Fn>
std::vector<int> collect_failing(std::span<const int> items, Fn&& failing) {
  std::vector<char> bad(items.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, items.size(), 64), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) bad[i] = failing(items[i]);
  });
  std::vector<int> out;
  for (std::size_t i = 0; i < items.size(); ++i)
    if (bad[i]) out.push_back(items[i]);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::vector<int> all_prisms(const Shell& s) {
  std::vector<int> ids(s.num_prisms());
  std::iota(ids.begin(), ids.end(), 0);
  return ids;
}

bool point_in_closed_tet(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return orient3d(p, b, c, d) >= 0 && orient3d(a, p, c, d) >= 0 && orient3d(a, b, p, d) >= 0 &&
         orient3d(a, b, c, p) >= 0;
}

// Exact: p in the closed union of the canonical tets of prism f (both slabs).
bool point_in_prism(const Shell& s, int f, const Vec3& p) {
  const Tri& t = s.faces[f];
  for (Slab slab : kSlabs)
    for (const auto& tet : canonical_split(t)) {
      if (zero_pillar(s, slab, t[tet.pillar])) continue;
      const auto& c = tet.corners;
      if (point_in_closed_tet(p, corner(s, slab, t, c[0]), corner(s, slab, t, c[1]), corner(s, slab, t, c[2]),
                              corner(s, slab, t, c[3])))
        return true;
    }
  return false;
}

} // namespace

// ---- 1 ----
bool prism_positive(const Shell& s, int prism) {
  const Tri& t = s.faces[prism];
  for (Slab slab : kSlabs)
    for (const auto& tet : all_slab_tets()) {
      if (zero_pillar(s, slab, t[tet.pillar])) continue;
      const auto& c = tet.corners;
      if (orient3d(corner(s, slab, t, c[0]), corner(s, slab, t, c[1]), corner(s, slab, t, c[2]),
                   corner(s, slab, t, c[3])) <= 0)
        return false;
    }
  return true;
}

std::vector<int> non_positive_prisms(const Shell& s, std::span<const int> prisms) {
  return collect_failing(prisms, [&](int f) { return !prism_positive(s, f); });
}
std::vector<int> non_positive_prisms(const Shell& s) {
  const auto ids = all_prisms(s);
  return non_positive_prisms(s, ids);
}

// ---- 2 ----
std::vector<std::vector<int>> input_trackers(const Shell& s) {
  std::vector<std::vector<int>> out(s.input.num_faces());
  for (int f = 0; f < s.num_prisms(); ++f)
    for (int t : s.tracked[f]) out[t].push_back(f);
  return out;
}

bool prism_section_valid(const Shell& s, int prism, const std::vector<std::vector<int>>& trackers) {
  const Tri& f = s.faces[prism];
  for (int t : s.tracked[prism]) {
    const auto [a, b, c] = straight_triangle(s, t);
    for (Slab slab : kSlabs)
      for (int k = 0; k < 3; ++k) {
        if (zero_pillar(s, slab, f[k])) continue;
        if (normal_dot_sign(a, b, c, slab_lower(s, slab, f[k]), slab_upper(s, slab, f[k])) > 0) continue;
        // Pillar k points the wrong way: t must not meet any tet holding it
        // (except along lateral fibres, see section_allowed_corners).
        for (const auto& tet : all_slab_tets()) {
          if (tet.pillar != k) continue;
          const auto& q = tet.corners;
          const Vec3 &p0 = corner(s, slab, f, q[0]), &p1 = corner(s, slab, f, q[1]), &p2 = corner(s, slab, f, q[2]),
                     &p3 = corner(s, slab, f, q[3]);
          // The section is only defined on a positive prism.
          if (orient3d(p0, p1, p2, p3) <= 0) return false;
          const Vec3* tri[3] = {&a, &b, &c};
          const Vec3* v[4] = {&p0, &p1, &p2, &p3};
          const auto allowed = section_allowed_corners(tet, slab == Slab::bottom);
          if (triangle_meets_tet_outside(tri, v, allowed.data())) return false;
        }
      }
    for (const Vec3* p : {&a, &b, &c}) {
      // Fast exact path: a corner equal to a middle vertex of this prism is
      // a vertex of the closed prism.
      if (*p == s.middle[f[0]] || *p == s.middle[f[1]] || *p == s.middle[f[2]]) continue;
      bool inside = false;
      for (int g : trackers[t])
        if (point_in_prism(s, g, *p)) {
          inside = true;
          break;
        }
      if (!inside) return false;
    }
  }
  return true;
}

std::vector<int> invalid_section_prisms(const Shell& s, std::span<const int> prisms,
                                        const std::vector<std::vector<int>>& trackers) {
  return collect_failing(prisms, [&](int f) { return !prism_section_valid(s, f, trackers); });
}
std::vector<int> invalid_section_prisms(const Shell& s) {
  const auto ids = all_prisms(s);
  return invalid_section_prisms(s, ids, input_trackers(s));
}

// ---- 3 ----
std::vector<std::pair<int, int>> decide_cap_pairs(const CapView& view, std::vector<std::pair<int, int>> candidates,
                                                  const std::function<void()>& poll) {
  std::vector<char> hit(candidates.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, candidates.size(), 256), [&](const auto& r) {
    if (poll) poll();
    for (std::size_t k = r.begin(); k != r.end(); ++k)
      hit[k] = view.intersect(candidates[k].first, candidates[k].second);
  });
  std::vector<std::pair<int, int>> out;
  for (std::size_t k = 0; k < candidates.size(); ++k)
    if (hit[k]) out.push_back(candidates[k]);
  std::sort(out.begin(), out.end());
  return out;
}

namespace {

std::vector<geometry::Box3> cap_boxes(const CapView& view, const std::vector<int>& caps) {
  std::vector<geometry::Box3> boxes(caps.size());
  tbb::parallel_for(std::size_t(0), caps.size(), [&](std::size_t i) { boxes[i] = view.box(caps[i]); });
  return boxes;
}

} // namespace

std::vector<std::pair<int, int>> cap_intersections(const Shell& s, std::span<const int> prisms) {
  const CapView view{s, s.num_prisms(), s.num_vertices()};
  std::vector<int> all(2 * view.F), mine;
  std::iota(all.begin(), all.end(), 0);
  for (int f : prisms) {
    mine.push_back(f);
    mine.push_back(f + view.F);
  }
  std::sort(mine.begin(), mine.end());
  mine.erase(std::unique(mine.begin(), mine.end()), mine.end());
  const auto pairs = geometry::overlapping_pairs(cap_boxes(view, mine), cap_boxes(view, all));
  // A pair of two queried caps is reported twice: keep it from its smaller cap.
  std::vector<char> queried(all.size(), 0);
  for (int c : mine) queried[c] = 1;
  std::vector<std::pair<int, int>> candidates;
  candidates.reserve(pairs.size());
  for (auto [i, j] : pairs) {
    const int a = mine[i], b = all[j];
    if (a != b && (a < b || !queried[b])) candidates.emplace_back(std::min(a, b), std::max(a, b));
  }
  return decide_cap_pairs(view, std::move(candidates));
}

std::vector<std::pair<int, int>> cap_intersections(const Shell& s) {
  const CapView view{s, s.num_prisms(), s.num_vertices()};
  std::vector<int> all(2 * view.F);
  std::iota(all.begin(), all.end(), 0);
  auto pairs = geometry::overlapping_pairs(cap_boxes(view, all));
  return decide_cap_pairs(view, std::move(pairs));
}

// ---- all ----
std::vector<InvariantViolation> check_shell(const Shell& s) {
  std::vector<InvariantViolation> out;
  for (int f : non_positive_prisms(s)) out.push_back({InvariantKind::prism_positivity, f});
  for (int f : invalid_section_prisms(s)) out.push_back({InvariantKind::section, f});
  const int F = s.num_prisms();
  for (auto [a, b] : cap_intersections(s)) out.push_back({InvariantKind::caps_intersection_free, a % F, b % F});
  return out;
}

void require_valid_shell(const Shell& s, std::string_view stage) {
  const auto bad = check_shell(s);
  if (bad.empty()) return;
  std::string list;
  for (std::size_t i = 0; i < bad.size() && i < 10; ++i)
    list += fmt::format(" {}(prism {}{})", to_string(bad[i].kind), bad[i].prism,
                        bad[i].other >= 0 ? fmt::format(", {}", bad[i].other) : "");
  throw Error(ExitCode::internal,
              fmt::format("shell invariants violated after {}: {} violation(s):{}", stage, bad.size(), list));
}

} // namespace curvetet::shell
