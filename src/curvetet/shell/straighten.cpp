#include "curvetet/shell/straighten.hpp"

#include "curvetet/shell/exact_dot.hpp"

#include "curvetet/geometry/box_pairs.hpp"
#include "curvetet/geometry/triangle_pair.hpp"
#include "curvetet/shell/feature_tracking.hpp"
#include "curvetet/shell/prism_tets.hpp"

#include <algorithm>
#include <cmath>

namespace curvetet::shell {

namespace {

using Triangle = std::array<Vec3, 3>;

const StarCandidate::Straightened* find_straightened(const StarCandidate& c, int v) {
  auto it = std::lower_bound(c.straightened.begin(), c.straightened.end(), v,
                             [](const StarCandidate::Straightened& x, int w) { return x.vertex < w; });
  return it != c.straightened.end() && it->vertex == v ? &*it : nullptr;
}

// Every input chain vertex in the range of a new or changed coarse feature
// edge: interior ones on the straight edge at their arc-length parameter,
// range ends back on the input. Sorted by vertex, each once.
void plan_positions(const ShellEditor& e, const FeatureEdit& plan, StarCandidate& c) {
  const Shell& s = e.shell();
  const ShellFeatures& F = s.features;
  for (const auto& [ab, edge] : plan.added) {
    const int a = edge.first, b = ab[0] == a ? ab[1] : ab[0];
    const Vec3 pa = e.middle(c, a), pb = e.middle(c, b);
    const double end = edge.start + edge.length;
    const double s0 = F.arc_at(edge.chain, edge.start), span = F.arc_at(edge.chain, end) - s0;
    for (auto q = static_cast<long long>(std::ceil(edge.start)); q <= static_cast<long long>(std::floor(end)); ++q) {
      const int iv = F.input_vertex(edge.chain, q);
      StarCandidate::Straightened x{iv, s.input.vertices[iv]};
      if (double(q) != edge.start && double(q) != end) {
        x.a = a;
        x.b = b;
        x.t = (F.arc_at(edge.chain, double(q)) - s0) / span;
        x.at = (1 - x.t) * pa + x.t * pb;
      }
      c.straightened.push_back(x);
    }
  }
  std::sort(c.straightened.begin(), c.straightened.end(),
            [](const auto& x, const auto& y) { return x.vertex < y.vertex; });
  c.straightened.erase(std::unique(c.straightened.begin(), c.straightened.end(),
                                   [](const auto& x, const auto& y) { return x.vertex == y.vertex; }),
                       c.straightened.end());
}

// β stays locally injective: same orientation, decided exactly. Besides,
// a quality rule (not a guarantee): the area does not collapse below
// 1e-10 of the input triangle's.
bool keeps_area(const Triangle& now, const Triangle& input) {
  if (normals_dot_sign(now[0], now[1], now[2], input[0], input[1], input[2]) <= 0) return false;
  const Vec3 n = (now[1] - now[0]).cross(now[2] - now[0]);
  const Vec3 n0 = (input[1] - input[0]).cross(input[2] - input[0]);
  return n.norm() > 1e-10 * n0.norm();
}

bool degenerate(const Triangle& t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; }

// The pillar quad of prism g over its corners (i, j), both slabs, each cut
// along the diagonal of prism_tets.hpp's canonical split (lower corner of the
// smaller id to upper corner of the larger).
void add_quad(const PrismGeom& g, int i, int j, std::vector<Triangle>& out) {
  const int lo = g.ids[i] < g.ids[j] ? i : j, hi = lo == i ? j : i;
  for (Slab slab : {Slab::bottom, Slab::top}) {
    const Triangle t1{g.lower(slab, lo), g.lower(slab, hi), g.upper(slab, hi)};
    const Triangle t2{g.lower(slab, lo), g.upper(slab, hi), g.upper(slab, lo)};
    for (const auto& t : {t1, t2})
      if (!degenerate(t)) out.push_back(t);
  }
}

// Meets `wall` elsewhere than at corners bitwise shared with it.
bool crosses(const Triangle& t, const Triangle& wall) {
  geometry::SharedCorners shared;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (t[i] == wall[j] && shared.count < 3) {
        shared.a[shared.count] = i;
        shared.b[shared.count] = j;
        ++shared.count;
      }
  return geometry::triangles_intersect_improperly(t, wall, shared);
}

geometry::Box3 box_of(const Triangle& t) { return geometry::bounding_box(t[0], t[1], t[2]); }

// The live prisms outside the star sharing a vertex with it, and the outer
// boundary of (new star prisms + ring): the ring's caps and its pillar quads
// over edges whose other prism is in neither. A reshaped face meeting that
// boundary only at shared corners, and some new prism (Coverage), lies in
// the union.
struct Ring {
  std::vector<int> prisms; // sorted
  std::vector<PrismGeom> geoms;
  std::vector<Triangle> walls;
};

Ring ring_around(const ShellEditor& e, const StarCandidate& c) {
  const Shell& s = e.shell();
  Ring out;
  for (const auto& f : c.faces)
    for (int v : f)
      if (v != kNewVertex)
        for (int q : e.faces_of(v))
          if (e.face_alive(q) && !std::binary_search(c.removed.begin(), c.removed.end(), q)) out.prisms.push_back(q);
  std::sort(out.prisms.begin(), out.prisms.end());
  out.prisms.erase(std::unique(out.prisms.begin(), out.prisms.end()), out.prisms.end());
  auto inside = [&](int q) {
    return std::binary_search(c.removed.begin(), c.removed.end(), q) ||
           std::binary_search(out.prisms.begin(), out.prisms.end(), q);
  };
  for (int q : out.prisms) {
    const PrismGeom g = e.geom(q);
    out.geoms.push_back(g);
    for (const Triangle& cap : {g.bottom, g.top})
      if (!degenerate(cap)) out.walls.push_back(cap);
    const Tri& t = s.faces[q];
    for (int k = 0; k < 3; ++k) {
      const int i = t[k], j = t[(k + 1) % 3];
      bool shared = false; // the other prism of edge (i, j) is inside
      for (int other : e.faces_of(j))
        if (other != q && e.face_alive(other) && std::find(s.faces[other].begin(), s.faces[other].end(), i) != s.faces[other].end())
          shared = inside(other);
      if (!shared) add_quad(g, k, (k + 1) % 3, out.walls);
    }
  }
  return out;
}

class Straightening final : public StarInvariant {
 public:
  Rejection reason() const override { return Rejection::section; }
  bool holds(const StarContext& ctx, StarCandidate& c, Rejection& why) const override {
    c.straightened.clear();
    c.reshaped.clear();
    c.ring_tracked.clear();
    const ShellEditor& e = ctx.editor;
    const Shell& s = e.shell();
    if (s.features.empty()) return true;
    const FeatureEdit plan = plan_feature_edit(s, c);
    if (!plan.allowed) {
      why = Rejection::feature;
      return false;
    }
    plan_positions(e, plan, c);
    const auto& around = s.features.input_faces_around;
    for (const auto& x : c.straightened) {
      const bool moves = x.at != shell::straight_vertex(s, x.vertex);
      // Its image is recomputed (and snapped) only when it lies in a removed prism.
      if ((moves || x.a >= 0) && !std::binary_search(c.removed.begin(), c.removed.end(), s.points[x.vertex].image.prism)) {
        why = Rejection::coverage;
        return false;
      }
      if (!moves) continue;
      for (int i = around.offsets[x.vertex]; i < around.offsets[x.vertex + 1]; ++i) c.reshaped.push_back(around.faces[i]);
    }
    std::sort(c.reshaped.begin(), c.reshaped.end());
    c.reshaped.erase(std::unique(c.reshaped.begin(), c.reshaped.end()), c.reshaped.end());
    if (c.reshaped.empty()) return true;

    const Ring ring = ring_around(e, c);
    for (int t : c.reshaped) {
      const Triangle now = straight_triangle(s, c, t);
      const auto& f = s.input.faces[t];
      if (!keeps_area(now, {s.input.vertices[f[0]], s.input.vertices[f[1]], s.input.vertices[f[2]]})) return false;
      const auto box = box_of(now);
      for (const auto& w : ring.walls)
        if (geometry::boxes_overlap(box, box_of(w)) && crosses(now, w)) {
          why = Rejection::coverage;
          return false;
        }
      // Inside the new prisms and the ring: the ring prisms it meets track
      // it and hold the section condition with it.
      for (std::size_t r = 0; r < ring.prisms.size(); ++r) {
        const int q = ring.prisms[r];
        const PrismGeom& g = ring.geoms[r];
        const bool tracks = std::binary_search(s.tracked[q].begin(), s.tracked[q].end(), t);
        const bool meets = triangle_meets_prism(g, now[0], now[1], now[2]);
        if (!tracks && !meets) continue;
        if (!section_condition(g, now[0], now[1], now[2])) return false;
        if (!tracks) c.ring_tracked.push_back({q, t});
      }
    }
    return true;
  }
};

} // namespace

Vec3 straight_vertex(const Shell& s, const StarCandidate& c, int input_vertex) {
  const auto* x = find_straightened(c, input_vertex);
  return x ? x->at : shell::straight_vertex(s, input_vertex);
}

bool on_straightened_edge(const Shell& s, const StarCandidate& c, int p) {
  if (const auto* x = find_straightened(c, p)) return x->a >= 0;
  const auto& on_edge = s.features.on_edge;
  return p < static_cast<int>(on_edge.size()) && on_edge[p].a >= 0;
}

Vec3 straight_point(const Shell& s, const StarCandidate& c, int p) {
  if (p < s.input.num_vertices()) return straight_vertex(s, c, p);
  const auto t = straight_triangle(s, c, s.points[p].input_face);
  const auto& b = s.points[p].barycentric;
  return b[0] * t[0] + b[1] * t[1] + b[2] * t[2];
}

std::array<Vec3, 3> straight_triangle(const Shell& s, const StarCandidate& c, int input_face) {
  if (c.straightened.empty()) return shell::straight_triangle(s, input_face);
  const Tri& f = s.input.faces[input_face];
  return {straight_vertex(s, c, f[0]), straight_vertex(s, c, f[1]), straight_vertex(s, c, f[2])};
}

std::unique_ptr<StarInvariant> make_straightening_invariant() { return std::make_unique<Straightening>(); }

bool snap_straightened_images(const Shell& s, StarCandidate& c) {
  const auto& on_edge = s.features.on_edge;
  if (c.straightened.empty() && on_edge.empty()) return true;
  for (auto& im : c.images) {
    // Straightened by c, or earlier (then its edge is still one of c's faces:
    // only feature operations, which straighten again, remove it).
    StraightOnEdge e;
    if (const auto* x = find_straightened(c, im.point)) e = {x->a, x->b, x->t};
    else if (im.point < static_cast<int>(on_edge.size())) e = on_edge[im.point];
    if (e.a < 0) continue;
    const int face = s.points[im.point].input_face;
    bool placed = false;
    for (std::size_t k = 0; k < c.faces.size() && !placed; ++k) {
      const Tri& f = c.faces[k];
      const auto ia = std::find(f.begin(), f.end(), e.a) - f.begin(), ib = std::find(f.begin(), f.end(), e.b) - f.begin();
      if (ia == 3 || ib == 3 || !std::binary_search(c.tracked[k].begin(), c.tracked[k].end(), face)) continue;
      double w[3] = {0, 0, 0};
      w[ia] = 1 - e.t;
      w[ib] = e.t;
      // On edge (1, 2) the third weight is 1 - u - v: make it exactly 0.
      if (ia != 0 && ib != 0) w[2] = 1 - w[1];
      im = {im.point, static_cast<int>(k), w[1], w[2]};
      placed = true;
    }
    if (!placed) return false;
  }
  return true;
}

void apply_straightening(Shell& s, const StarCandidate& c, int new_vertex) {
  if (c.straightened.empty()) return;
  if (s.straight.empty()) s.straight = s.input.vertices;
  auto& on_edge = s.features.on_edge;
  if (on_edge.empty()) on_edge.resize(s.input.vertices.size());
  auto id = [&](int v) { return v == kNewVertex ? new_vertex : v; };
  for (const auto& x : c.straightened) {
    s.straight[x.vertex] = x.at;
    on_edge[x.vertex] = x.a < 0 ? StraightOnEdge{} : StraightOnEdge{id(x.a), id(x.b), x.t};
  }
  for (const auto& [q, t] : c.ring_tracked) {
    auto& tracked = s.tracked[q];
    tracked.insert(std::lower_bound(tracked.begin(), tracked.end(), t), t);
  }
}

} // namespace curvetet::shell
