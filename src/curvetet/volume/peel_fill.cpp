#include "curvetet/volume/peel_fill.hpp"

#include "curvetet/core/log.hpp"
#include "curvetet/geometry/predicates.hpp"
#include "curvetet/geometry/triangle_pair.hpp"
#include "curvetet/volume/mesh_keys.hpp"

#include <algorithm>
#include <optional>
#include <unordered_map>
#include <unordered_set>

namespace curvetet::volume {
namespace {

struct Bounds {
  mesh::Vec3 lo, hi;
  bool overlaps(const Bounds& o) const {
    return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all();
  }
};
template <std::size_t N>
Bounds bounds_of(const std::vector<mesh::Vec3>& p, const std::array<int, N>& ids) {
  Bounds b{p[ids[0]], p[ids[0]]};
  for (int i : ids) {
    b.lo = b.lo.cwiseMin(p[i]);
    b.hi = b.hi.cwiseMax(p[i]);
  }
  return b;
}

// The same three ids in the same cyclic order.
bool same_orientation(const mesh::Tri& f, const mesh::Tri& g) {
  for (int r = 0; r < 3; ++r)
    if (f[0] == g[r] && f[1] == g[(r + 1) % 3] && f[2] == g[(r + 2) % 3]) return true;
  return false;
}

// The faces of positive tet t, each oriented to see t on its positive side.
std::array<mesh::Tri, 4> inward_faces(const std::array<int, 4>& t) {
  return {mesh::Tri{t[0], t[1], t[2]}, mesh::Tri{t[0], t[3], t[1]}, mesh::Tri{t[0], t[2], t[3]},
          mesh::Tri{t[1], t[3], t[2]}};
}

// Shape in doubles, for ordering candidates only: volume over the cube of
// the root mean square edge (scale-free, 0 for flat tets).
double shape(const std::vector<mesh::Vec3>& p, const std::array<int, 4>& t) {
  const mesh::Vec3 &a = p[t[0]], &b = p[t[1]], &c = p[t[2]], &d = p[t[3]];
  const double volume = (b - a).cross(c - a).dot(d - a);
  const double s = (b - a).squaredNorm() + (c - a).squaredNorm() + (d - a).squaredNorm() + (c - b).squaredNorm() +
                   (d - b).squaredNorm() + (d - c).squaredNorm();
  return s > 0 ? volume / (s * std::sqrt(s)) : 0;
}

class Front {
public:
  Front(const std::vector<mesh::Vec3>& p, const std::vector<mesh::Tri>& faces) : p_(p) {
    for (const auto& f : faces) add(f);
  }

  bool empty() const { return alive_count_ == 0; }
  int size() const { return static_cast<int>(faces_.size()); }
  bool alive(int i) const { return alive_[i]; }
  const mesh::Tri& face(int i) const { return faces_[i]; }

  // The alive faces on edge (a, b).
  std::vector<int> around_edge(int a, int b) const {
    std::vector<int> out;
    if (const auto it = by_edge_.find(edge_key(a, b)); it != by_edge_.end())
      for (int i : it->second)
        if (alive_[i]) out.push_back(i);
    return out;
  }

  std::vector<int> vertices() const {
    std::vector<int> out;
    for (const auto& [v, count] : degree_)
      if (count > 0) out.push_back(v);
    std::sort(out.begin(), out.end()); // the same tets whatever the hash order
    return out;
  }

  // How many of t's faces are front faces (either way round).
  int matches(const std::array<int, 4>& t) const {
    int n = 0;
    for (const auto& f : inward_faces(t)) n += find(f) >= 0;
    return n;
  }

  // The front faces that tet t would consume, or nullopt when t may not be
  // added (see peel_fill.hpp).
  std::optional<std::vector<int>> consumed_by(const std::array<int, 4>& t) const {
    if (geometry::orient3d(p_[t[0]], p_[t[1]], p_[t[2]], p_[t[3]]) <= 0) return std::nullopt;
    std::vector<int> matched;
    std::vector<mesh::Tri> open;
    for (const auto& f : inward_faces(t)) {
      const int j = find(f);
      if (j < 0) {
        open.push_back(f);
      } else if (same_orientation(f, faces_[j])) {
        matched.push_back(j);
      } else {
        return std::nullopt; // t lies behind that front face: outside the region
      }
    }
    const Bounds box = bounds_of(p_, t);
    for (const auto& [v, count] : degree_) {
      if (count == 0 || std::find(t.begin(), t.end(), v) != t.end()) continue;
      const mesh::Vec3& x = p_[v];
      if ((x.array() < box.lo.array()).any() || (x.array() > box.hi.array()).any()) continue;
      const auto sides = inward_faces(t);
      if (std::all_of(sides.begin(), sides.end(), [&](const mesh::Tri& f) {
            return geometry::orient3d(p_[f[0]], p_[f[1]], p_[f[2]], x) >= 0;
          }))
        return std::nullopt;
    }
    for (const auto& f : open) {
      const std::array<mesh::Vec3, 3> a{p_[f[0]], p_[f[1]], p_[f[2]]};
      const Bounds fb = bounds_of(p_, f);
      for (int j = 0; j < size(); ++j) {
        if (!alive_[j] || !fb.overlaps(bounds_[j])) continue;
        const auto& g = faces_[j];
        const std::array<mesh::Vec3, 3> b{p_[g[0]], p_[g[1]], p_[g[2]]};
        if (geometry::triangles_intersect_improperly(a, b, geometry::shared_corners(f, g))) return std::nullopt;
      }
    }
    return matched;
  }

