#include "curvetet/shell/curved_middle.hpp"

#include "curvetet/shell/slab_tet_nodes.hpp"
#include "curvetet/shell/straighten.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/geometry/predicates.hpp"
#include "curvetet/highorder/conforming_nodes.hpp"
#include "curvetet/highorder/element_map.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/highorder/patch_fit.hpp"
#include "curvetet/shell/shell_editor.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <limits>

namespace curvetet::shell {

namespace {

using highorder::PatchFitProblem;

// Nodes of directed edge (corner ia -> corner ib) of a degree-k triangle,
// the k - 1 points strictly between, from ia towards ib.
std::vector<Vec3> edge_nodes(const std::vector<Vec3>& nodes, int k, int ia, int ib) {
  std::vector<Vec3> out;
  for (int step = 1; step < k; ++step) {
    int w[3] = {0, 0, 0};
    w[ia] = k - step;
    w[ib] = step;
    out.push_back(nodes[highorder::triangle_node_index(k, {w[1], w[2]})]);
  }
  return out;
}

bool slabs_positive(const PrismGeom& g, int k, const std::vector<Vec3>& nodes, bool straight_parts,
                    const highorder::CertificateOptions& o) {
  for (const auto side : {highorder::SlabSide::bottom, highorder::SlabSide::top}) {
    const auto& cap = side == highorder::SlabSide::bottom ? g.bottom : g.top;
    std::array<bool, 3> collapsed{};
    for (int i = 0; i < 3; ++i) collapsed[i] = cap[i] == g.middle[i];
    if (collapsed[0] && collapsed[1] && collapsed[2]) continue; // a flat slab: no volume to certify
    const SlabPatch patch{k, nodes.data(), cap, side == highorder::SlabSide::bottom, collapsed, straight_parts};
    const StraightParts straight = straight_parts ? shell::straight_parts(patch) : StraightParts{};
    const bool pinched = collapsed[0] || collapsed[1] || collapsed[2];
    const bool any_straight = straight.edge[0] || straight.edge[1] || straight.edge[2];
    // The output tets are pieces of the slab map: certify the map (one
    // certificate, also what makes the curved middle a proper patch).
    if (!straight.whole) {
      const auto cert = highorder::certify_slab(k, nodes.data(), cap, side, collapsed, o);
      if (cert.validity != highorder::Validity::positive) return false;
      if (!pinched && !any_straight) continue;
    }
    // Some nodes are placed off the slab map (slab_tet_nodes): certify the
    // tets themselves, at order k + 1; straight ones by their sign.
    const Slab slab = side == highorder::SlabSide::bottom ? Slab::bottom : Slab::top;
    for (const auto& tet : canonical_split(g.ids)) {
      if (collapsed[tet.pillar]) continue;
      if (straight.whole) {
        const auto& q = tet.corners;
        if (geometry::orient3d(g.corner(slab, q[0]), g.corner(slab, q[1]), g.corner(slab, q[2]), g.corner(slab, q[3])) <= 0)
          return false;
        continue;
      }
      const auto tet_nodes = slab_tet_nodes(patch, tet, k + 1);
      if (highorder::certify_tet(k + 1, tet_nodes.data(), o).validity != highorder::Validity::positive) return false;
    }
  }
  return true;
}

int local_id(std::vector<int>& ids, int v) {
  const auto it = std::find(ids.begin(), ids.end(), v);
  if (it != ids.end()) return static_cast<int>(it - ids.begin());
  ids.push_back(v);
  return static_cast<int>(ids.size()) - 1;
}

// The star's boundary edges (a -> b as the new faces orient them) with the
// nodes the removed prism holding that same directed edge has on it.
void add_fixed_edges(const Shell& s, const StarCandidate& c, int k, std::vector<int>& ids, PatchFitProblem& p) {
  auto has_directed = [&](int a, int b) {
    for (const auto& t : c.faces)
      for (int i = 0; i < 3; ++i)
        if (t[i] == a && t[(i + 1) % 3] == b) return true;
    return false;
  };
  for (const auto& t : c.faces)
    for (int i = 0; i < 3; ++i) {
      const int a = t[i], b = t[(i + 1) % 3];
      if (has_directed(b, a)) continue; // interior edge of the star
      bool found = false;
      for (int f : c.removed) {
        const Tri& r = s.faces[f];
        for (int j = 0; j < 3 && !found; ++j)
          if (r[j] == a && r[(j + 1) % 3] == b) {
            p.fixed_edges.push_back({local_id(ids, a), local_id(ids, b), edge_nodes(s.middle_nodes[f], k, j, (j + 1) % 3)});
            found = true;
          }
        if (found) break;
      }
      if (!found) throw Error(ExitCode::internal, "curved middle fit: a star boundary edge is not an edge of the removed prisms");
    }
}

// Centroid and edge midpoints of an input face.
constexpr double kFaceSampleWeights[4][3] = {{1.0 / 3, 1.0 / 3, 1.0 / 3}, {0.5, 0.5, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5}};

void add_samples(const Shell& s, const StarCandidate& c, PatchFitProblem& p) {
  for (const auto& im : c.images) p.samples.push_back({im.local, {im.u, im.v}, s.points[im.point].position});
  for (std::size_t k = 0; k < c.faces.size(); ++k) {
    if (c.tracked[k].empty()) continue;
    const PrismProjection project(c.geoms[k]);
    for (int t : c.tracked[k]) {
      // A point of M̄ (where Π acts) paired with the same point of M (β⁻¹).
      const auto bar = straight_triangle(s, c, t);
      const auto& f = s.input.faces[t];
      const std::array<Vec3, 3> in{s.input.vertices[f[0]], s.input.vertices[f[1]], s.input.vertices[f[2]]};
      for (const auto& w : kFaceSampleWeights) {
        const Vec3 x = w[0] * bar[0] + w[1] * bar[1] + w[2] * bar[2];
        double depth;
        const auto uv = project(x, 1e-9, &depth);
        if (uv) p.samples.push_back({static_cast<int>(k), {(*uv)[0], (*uv)[1]}, Vec3(w[0] * in[0] + w[1] * in[1] + w[2] * in[2])});
      }
    }
  }
}

} // namespace

CurvedMiddleFit::CurvedMiddleFit(int degree) : degree_(degree) {
  if (degree < 2 || degree > 7) throw Error(ExitCode::usage, "the curved middle degree must be in 2..7 (order 3..8)");
  // A rejected fit only costs a coarser result; keep the budget small.
  certificate_.max_pieces = 200;
  certificate_.max_depth = 10;
}

bool CurvedMiddleFit::fit_and_check(const ShellEditor& editor, StarCandidate& c, double epsilon) const {
  const Shell& s = editor.shell();
  if (s.middle_degree != degree_ || s.middle_nodes.size() != s.faces.size())
    throw Error(ExitCode::internal, "curved middle fit: the shell's middle nodes are not of the fitted degree");
  PatchFitProblem p;
  p.degree = degree_;
  std::vector<int> ids;
  for (const auto& t : c.faces) p.triangles.push_back({local_id(ids, t[0]), local_id(ids, t[1]), local_id(ids, t[2])});
  add_fixed_edges(s, c, degree_, ids, p);
  p.corners.resize(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) p.corners[i] = editor.middle(c, ids[i]);
  add_samples(s, c, p);
  // Alternatives in order: the least-squares fit, then (where that misses
  // epsilon at a constraint point or is not certified, e.g. across a sharp
  // crease) the star's free nodes left flat, so curving never makes a star
  // that a flat middle would pass fail.
  auto within_epsilon = [&](const std::vector<std::vector<Vec3>>& nodes) {
    for (const auto& im : c.images) {
      const Vec3 x = highorder::triangle_point(degree_, nodes[im.local].data(), Eigen::Vector2d(im.u, im.v));
      if (!((x - s.points[im.point].position).norm() < epsilon)) return false;
    }
    return true;
  };
  using clock = std::chrono::steady_clock;
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (attempt == 1) p.samples.clear(); // minimum-norm change from flat: the free nodes stay flat
    const auto t0 = clock::now();
    auto fit = highorder::fit_patch_star(p);
    const auto t1 = clock::now();
    bool ok = within_epsilon(fit.nodes);
    for (std::size_t k = 0; k < c.faces.size() && ok; ++k)
      ok = slabs_positive(c.geoms[k], degree_, fit.nodes[k], s.straight_slab_parts, certificate_);
    const auto t2 = clock::now();
    fits_ += 1;
    rejected_ += ok ? 0 : 1;
    fit_ns_ += std::chrono::duration_cast<std::chrono::nanoseconds>(t1 - t0).count();
    certificate_ns_ += std::chrono::duration_cast<std::chrono::nanoseconds>(t2 - t1).count();
    if (ok) {
      c.middle_nodes = std::move(fit.nodes);
      return true;
    }
  }
  return false;
}

