#include "curvetet/shell/star_invariants.hpp"

#include "curvetet/shell/feature_invariant.hpp"
#include "curvetet/shell/straighten.hpp"
#include "curvetet/shell/surface_distance.hpp"

#include "curvetet/geometry/triangle_pair.hpp"

#include "curvetet/geometry/predicates.hpp"
#include "curvetet/highorder/quality.hpp"
#include "curvetet/shell/prism_tets.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>

namespace curvetet::shell {

using geometry::orient3d;

std::string_view to_string(OpKind k) {
  switch (k) {
    case OpKind::collapse: return "collapse";
    case OpKind::flip: return "flip";
    case OpKind::split: return "split";
    case OpKind::smooth: return "smooth";
    case OpKind::refit: return "refit";
  }
  return "?";
}

std::string_view to_string(Rejection r) {
  switch (r) {
    case Rejection::topology: return "topology";
    case Rejection::singular_adjacent: return "singular_adjacent";
    case Rejection::quality: return "quality";
    case Rejection::slab_quality: return "slab_quality";
    case Rejection::thickness: return "thickness";
    case Rejection::prism_positivity: return "prism_positivity";
    case Rejection::coverage: return "coverage";
    case Rejection::section: return "section";
    case Rejection::caps_intersection: return "caps_intersection";
    case Rejection::curved_fit: return "curved_fit";
    case Rejection::curved_quality: return "curved_quality";
    case Rejection::distance: return "distance";
    case Rejection::surface_distance: return "surface_distance";
    case Rejection::feature: return "feature";
    case Rejection::batch_conflict: return "batch_conflict";
    case Rejection::count_: break;
  }
  return "?";
}

double lower_slab_amips(const std::array<Vec3, 3>& bottom, const std::array<Vec3, 3>& middle) {
  std::array<Vec3, 6> corner;
  for (int k = 0; k < 3; ++k) {
    corner[k] = bottom[k];
    corner[k + 3] = middle[k];
  }
  double worst = 0;
  for (const auto& t : all_slab_tets()) {
    if (bottom[t.pillar] == middle[t.pillar]) continue;
    const auto& c = t.corners;
    Eigen::Matrix3d j;
    j << corner[c[1]] - corner[c[0]], corner[c[2]] - corner[c[0]], corner[c[3]] - corner[c[0]];
    worst = std::max(worst, highorder::amips(j));
  }
  return worst;
}

double mips(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double area = 0.5 * (b - a).cross(c - a).norm();
  if (!(area > 0)) return std::numeric_limits<double>::infinity();
  return ((b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm()) / (4 * std::sqrt(3.0) * area);
}

namespace {

geometry::Box3 box_of(const std::array<Vec3, 3>& p) { return geometry::bounding_box(p[0], p[1], p[2]); }

geometry::Box3 prism_box(const PrismGeom& g) {
  geometry::Box3 b{g.bottom[0], g.bottom[0]};
  for (const auto* arr : {&g.bottom, &g.middle, &g.top})
    for (const auto& p : *arr) {
      b.min = b.min.cwiseMin(p);
      b.max = b.max.cwiseMax(p);
    }
  return b;
}

// A cap triangle with merged vertex ids: bottom v -> 2v, top v -> 2v + 1, or
// 2v when the pillar of v is pinched (B[v] == T[v]: one point).
struct CapTri {
  std::array<std::int64_t, 3> ids;
  std::array<Vec3, 3> p;
  std::array<bool, 3> pinched;
  std::int64_t prism;  // identity of the prism (for the bottom/top pair rule)
  bool all_pinched;
};

CapTri make_cap(const std::array<int, 3>& t, const std::array<Vec3, 3>& bottom, const std::array<Vec3, 3>& top,
                bool is_top, std::int64_t prism) {
  CapTri c;
  c.all_pinched = true;
  for (int k = 0; k < 3; ++k) {
    c.pinched[k] = bottom[k] == top[k];
    c.ids[k] = 2 * std::int64_t(t[k]) + (is_top && !c.pinched[k] ? 1 : 0);
    c.p[k] = is_top ? top[k] : bottom[k];
    c.all_pinched = c.all_pinched && c.pinched[k];
  }
  c.prism = prism;
  return c;
}

CapTri shell_cap(const Shell& s, int cap) {
  const Tri& t = s.faces[cap / 2];
  std::array<Vec3, 3> b, tp;
  for (int k = 0; k < 3; ++k) {
    b[k] = s.bottom[t[k]];
    tp[k] = s.top[t[k]];
  }
  return make_cap(t, b, tp, cap % 2 == 1, cap / 2);
}

CapTri new_cap(const StarCandidate& c, int k, bool is_top) {
  const auto& g = c.geoms[k];
  return make_cap(g.ids, g.bottom, g.top, is_top, -1 - k);
}

bool caps_intersect(const CapTri& a, const CapTri& b) {
  if (a.prism == b.prism && a.all_pinched) return false; // coincident caps of a flat prism
  return geometry::triangles_intersect_improperly(a.p, b.p, geometry::shared_corners(a.ids, b.ids));
}

// An input triangle against a cap: they may touch only at a pinched cap
// corner that is (bitwise) one of the triangle's corners.
bool input_crosses_cap(const std::array<Vec3, 3>& t, const CapTri& cap) {
  geometry::SharedCorners shared;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (cap.pinched[j] && t[i] == cap.p[j]) {
        shared.a[shared.count] = i;
        shared.b[shared.count] = j;
        ++shared.count;
      }
  return geometry::triangles_intersect_improperly(t, cap.p, shared);
}

// ---------------------------------------------------------------------------

class SingularIsolation final : public StarInvariant {
 public:
  Rejection reason() const override { return Rejection::singular_adjacent; }
  bool holds(const StarContext& ctx, StarCandidate& c, Rejection&) const override {
    const auto& sing = ctx.editor.shell().singular;
    auto singular = [&](int v) { return v != kNewVertex && sing[v]; };
    for (const auto& f : c.faces)
      for (int k = 0; k < 3; ++k)
        if (singular(f[k]) && singular(f[(k + 1) % 3])) return false;
    return true;
  }
};

class MiddleQuality final : public StarInvariant {
 public:
  Rejection reason() const override { return Rejection::quality; }
  bool holds(const StarContext& ctx, StarCandidate& c, Rejection&) const override {
    const auto& e = ctx.editor;
    const auto& s = e.shell();
    for (const auto& t : c.faces) {
      const double q = mips(e.middle(c, t[0]), e.middle(c, t[1]), e.middle(c, t[2]));
      if (q <= ctx.quality_bound) continue;
      // Above the bound: no worse than an old face it shares an edge with.
      // (Bounded by the star's worst face alone, needles beside the input's
      // short edges grew along them wherever a worse face was elsewhere in
      // the star: abc_00000001, cheese; docs/usable_elements.md, session 38.)
      double across = 0;
      for (int k = 0; k < 3; ++k) {
        const int x = t[k], y = t[(k + 1) % 3];
        for (int f : c.removed) {
          const auto& o = s.faces[f];
          const bool has_x = o[0] == x || o[1] == x || o[2] == x, has_y = o[0] == y || o[1] == y || o[2] == y;
          if (has_x && has_y) across = std::max(across, mips(s.middle[o[0]], s.middle[o[1]], s.middle[o[2]]));
        }
      }
      if (!(q <= across)) return false;
    }
    return true;
  }
};

class SlabQuality final : public StarInvariant {
 public:
  Rejection reason() const override { return Rejection::slab_quality; }
  bool holds(const StarContext& ctx, StarCandidate& c, Rejection&) const override {
    if (!std::isfinite(ctx.slab_quality_bound)) return true;
    const auto& e = ctx.editor;
    const auto& s = e.shell();
    const auto slab = [&](const std::array<int, 3>& f, auto bottom, auto middle) {
      return lower_slab_amips({bottom(f[0]), bottom(f[1]), bottom(f[2])}, {middle(f[0]), middle(f[1]), middle(f[2])});
    };
    double old_max = 0;
    for (int f : c.removed)
      old_max = std::max(old_max, slab(s.faces[f], [&](int v) { return s.bottom[v]; }, [&](int v) { return s.middle[v]; }));
    const double bound = std::max(old_max, ctx.slab_quality_bound);
    for (const auto& f : c.faces)
      if (!(slab(f, [&](int v) { return e.bottom(c, v); }, [&](int v) { return e.middle(c, v); }) <= bound)) return false;
    return true;
  }
};

// Longest edge of triangle t over the solid's thickness at its thinnest
// corner (0 where no corner's thickness is known).
template <class Middle>
double edge_over_thickness(const Tri& t, Middle middle, const std::vector<double>& thickness) {
  const auto at = [&](int v) {
    return v >= 0 && v < static_cast<int>(thickness.size()) ? thickness[v] : std::numeric_limits<double>::infinity();
  };
  const double thinnest = std::min({at(t[0]), at(t[1]), at(t[2])});
  if (!std::isfinite(thinnest)) return 0;
  double longest = 0;
  for (int k = 0; k < 3; ++k) longest = std::max(longest, (middle(t[k]) - middle(t[(k + 1) % 3])).norm());
  return longest / thinnest;
}

class Thickness final : public StarInvariant {
 public:
  Rejection reason() const override { return Rejection::thickness; }
  bool holds(const StarContext& ctx, StarCandidate& c, Rejection&) const override {
    if (!ctx.thickness || !std::isfinite(ctx.thickness_ratio)) return true;
    const auto& e = ctx.editor;
    const auto& s = e.shell();
    double old_max = 0;
    for (int f : c.removed)
      old_max = std::max(old_max, edge_over_thickness(s.faces[f], [&](int v) { return s.middle[v]; }, *ctx.thickness));
    const double bound = std::max(old_max, ctx.thickness_ratio);
    for (const auto& t : c.faces)
      if (!(edge_over_thickness(t, [&](int v) -> const Vec3& { return e.middle(c, v); }, *ctx.thickness) <= bound))
        return false;
    return true;
  }
};

class PrismPositivity final : public StarInvariant {
 public:
  Rejection reason() const override { return Rejection::prism_positivity; }
  bool holds(const StarContext& ctx, StarCandidate& c, Rejection&) const override {
    c.geoms.resize(c.faces.size());
    for (std::size_t k = 0; k < c.faces.size(); ++k) c.geoms[k] = ctx.editor.candidate_geom(c, static_cast<int>(k));
    for (const auto& g : c.geoms)
      if (!positive(g)) return false;
    return true;
  }
};

class Coverage final : public StarInvariant {
 public:
  Rejection reason() const override { return Rejection::coverage; }
  bool holds(const StarContext& ctx, StarCandidate& c, Rejection&) const override {
    const Shell& s = ctx.editor.shell();
    c.old_tracked.clear();
    for (int f : c.removed) c.old_tracked.insert(c.old_tracked.end(), s.tracked[f].begin(), s.tracked[f].end());
    // Reshaped faces (straightening) may now reach new prisms.
    c.old_tracked.insert(c.old_tracked.end(), c.reshaped.begin(), c.reshaped.end());
    std::sort(c.old_tracked.begin(), c.old_tracked.end());
    c.old_tracked.erase(std::unique(c.old_tracked.begin(), c.old_tracked.end()), c.old_tracked.end());
    const int K = static_cast<int>(c.faces.size());
    std::vector<geometry::Box3> boxes(K);
    std::vector<CapTri> caps;
    for (int k = 0; k < K; ++k) {
      boxes[k] = prism_box(c.geoms[k]);
      caps.push_back(new_cap(c, k, false));
      caps.push_back(new_cap(c, k, true));
    }
    c.tracked.assign(K, {});
    for (int t : c.old_tracked) {
      const auto tri = straight_triangle(s, c, t);
      const auto tb = box_of(tri);
      bool landed = false;
      for (int k = 0; k < K; ++k) {
        if (!geometry::boxes_overlap(tb, boxes[k])) continue;
        if (triangle_meets_prism(c.geoms[k], tri[0], tri[1], tri[2])) {
          c.tracked[k].push_back(t);
          landed = true;
        }
      }
      if (!landed) return false;
      for (const auto& cap : caps)
        if (geometry::boxes_overlap(tb, box_of(cap.p)) && input_crosses_cap(tri, cap)) return false;
    }
    return true;
  }
};

class Section final : public StarInvariant {
 public:
  Rejection reason() const override { return Rejection::section; }
  bool holds(const StarContext& ctx, StarCandidate& c, Rejection&) const override {
    const Shell& s = ctx.editor.shell();
    for (std::size_t k = 0; k < c.faces.size(); ++k)
      for (int t : c.tracked[k]) {
        const auto tri = straight_triangle(s, c, t);
        if (!section_condition(c.geoms[k], tri[0], tri[1], tri[2])) return false;
      }
    return true;
  }
};

class CapsIntersection final : public StarInvariant {
 public:
  Rejection reason() const override { return Rejection::caps_intersection; }
  bool holds(const StarContext& ctx, StarCandidate& c, Rejection&) const override {
    const Shell& s = ctx.editor.shell();
    const int K = static_cast<int>(c.faces.size());
    std::vector<CapTri> caps;
    for (int k = 0; k < K; ++k) {
      caps.push_back(new_cap(c, k, false));
      caps.push_back(new_cap(c, k, true));
    }
    for (std::size_t i = 0; i < caps.size(); ++i)
      for (std::size_t j = i + 1; j < caps.size(); ++j)
        if (geometry::boxes_overlap(box_of(caps[i].p), box_of(caps[j].p)) && caps_intersect(caps[i], caps[j])) return false;
    for (const auto& cap : caps) {
      const auto box = box_of(cap.p);
      for (int other : ctx.editor.grid().query(box)) {
        const int f = other / 2;
        if (!ctx.editor.face_alive(f) || std::binary_search(c.removed.begin(), c.removed.end(), f)) continue;
        if (!geometry::boxes_overlap(box, ctx.editor.cap_box(other))) continue;
        if (caps_intersect(cap, shell_cap(s, other))) return false;
      }
    }
    return true;
  }
};

class CurvedFit final : public StarInvariant {
 public:
  Rejection reason() const override { return Rejection::curved_fit; }
  bool holds(const StarContext& ctx, StarCandidate& c, Rejection&) const override { return ctx.fit.fit_and_check(ctx.editor, c, ctx.epsilon); }
};

// MiddleQuality on the fitted patches, at every point of their lattice: a
// fit can distort a patch's parametrization far beyond its flat triangle's
// (the fibers it follows converge), and every output tet on that face
// inherits the distortion whatever its other nodes do. Its bound is looser
// than MiddleQuality's: at 10 it reshuffles the coarsening of smooth models
// into ear tets at ridges (docs/usable_elements.md, session 19).
class CurvedMiddleQuality final : public StarInvariant {
 public:
  Rejection reason() const override { return Rejection::curved_quality; }
  bool holds(const StarContext& ctx, StarCandidate& c, Rejection&) const override {
    if (c.middle_nodes.empty() || !std::isfinite(ctx.curved_quality_bound)) return true;
    const auto& s = ctx.editor.shell();
    double old_max = 0;
    for (int f : c.removed)
      old_max = std::max(old_max, s.middle_nodes.empty() || s.middle_nodes[f].empty()
                                      ? mips(s.middle[s.faces[f][0]], s.middle[s.faces[f][1]], s.middle[s.faces[f][2]])
                                      : highorder::triangle_max_mips(s.middle_degree, s.middle_nodes[f].data()));
    const double bound = std::max(old_max, ctx.curved_quality_bound);
    for (const auto& nodes : c.middle_nodes)
      if (!nodes.empty() && !(highorder::triangle_max_mips(ctx.fit.degree(), nodes.data()) <= bound)) return false;
    return true;
  }
};

// Π of every constraint point of the removed prisms under the new prisms
// (fills c.images). A point must land in a new prism tracking its face.
class MapImages final : public StarInvariant {
 public:
  Rejection reason() const override { return Rejection::coverage; }
  bool holds(const StarContext& ctx, StarCandidate& c, Rejection&) const override {
    const Shell& s = ctx.editor.shell();
    c.images.clear();
    std::vector<std::optional<PrismProjection>> projections(c.faces.size()); // built on first use
    for (int f : c.removed)
      for (int p : ctx.editor.points_in(f)) {
        const auto& pt = s.points[p];
        // The deepest new prism tracking its face (double), confirmed by
        // the exact containment test; the next deepest if that fails.
        struct Hit {
          double depth;
          int k;
          std::array<double, 2> uv;
        };
        std::vector<Hit> hits;
        const Vec3 x = straight_point(s, c, p);
        for (std::size_t k = 0; k < c.faces.size(); ++k) {
          if (!std::binary_search(c.tracked[k].begin(), c.tracked[k].end(), pt.input_face)) continue;
          double depth;
          if (!projections[k]) projections[k].emplace(c.geoms[k]);
          const auto uv = (*projections[k])(x, std::numeric_limits<double>::infinity(), &depth);
          if (uv) hits.push_back({depth, static_cast<int>(k), *uv});
        }
        std::sort(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) { return a.depth > b.depth; });
        if (hits.empty()) return false; // no new prism tracks its face: not covered
        // Chain vertices straightened onto a coarse edge lie on it only up to
        // rounding; their image is placed on the edge exactly (snap below).
        if (on_straightened_edge(s, c, p)) {
          c.images.push_back({p, hits.front().k, hits.front().uv[0], hits.front().uv[1]});
          continue;
        }
        const auto inside = std::find_if(hits.begin(), hits.end(), [&](const Hit& h) { return prism_contains(c.geoms[h.k], x); });
        if (inside == hits.end()) return false; // outside every new prism tracking its face: not covered
        c.images.push_back({p, inside->k, inside->uv[0], inside->uv[1]});
      }
    return snap_straightened_images(s, c);
  }
};

class Distance final : public StarInvariant {
 public:
  Rejection reason() const override { return Rejection::distance; }
  bool holds(const StarContext& ctx, StarCandidate& c, Rejection&) const override {
    const Shell& s = ctx.editor.shell();
    c.max_distance = 0;
    for (const auto& im : c.images) {
      const Vec3 x = ctx.fit.evaluate(c, im.local, im.u, im.v);
      const double d = (x - s.points[im.point].position).norm();
      if (!(d < ctx.epsilon)) return false;
      c.max_distance = std::max(c.max_distance, d);
    }
    return true;
  }
};

// The other direction: every point of each new middle patch within epsilon
// of the input faces its prism tracks (a derived bound, surface_distance.hpp).
class SurfaceDistance final : public StarInvariant {
 public:
  Rejection reason() const override { return Rejection::surface_distance; }
  bool holds(const StarContext& ctx, StarCandidate& c, Rejection&) const override {
    c.max_surface_distance = 0;
    std::vector<PatchDistanceCheck> checks;
    for (std::size_t k = 0; k < c.faces.size(); ++k) {
      const auto nodes = ctx.fit.patch_nodes(c, static_cast<int>(k));
      checks.emplace_back(ctx.fit.degree(), nodes, ctx.editor.shell().input, c.tracked[k], ctx.epsilon);
      if (checks.back().fails_early()) return false;
    }
    for (const auto& check : checks) {
      const auto d = check.bound();
      if (!(d.bound() <= ctx.epsilon)) return false;
      c.max_surface_distance = std::max(c.max_surface_distance, d.bound());
    }
    return true;
  }
};

} // namespace

InvariantList default_star_invariants() {
  InvariantList l;
  l.push_back(std::make_unique<SingularIsolation>());
  l.push_back(std::make_unique<MiddleQuality>());
  l.push_back(std::make_unique<SlabQuality>());
  l.push_back(std::make_unique<Thickness>());
  l.push_back(std::make_unique<PrismPositivity>());
  l.push_back(make_straightening_invariant());
  l.push_back(std::make_unique<Coverage>());
  l.push_back(std::make_unique<Section>());
  l.push_back(std::make_unique<MapImages>());
  l.push_back(std::make_unique<CurvedFit>());
  l.push_back(std::make_unique<Distance>());
  l.push_back(std::make_unique<SurfaceDistance>());
  // Costly and rejecting few candidates: after the checks that reject most
  // (the order changes no verdict, only the cost and the reasons counted).
  l.push_back(std::make_unique<CurvedMiddleQuality>());
  l.push_back(std::make_unique<CapsIntersection>());
  l.push_back(make_feature_invariant());
  return l;
}

std::optional<Rejection> check_candidate(const InvariantList& list, const StarContext& ctx, StarCandidate& c,
                                         InvariantSeconds* seconds) {
  using clock = std::chrono::steady_clock;
  for (const auto& inv : list) {
    Rejection why = inv->reason();
    const auto start = seconds ? clock::now() : clock::time_point{};
    const bool ok = inv->holds(ctx, c, why);
    if (seconds)
      (*seconds)[static_cast<int>(inv->reason())] += std::chrono::duration<double>(clock::now() - start).count();
    if (!ok) return why;
  }
  return std::nullopt;
}

bool caps_free_of_batch(const StarContext& ctx, const StarCandidate& c, int batch) {
  const Shell& s = ctx.editor.shell();
  for (std::size_t k = 0; k < c.faces.size(); ++k)
    for (int side = 0; side < 2; ++side) {
      const CapTri cap = new_cap(c, static_cast<int>(k), side == 1);
      const auto box = box_of(cap.p);
      for (int other : ctx.editor.grid().query(box)) {
        const int f = other / 2;
        if (!ctx.editor.face_alive(f) || ctx.editor.batch_of(f) != batch) continue;
        if (!geometry::boxes_overlap(box, ctx.editor.cap_box(other))) continue;
        if (caps_intersect(cap, shell_cap(s, other))) return false;
      }
    }
  return true;
}

} // namespace curvetet::shell