  // Adds t: its consumed faces leave, its other faces join reversed.
  // Returns how many faces joined (for undo_tet).
  int add_tet(const std::array<int, 4>& t, const std::vector<int>& consumed) {
    for (int j : consumed) remove(j);
    int added = 0;
    for (const auto& f : inward_faces(t))
      if (std::none_of(consumed.begin(), consumed.end(),
                       [&](int j) { return face_key(f[0], f[1], f[2]) == key(faces_[j]); })) {
        add({f[0], f[2], f[1]});
        ++added;
      }
    return added;
  }
  // Takes back the last add_tet(t, consumed) that added `added` faces.
  void undo_tet(const std::vector<int>& consumed, int added) {
    for (; added > 0; --added) pop_last();
    for (int j : consumed) revive(j);
  }

  std::vector<mesh::Tri> alive_faces() const {
    std::vector<mesh::Tri> out;
    for (int i = 0; i < size(); ++i)
      if (alive_[i]) out.push_back(faces_[i]);
    return out;
  }

private:
  static std::uint64_t key(const mesh::Tri& f) { return face_key(f[0], f[1], f[2]); }

  int find(const mesh::Tri& f) const {
    if (const auto it = by_key_.find(key(f)); it != by_key_.end())
      for (int i : it->second)
        if (alive_[i]) return i;
    return -1;
  }
  void add(const mesh::Tri& f) {
    const int i = size();
    faces_.push_back(f);
    alive_.push_back(1);
    bounds_.push_back(bounds_of(p_, f));
    by_key_[key(f)].push_back(i);
    for (int e = 0; e < 3; ++e) {
      by_edge_[edge_key(f[e], f[(e + 1) % 3])].push_back(i);
      ++degree_[f[e]];
    }
    ++alive_count_;
  }
  void remove(int i) {
    alive_[i] = 0;
    for (int v : faces_[i]) --degree_[v];
    --alive_count_;
  }
  void revive(int i) {
    alive_[i] = 1;
    for (int v : faces_[i]) ++degree_[v];
    ++alive_count_;
  }
  // Undoes the last add() (whose index is the last in every list).
  void pop_last() {
    const auto f = faces_.back();
    remove(size() - 1);
    by_key_[key(f)].pop_back();
    for (int e = 0; e < 3; ++e) by_edge_[edge_key(f[e], f[(e + 1) % 3])].pop_back();
    faces_.pop_back();
    alive_.pop_back();
    bounds_.pop_back();
  }

  const std::vector<mesh::Vec3>& p_;
  std::vector<mesh::Tri> faces_;
  std::vector<char> alive_;
  std::vector<Bounds> bounds_;
  std::unordered_map<std::uint64_t, std::vector<int>> by_key_, by_edge_;
  std::unordered_map<int, int> degree_;
  int alive_count_ = 0;
};

// How candidates are ranked: by shape (attempt 0), by the number of front
// faces they close then shape (attempt 1), by shape times a pseudo-random
// factor in (0, 1] seeded by the attempt (the others): a greedy order that
// gets stuck is usually freed by a different one.
struct Rank {
  int attempt = 0;
  double operator()(const Front& front, const std::vector<mesh::Vec3>& p, const std::array<int, 4>& t) const {
    const double s = shape(p, t);
    if (attempt == 0) return s;
    if (attempt == 1) return front.matches(t) + std::clamp(s, 0.0, 0.5);
    const std::uint64_t x = mix64(face_key(t[0], t[1], t[2]) * 31 + static_cast<std::uint64_t>(t[3]) +
                                  0x9e3779b97f4a7c15ull * static_cast<std::uint64_t>(attempt));
    return s * (static_cast<double>(x >> 11) + 1) * 0x1p-53;
  }
};

// The same for the same four corners in any order.
std::uint64_t tet_key(std::array<int, 4> t) {
  std::sort(t.begin(), t.end());
  std::uint64_t x = 0;
  for (int v : t) x = x * 0x9e3779b97f4a7c15ull + static_cast<std::uint64_t>(v) + 1;
  return x;
}

struct Candidate {
  double score;
  std::array<int, 4> tet;
};

// The tet over front face f with the given apex (any sign: the exact test
// decides).
void push_candidate(const Front& front, const std::vector<mesh::Vec3>& p, const Rank& rank, const mesh::Tri& f,
                    int apex, std::vector<Candidate>& out) {
  if (apex == f[0] || apex == f[1] || apex == f[2]) return;
  const std::array<int, 4> t{f[0], f[1], f[2], apex};
  out.push_back({rank(front, p, t), t});
}

// A depth-first search over the candidates, best first: at each step the
// ears (apex of a front face across an edge), or where none fits, any front
// vertex near the first face that has one; up to kBranch fitting candidates
// tried per step, `budget` steps in all. Keeps the deepest state reached
// (fewest faces left) for the caller when no order closes the front.
constexpr int kBranch = 2;
constexpr std::size_t kNearest = 12;
class Search {
public:
  Search(const std::vector<mesh::Vec3>& p, const std::vector<mesh::Tri>& faces, const Rank& rank, long budget)
      : p_(p), front_(p, faces), rank_(rank), budget_(budget) {
    best_.rest = faces;
  }

