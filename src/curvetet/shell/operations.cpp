#include "curvetet/shell/operations.hpp"

#include "curvetet/shell/extrusion.hpp"
#include "curvetet/shell/feature_tracking.hpp"

#include <algorithm>
#include <limits>

namespace curvetet::shell {

namespace {

int corner_of(const Tri& t, int v) {
  for (int k = 0; k < 3; ++k)
    if (t[k] == v) return k;
  return -1;
}

int valence(const ShellEditor& e, int v) { return static_cast<int>(e.faces_of(v).size()); }

std::vector<int> sorted(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  return v;
}

// Pillar of v rotated to the extrusion direction of `star` (faces around v,
// v's middle at `mid`) and each side's length zoomed toward the target (at
// most x1.5 per step, never shortened). False where the direction is singular.
bool reaimed_pillar(const Shell& s, const std::vector<Tri>& star, int v, const Vec3& mid, const SmoothParams& p,
                    Vec3& bottom, Vec3& top) {
  std::vector<Vec3> normals;
  for (const Tri& t : star) {
    Vec3 q[3];
    for (int k = 0; k < 3; ++k) q[k] = t[k] == v ? mid : s.middle[t[k]];
    const Vec3 n = (q[1] - q[0]).cross(q[2] - q[0]);
    if (!(n.norm() > 0)) return false;
    normals.push_back(n.normalized());
  }
  const auto dir = extrusion_direction(normals, p.singular_dot);
  if (dir.singular) return false;
  const double lt = (s.top[v] - s.middle[v]).norm(), lb = (s.middle[v] - s.bottom[v]).norm();
  const double nt = std::min(p.target_pillar, 1.5 * lt), nb = std::min(p.target_pillar, 1.5 * lb);
  top = mid + std::max(nt, lt) * dir.direction;
  bottom = mid - std::max(nb, lb) * dir.direction;
  return true;
}

} // namespace

std::optional<EdgeFaces> edge_faces(const ShellEditor& e, int a, int b) {
  const Shell& s = e.shell();
  EdgeFaces out{-1, -1, -1, -1};
  for (int f : e.faces_of(a)) {
    const Tri& t = s.faces[f];
    const int i = corner_of(t, a);
    if (t[(i + 1) % 3] == b) {
      out.f_ab = f;
      out.c = t[(i + 2) % 3];
    } else if (t[(i + 2) % 3] == b) {
      out.f_ba = f;
      out.d = t[(i + 1) % 3];
    }
  }
  if (out.f_ab < 0 || out.f_ba < 0 || out.c == out.d) return std::nullopt;
  return out;
}

std::optional<StarCandidate> collapse_candidate(const ShellEditor& e, int from, int to) {
  const auto ef = edge_faces(e, from, to);
  if (!ef) return std::nullopt;
  const auto na = e.neighbours(from), nb = e.neighbours(to);
  std::vector<int> common;
  std::set_intersection(na.begin(), na.end(), nb.begin(), nb.end(), std::back_inserter(common));
  if (common.size() != 2) return std::nullopt; // link condition
  if (valence(e, ef->c) <= 3 || valence(e, ef->d) <= 3) return std::nullopt;
  StarCandidate c;
  c.op = OpKind::collapse;
  c.removed = sorted(e.faces_of(from));
  c.removed_vertex = from;
  c.edge = {from, to};
  for (int f : c.removed) {
    Tri t = e.shell().faces[f];
    if (corner_of(t, to) >= 0) continue; // the two faces of the edge vanish
    t[corner_of(t, from)] = to;
    c.faces.push_back(t);
  }
  return c;
}

std::optional<StarCandidate> collapse_reaimed_candidate(const ShellEditor& e, const StarCandidate& collapse,
                                                        const SmoothParams& p) {
  const Shell& s = e.shell();
  const int from = collapse.edge[0], to = collapse.edge[1];
  if (s.singular[to]) return std::nullopt;
  StarCandidate c = collapse;
  for (int f : e.faces_of(to))
    if (corner_of(s.faces[f], from) < 0) {
      c.removed.push_back(f);
      c.faces.push_back(s.faces[f]);
    }
  // `removed` stays sorted; `faces` need not follow its order.
  std::sort(c.removed.begin(), c.removed.end());
  Vec3 bottom, top;
  if (!reaimed_pillar(s, c.faces, to, s.middle[to], p, bottom, top)) return std::nullopt;
  c.moved = {to};
  c.moved_bottom = {bottom};
  c.moved_middle = {s.middle[to]};
  c.moved_top = {top};
  return c;
}

std::optional<StarCandidate> flip_candidate(const ShellEditor& e, int a, int b) {
  const auto ef = edge_faces(e, a, b);
  if (!ef) return std::nullopt;
  if (valence(e, a) <= 3 || valence(e, b) <= 3) return std::nullopt;
  const auto nc = e.neighbours(ef->c);
  if (std::binary_search(nc.begin(), nc.end(), ef->d)) return std::nullopt; // (c, d) exists
  StarCandidate c;
  c.op = OpKind::flip;
  c.edge = {a, b};
  c.removed = sorted({ef->f_ab, ef->f_ba});
  c.faces = {{a, ef->d, ef->c}, {ef->d, b, ef->c}};
  return c;
}

int flip_valence_gain(const ShellEditor& e, int a, int b) {
  const auto ef = edge_faces(e, a, b);
  if (!ef) return 0;
  auto sq = [](int x) { return (x - 6) * (x - 6); };
  const int va = valence(e, a), vb = valence(e, b), vc = valence(e, ef->c), vd = valence(e, ef->d);
  return sq(va - 1) + sq(vb - 1) + sq(vc + 1) + sq(vd + 1) - sq(va) - sq(vb) - sq(vc) - sq(vd);
}

std::optional<StarCandidate> split_candidate(const ShellEditor& e, int a, int b) {
  const auto ef = edge_faces(e, a, b);
  if (!ef) return std::nullopt;
  const Shell& s = e.shell();
  // The edge midpoint in each adjacent prism, and where its fiber meets M;
  // on a feature edge, an input vertex of its chain instead (App. B).
  std::optional<Vec3> hit = feature_split_point(s, a, b);
  const bool on_feature = s.features.edge(a, b) != nullptr;
  for (int f : {ef->f_ab, ef->f_ba}) {
    if (on_feature) break;
    const Tri& t = s.faces[f];
    double uv[3] = {0, 0, 0};
    uv[corner_of(t, a)] = 0.5;
    uv[corner_of(t, b)] = 0.5;
    const PrismGeom g = e.geom(f);
    for (int it : s.tracked[f]) {
      const auto tri = straight_triangle(s, it);
      hit = fiber_hit(g, uv[1], uv[2], tri[0], tri[1], tri[2]);
      if (hit) break;
    }
    if (hit) break;
  }
  if (!hit) return std::nullopt;
  StarCandidate c;
  c.op = OpKind::split;
  c.edge = {a, b};
  c.removed = sorted({ef->f_ab, ef->f_ba});
  const int m = kNewVertex;
  c.faces = {{a, m, ef->c}, {m, b, ef->c}, {b, m, ef->d}, {m, a, ef->d}};
  c.moved = {m};
  c.moved_bottom = {0.5 * (s.bottom[a] + s.bottom[b])};
  c.moved_middle = {*hit};
  c.moved_top = {0.5 * (s.top[a] + s.top[b])};
  return c;
}

std::vector<StarCandidate> smooth_candidates(const ShellEditor& e, int v, const SmoothParams& p) {
  std::vector<StarCandidate> out;
  const Shell& s = e.shell();
  if (s.singular[v]) return out;
  StarCandidate base;
  base.op = OpKind::smooth;
  base.removed = sorted(e.faces_of(v));
  for (int f : base.removed) base.faces.push_back(s.faces[f]);
  base.moved = {v};

  // Pan target: the input vertex nearest to the neighbours' centroid.
  const auto nb = e.neighbours(v);
  Vec3 centroid = Vec3::Zero();
  for (int w : nb) centroid += s.middle[w];
  centroid /= static_cast<double>(nb.size());
  // A feature vertex pans only along its chain (App. B; a corner not at all).
  std::vector<Vec3> targets;
  if (auto on_chain = feature_pan_targets(s, v)) {
    targets = std::move(*on_chain);
  } else {
    std::vector<int> input_vertices;
    for (int f : base.removed)
      for (int t : s.tracked[f])
        for (int iv : s.input.faces[t]) input_vertices.push_back(iv);
    std::sort(input_vertices.begin(), input_vertices.end());
    input_vertices.erase(std::unique(input_vertices.begin(), input_vertices.end()), input_vertices.end());
    for (int iv : input_vertices) targets.push_back(s.input.vertices[iv]);
  }
  double best = std::numeric_limits<double>::infinity();
  Vec3 target = s.middle[v];
  for (const Vec3& x : targets) {
    const double d = (x - centroid).squaredNorm();
    if (d < best) {
      best = d;
      target = x;
    }
  }
  const bool pan = target != s.middle[v];

  auto pillar = [&](const Vec3& mid, Vec3& bottom, Vec3& top) {
    return reaimed_pillar(s, base.faces, v, mid, p, bottom, top);
  };

  auto add = [&](const Vec3& bottom, const Vec3& mid, const Vec3& top) {
    StarCandidate c = base;
    c.moved_bottom = {bottom};
    c.moved_middle = {mid};
    c.moved_top = {top};
    out.push_back(std::move(c));
  };
  Vec3 b, t;
  if (pan && pillar(target, b, t)) add(b, target, t);
  if (pan) {
    const Vec3 delta = target - s.middle[v];
    add(s.bottom[v] + delta, target, s.top[v] + delta);
  }
  // Pillar alone only when it grows (a bare re-aim would always "succeed").
  if (pillar(s.middle[v], b, t) &&
      ((t - s.middle[v]).norm() > 1.01 * (s.top[v] - s.middle[v]).norm() ||
       (s.middle[v] - b).norm() > 1.01 * (s.middle[v] - s.bottom[v]).norm()))
    add(b, s.middle[v], t);
  return out;
}

} // namespace curvetet::shell
