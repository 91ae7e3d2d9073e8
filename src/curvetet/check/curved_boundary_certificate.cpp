#include "curvetet/check/curved_boundary_certificate.hpp"

#include "curvetet/check/bezier_patch.hpp"
#include "curvetet/check/patch_separation.hpp"
#include "curvetet/geometry/box_pairs.hpp"
#include "curvetet/highorder/node_ordering.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <map>
#include <optional>

namespace curvetet::check {
namespace {

// Root slot of a -> root slot of b holding the same vertex, -1 if none; the
// identity for two pieces of one root.
using SlotMap = std::array<int, 3>;
constexpr SlotMap kSameRoot{0, 1, 2};

struct Counters {
  std::atomic<std::size_t> tests{0};
  std::atomic<int> deepest{0};
  void reached(int depth) {
    int seen = deepest.load();
    while (depth > seen && !deepest.compare_exchange_weak(seen, depth)) {
    }
  }
};

// Corner pairs (i of a, j of b) that are the same exact point: a's corner
// lies on the part of its root that b's root shares and has the same
// parameters there (pieces are dyadic, so parameters compare exactly).
int shared_corners(const BezierPatch& a, const BezierPatch& b, const SlotMap& map,
                   std::array<std::array<int, 2>, 3>& out) {
  int count = 0;
  for (int i = 0; i < 3; ++i) {
    Barycentric on_b{0, 0, 0};
    bool shared = true;
    for (int k = 0; k < 3 && shared; ++k)
      if (a.corners[i][k] != 0) {
        shared = map[k] >= 0;
        if (shared) on_b[map[k]] = a.corners[i][k];
      }
    if (!shared) continue;
    for (int j = 0; j < 3; ++j)
      if (b.corners[j] == on_b) out[count++] = {i, j};
  }
  return count;
}

double box_size(const BezierPatch& p) {
  const auto b = p.box();
  return (b.max - b.min).norm();
}

struct Frame {
  BezierPatch a, b;
  int depth_a, depth_b;
};

// Pieces a (of root_a) and b (of root_b) meet only where they share. Pieces
// that share corners are split together, so their shared parts stay whole
// edges or corners of both; pieces that share nothing stay so when split,
// and only the larger is split. Each proof tried takes one from `budget`.
bool pieces_settled(const BezierPatch& root_a, const BezierPatch& root_b, const SlotMap& map, Frame start,
                    const CurvedBoundaryOptions& o, Counters& counters, std::size_t& budget) {
  std::vector<Frame> stack{std::move(start)};
  std::size_t tests = 0;
  while (!stack.empty()) {
    Frame f = std::move(stack.back());
    stack.pop_back();
    if (budget == 0) {
      counters.tests += tests;
      return false;
    }
    --budget;
    ++tests;
    std::array<std::array<int, 2>, 3> shared{};
    const int n = shared_corners(f.a, f.b, map, shared);
    const bool settled =
        n == 0   ? apart(f.a, f.b)
        : n == 1 ? meet_only_at_corner(f.a, shared[0][0], f.b, shared[0][1])
        : n == 2 ? meet_only_along_edge(f.a, shared[0][0], shared[1][0], f.b, shared[0][1], shared[1][1])
                 : false;
    if (settled) continue;
    const bool split_a = n > 0 || box_size(f.a) >= box_size(f.b), split_b = n > 0 || !split_a;
    if ((split_a && f.depth_a >= o.max_depth) || (split_b && f.depth_b >= o.max_depth)) {
      counters.tests += tests;
      return false;
    }
    counters.reached(std::max(f.depth_a + split_a, f.depth_b + split_b));
    if (split_a && split_b) {
      const auto pa = split_patch(root_a, f.a), pb = split_patch(root_b, f.b);
      for (const auto& x : pa)
        for (const auto& y : pb) stack.push_back({x, y, f.depth_a + 1, f.depth_b + 1});
    } else if (split_a) {
      for (auto& x : split_patch(root_a, f.a)) stack.push_back({std::move(x), f.b, f.depth_a + 1, f.depth_b});
    } else {
      for (auto& y : split_patch(root_b, f.b)) stack.push_back({f.a, std::move(y), f.depth_a, f.depth_b + 1});
    }
  }
  counters.tests += tests;
  return true;
}

// The patch is embedded: it passes alone, or its four pieces are embedded
// and pairwise meet only where they share. One budget for the whole patch,
// as for a pair: the sibling pairs of every level would multiply it.
bool patch_embedded(const BezierPatch& root, const CurvedBoundaryOptions& o, Counters& counters) {
  std::size_t budget = o.max_tests_per_pair;
  std::vector<std::pair<BezierPatch, int>> stack{{root, 0}};
  while (!stack.empty()) {
    auto [piece, depth] = std::move(stack.back());
    stack.pop_back();
    ++counters.tests;
    if (budget == 0) return false;
    --budget;
    if (embedded(piece)) continue;
    if (depth >= o.max_depth) return false;
    counters.reached(depth + 1);
    const auto pieces = split_patch(root, piece);
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        if (!pieces_settled(root, root, kSameRoot, {pieces[i], pieces[j], depth + 1, depth + 1}, o, counters,
                            budget))
          return false;
    for (const auto& p : pieces) stack.emplace_back(p, depth + 1);
  }
  return true;
}

// Nodes of triangle t's edge between slots s0 and s1, by their lattice
// step from s0.
std::map<int, int> edge_nodes(const mesh::TetMesh& m, int t, int s0, int s1) {
  std::map<int, int> nodes;
  const int* ids = m.boundary_triangle(t);
  for (int i = 0; i < m.triangle_nodes(); ++i) {
    const auto q = highorder::triangle_node(m.order, i);
    const std::array<int, 3> lambda{m.order - q[0] - q[1], q[0], q[1]};
    if (lambda[3 - s0 - s1] == 0) nodes[lambda[s1]] = ids[i];
  }
  return nodes;
}

// The two roots' slot map, or nullopt when they cannot be compared
// (three shared corners, or a shared edge with other nodes).
std::optional<SlotMap> slot_map(const mesh::TetMesh& m, int ta, int tb) {
  SlotMap map{-1, -1, -1};
  std::vector<std::array<int, 2>> shared;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (m.boundary_triangle(ta)[i] == m.boundary_triangle(tb)[j]) {
        map[i] = j;
        shared.push_back({i, j});
      }
  if (shared.size() == 3) return std::nullopt;
  if (shared.size() == 2 && edge_nodes(m, ta, shared[0][0], shared[1][0]) !=
                                edge_nodes(m, tb, shared[0][1], shared[1][1]))
    return std::nullopt;
  return map;
}

} // namespace

CurvedBoundaryCertificate certify_curved_boundary(const mesh::TetMesh& m, const CurvedBoundaryOptions& o) {
  CurvedBoundaryCertificate r;
  const int nb = m.num_boundary();
  r.patches = nb;
  std::vector<BezierPatch> roots(nb);
  std::vector<geometry::Box3> boxes(nb);
  tbb::parallel_for(0, nb, [&](int t) {
    std::vector<Eigen::Vector3d> nodes(m.triangle_nodes());
    for (int i = 0; i < m.triangle_nodes(); ++i) nodes[i] = m.nodes[m.boundary_triangle(t)[i]];
    roots[t] = root_patch(m.order, nodes);
    boxes[t] = roots[t].box();
  });
  auto pairs = geometry::overlapping_pairs(boxes);
  std::sort(pairs.begin(), pairs.end());
  r.pairs = pairs.size();
  Counters counters;
  std::vector<char> pair_ok(pairs.size()), patch_ok(nb);
  tbb::parallel_for(std::size_t{0}, pairs.size(), [&](std::size_t k) {
    const auto [ta, tb] = pairs[k];
    const auto map = slot_map(m, ta, tb);
    std::size_t budget = o.max_tests_per_pair;
    pair_ok[k] = map && pieces_settled(roots[ta], roots[tb], *map, {roots[ta], roots[tb], 0, 0}, o, counters, budget);
  });
  tbb::parallel_for(0, nb, [&](int t) { patch_ok[t] = patch_embedded(roots[t], o, counters); });
  for (int t = 0; t < nb; ++t)
    if (!patch_ok[t]) r.unsettled.push_back({t, t});
  for (std::size_t k = 0; k < pairs.size(); ++k)
    if (!pair_ok[k]) r.unsettled.push_back(pairs[k]);
  std::sort(r.unsettled.begin(), r.unsettled.end());
  r.piece_tests = counters.tests;
  r.deepest = counters.deepest;
  return r;
}

} // namespace curvetet::check