  Peeled run() {
    step();
    return best_;
  }

private:
  bool step() {
    if (front_.empty()) {
      best_ = {tets_, {}};
      return true;
    }
    if (--budget_ < 0) return false;
    for (const auto& [tet, consumed] : fitting()) {
      const int added = front_.add_tet(tet, consumed);
      tets_.push_back(tet);
      if (front_.alive_faces().size() < best_.rest.size()) best_ = {tets_, front_.alive_faces()};
      if (step()) return true;
      tets_.pop_back();
      front_.undo_tet(consumed, added);
      if (budget_ < 0) return false;
    }
    return false;
  }

  std::vector<std::pair<std::array<int, 4>, std::vector<int>>> fitting() {
    std::vector<std::pair<std::array<int, 4>, std::vector<int>>> out;
    std::vector<Candidate> candidates;
    std::unordered_set<std::uint64_t> checked; // the same tet comes from each of its front faces
    auto take = [&] {
      std::stable_sort(candidates.begin(), candidates.end(),
                       [](const Candidate& a, const Candidate& b) { return a.score > b.score; });
      for (const auto& c : candidates) {
        if (static_cast<int>(out.size()) == kBranch) break;
        if (!checked.insert(tet_key(c.tet)).second) continue;
        if (auto consumed = front_.consumed_by(c.tet)) out.emplace_back(c.tet, std::move(*consumed));
      }
    };
    for (int i = 0; i < front_.size(); ++i) {
      if (!front_.alive(i)) continue;
      const auto& f = front_.face(i);
      for (int e = 0; e < 3; ++e)
        for (int j : front_.around_edge(f[e], f[(e + 1) % 3]))
          if (j != i)
            for (int v : front_.face(j)) push_candidate(front_, p_, rank_, f, v, candidates);
    }
    take();
    if (!out.empty()) return out;
    const auto vertices = front_.vertices();
    for (int i = 0; i < front_.size() && out.empty(); ++i) {
      if (!front_.alive(i)) continue;
      candidates.clear();
      for (int v : nearest(vertices, front_.face(i))) push_candidate(front_, p_, rank_, front_.face(i), v, candidates);
      take();
    }
    return out;
  }

  // The kNearest front vertices nearest face f's centroid (ties by id): a
  // stuck front tries every face, and checking each vertex over each would
  // cost most of a failed search.
  std::vector<int> nearest(const std::vector<int>& vertices, const mesh::Tri& f) const {
    const mesh::Vec3 c = (p_[f[0]] + p_[f[1]] + p_[f[2]]) / 3;
    std::vector<std::pair<double, int>> by_distance;
    for (int v : vertices) by_distance.emplace_back((p_[v] - c).squaredNorm(), v);
    const auto n = std::min<std::size_t>(kNearest, by_distance.size());
    std::partial_sort(by_distance.begin(), by_distance.begin() + n, by_distance.end());
    std::vector<int> out;
    for (std::size_t k = 0; k < n; ++k) out.push_back(by_distance[k].second);
    return out;
  }

  const std::vector<mesh::Vec3>& p_;
  Front front_;
  Rank rank_;
  long budget_;
  std::vector<std::array<int, 4>> tets_;
  Peeled best_;
};

} // namespace

std::vector<Peeled> peel_tetrahedralize(const std::vector<mesh::Vec3>& p, const std::vector<mesh::Tri>& faces,
                                        long budget, int attempts) {
  std::vector<Peeled> out;
  for (int attempt = 0; attempt < attempts; ++attempt) {
    out.push_back(Search(p, faces, Rank{attempt}, budget).run());
    if (out.back().rest.empty()) return {std::move(out.back())};
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const Peeled& a, const Peeled& b) { return a.rest.size() < b.rest.size(); });
  logger().debug("volume: peeling {} faces leaves {} at best", faces.size(), out.front().rest.size());
  return out;
}

} // namespace curvetet::volume