CurvedFitStats CurvedMiddleFit::stats() const {
  return {degree_, fits_.load(), rejected_.load(), fit_ns_.load() * 1e-9, certificate_ns_.load() * 1e-9};
}

nlohmann::json CurvedFitStats::json() const {
  return {{"degree", degree},
          {"fits", fits},
          {"fits_rejected_by_certificate", rejected},
          {"fit_cpu_seconds", fit_seconds},
          {"certificate_cpu_seconds", certificate_seconds}};
}

Vec3 CurvedMiddleFit::evaluate(const StarCandidate& c, int k, double u, double v) const {
  return highorder::triangle_point(degree_, c.middle_nodes[k].data(), Eigen::Vector2d(u, v));
}

int first_uncertified_prism(const Shell& s) {
  if (s.middle_nodes.empty()) return -1;
  highorder::CertificateOptions o;
  std::atomic<int> worst{std::numeric_limits<int>::max()};
  tbb::parallel_for(0, s.num_prisms(), [&](int f) {
    if (!slabs_positive(prism_geom(s, f), s.middle_degree, s.middle_nodes[f], s.straight_slab_parts, o)) {
      int cur = worst.load();
      while (f < cur && !worst.compare_exchange_weak(cur, f)) {
      }
    }
  });
  return worst.load() == std::numeric_limits<int>::max() ? -1 : worst.load();
}

mesh::TetMesh middle_surface_mesh(const Shell& s) {
  const int k = s.middle_nodes.empty() ? 1 : s.middle_degree;
  const auto numbering = highorder::number_triangle_nodes(s.num_vertices(), s.faces, k);
  mesh::TetMesh m;
  m.order = k;
  m.nodes.assign(numbering.num_nodes, Vec3::Zero());
  for (int v = 0; v < s.num_vertices(); ++v) m.nodes[v] = s.middle[v];
  const int per = highorder::triangle_node_count(k);
  for (int f = 0; f < s.num_prisms(); ++f)
    for (int i = 0; i < per; ++i) {
      const int g = numbering.tet_nodes[static_cast<std::size_t>(f) * per + i];
      if (i >= 3) m.nodes[g] = s.middle_nodes[f][i]; // shared edge nodes agree bitwise between prisms
    }
  m.boundary = numbering.tet_nodes;
  m.boundary_tags.assign(s.num_prisms(), mesh::kBoundaryTag);
  m.groups = {{2, mesh::kBoundaryTag, "middle"}};
  return m;
}

} // namespace curvetet::shell
