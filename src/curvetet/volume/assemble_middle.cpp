#include "curvetet/volume/assemble_middle.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/core/log.hpp"
#include "curvetet/highorder/conforming_nodes.hpp"
#include "curvetet/highorder/element_map.hpp"
#include "curvetet/highorder/jacobian_certificate.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/shell/prism_tets.hpp"
#include "curvetet/shell/slab_tet_nodes.hpp"
#include "curvetet/volume/direct_fill.hpp"
#include "curvetet/volume/tetrahedralize.hpp"
#include "curvetet/volume/verify.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <map>
#include <optional>
#include <stdexcept>

namespace curvetet::volume {
namespace {

using FaceKey = std::array<int, 3>;

FaceKey sorted(FaceKey k) {
  std::sort(k.begin(), k.end());
  return k;
}

bool is_retracted(const CurvedMiddle& s, const std::vector<char>& retracted, int v) {
  return retracted[v] && !s.singular[v];
}

// The spread's matrix: for free nodes x != y, minus the number of tets
// holding the lattice edge (x, y); on the diagonal, the number of lattice
// edge ends at x. Integer counts, so any summation order gives the same
// matrix: built row by row, without a triplet per edge end.
Eigen::SparseMatrix<double> lattice_laplacian(const mesh::TetMesh& m, const std::vector<int>& free_id, int nf) {
  const std::size_t np = highorder::tet_node_count(m.order);
  const auto& edges = highorder::tet_lattice_edges(m.order);
  const auto for_each_end = [&](auto&& f) {
    for (std::size_t t = 0; t < static_cast<std::size_t>(m.num_tets()); ++t)
      for (const auto& [a, b] : edges) {
        const int x = free_id[m.tets[t * np + a]], y = free_id[m.tets[t * np + b]];
        if (x >= 0) f(x, y);
        if (y >= 0) f(y, x);
      }
  };
  std::vector<int> start(nf + 1, 0), ends(nf, 0);
  for_each_end([&](int x, int y) {
    ++ends[x];
    if (y >= 0) ++start[x + 1];
  });
  for (int x = 0; x < nf; ++x) start[x + 1] += start[x];
  std::vector<int> column(start[nf]), multiplicity(start[nf]);
  std::vector<int> next(start.begin(), start.end() - 1);
  for_each_end([&](int x, int y) {
    if (y >= 0) column[next[x]++] = y;
  });
  // Per row: its distinct free neighbours, sorted, and how often each came.
  std::vector<int> distinct(nf);
  tbb::parallel_for(0, nf, [&](int x) {
    const auto first = column.begin() + start[x];
    std::sort(first, column.begin() + start[x + 1]);
    int k = 0;
    for (int i = start[x]; i < start[x + 1]; ++i) {
      if (k > 0 && column[start[x] + k - 1] == column[i]) {
        ++multiplicity[start[x] + k - 1];
        continue;
      }
      column[start[x] + k] = column[i];
      multiplicity[start[x] + k++] = 1;
    }
    distinct[x] = k;
  });
  Eigen::SparseMatrix<double> l(nf, nf);
  Eigen::VectorXi per_column(nf);
  for (int x = 0; x < nf; ++x) per_column[x] = distinct[x] + 1;
  l.reserve(per_column);
  for (int x = 0; x < nf; ++x) { // column x, rows in increasing order (symmetric: its row x)
    bool diagonal = false;
    for (int i = start[x]; i < start[x] + distinct[x]; ++i) {
      if (!diagonal && column[i] > x) {
        l.insert(x, x) = ends[x];
        diagonal = true;
      }
      l.insert(column[i], x) = -multiplicity[i];
    }
    if (!diagonal) l.insert(x, x) = ends[x];
  }
  l.makeCompressed();
  return l;
}

// Moves every node that is not fixed by the discrete harmonic extension of
// the fixed nodes' displacement from `straight` (every lattice edge of every
// tet a unit spring). Solved by conjugate gradients with an incomplete
// Cholesky preconditioner to a relative residual of 1e-12 (a direct
// factorization is an order of magnitude slower on large fills,
// docs/performance.md); the direct solve only if CG does not get there.
// The preconditioner keeps the nodes' numbering (tet by tet, so neighbours
// are close): a fill-reducing reordering costs more than it saves here.
// The nodes only start the certificate's checks, so the rounding of either
// solve is harmless.
void spread_displacement(mesh::TetMesh& m, const std::vector<mesh::Vec3>& straight, const std::vector<char>& fixed) {
  const int nn = static_cast<int>(m.nodes.size());
  std::vector<int> free_id(nn, -1);
  int nf = 0;
  for (int i = 0; i < nn; ++i)
    if (!fixed[i]) free_id[i] = nf++;
  if (nf == 0) return;
  // The fixed neighbours' displacements, summed in tet and edge order.
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(nf, 3);
  const std::size_t np = highorder::tet_node_count(m.order);
  for (std::size_t t = 0; t < static_cast<std::size_t>(m.num_tets()); ++t)
    for (const auto& [a, b] : highorder::tet_lattice_edges(m.order)) {
      const int ga = m.tets[t * np + a], gb = m.tets[t * np + b];
      for (const auto& [x, y] : {std::pair{ga, gb}, std::pair{gb, ga}})
        if (free_id[x] >= 0 && free_id[y] < 0) rhs.row(free_id[x]) += (m.nodes[y] - straight[y]).transpose();
    }
  const Eigen::SparseMatrix<double> laplacian = lattice_laplacian(m, free_id, nf);
  // One preconditioner, the three coordinates solved at once: Eigen's
  // solver object runs columns in turn and is not safe to share, so each
  // column calls the CG kernel it uses (same arithmetic, same result).
  const Eigen::IncompleteCholesky<double, Eigen::Lower, Eigen::NaturalOrdering<int>> preconditioner(laplacian);
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(nf, 3);
  std::array<bool, 3> converged{};
  if (preconditioner.info() == Eigen::Success) tbb::parallel_for(0, 3, [&](int k) {
    Eigen::Index iterations = 2 * static_cast<Eigen::Index>(nf); // Eigen's default limit
    double error = 1e-12;                                            // in: tolerance; out: relative residual
    Eigen::VectorXd x = Eigen::VectorXd::Zero(nf);
    Eigen::internal::conjugate_gradient(laplacian.transpose(), Eigen::VectorXd(rhs.col(k)), x, preconditioner,
                                        iterations, error);
    converged[k] = error <= 1e-12;
    d.col(k) = x;
  });
  if (!(converged[0] && converged[1] && converged[2]))
    d = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>(laplacian).solve(rhs);
  for (int i = 0; i < nn; ++i)
    if (free_id[i] >= 0) m.nodes[i] = straight[i] + d.row(free_id[i]).transpose();
}

// The fill on the middle surface has interior points this many mean
// boundary edges apart, so that the interior refines with the surface too.
constexpr double kInteriorSpacing = 2;

// Marks for retraction the surface corners (ids < n) of the tets the
// certificate does not prove positive; returns how many tets those are and
// (in *added) how many corners it marked.
int retract_uncertified(const mesh::TetMesh& m, int n, std::vector<char>& retracted, int* added) {
  std::vector<char> bad(m.num_tets(), 0);
  tbb::parallel_for(0, m.num_tets(), [&](int t) {
    std::vector<mesh::Vec3> nodes(m.tet_nodes());
    m.tet_positions(t, nodes.data());
    bad[t] = highorder::certify_tet(m.order, nodes.data()).validity != highorder::Validity::positive;
  });
  *added = 0;
  for (int t = 0; t < m.num_tets(); ++t)
    for (int k = 0; k < 4 && bad[t]; ++k)
      if (m.tet(t)[k] < n && !retracted[m.tet(t)[k]]) {
        retracted[m.tet(t)[k]] = 1;
        ++*added;
      }
  return static_cast<int>(std::count(bad.begin(), bad.end(), 1));
}

} // namespace

mesh::SurfaceMesh retracted_surface(const CurvedMiddle& s, const std::vector<char>& retracted) {
  mesh::SurfaceMesh m;
  m.vertices = s.bottom;
  m.faces = s.faces;
  for (std::size_t f = 0; f < s.faces.size(); ++f)
    for (int k = 0; k < 3; ++k)
      if (!is_retracted(s, retracted, s.faces[f][k])) m.vertices[s.faces[f][k]] = s.middle_nodes[f][k];
  return m;
}

mesh::TetMesh assemble_retracted(const CurvedMiddle& s, const std::vector<char>& retracted,
                                 const mesh::LinearTetMesh& fill, int order, AssemblyStats* stats_out) {
  const int n = static_cast<int>(s.bottom.size());
  if (fill.num_vertices() < n) throw std::invalid_argument("assemble_retracted: fill lacks the surface's vertices");

  // Corners: the fill's, then the middle end of every retracted pillar.
  std::vector<mesh::Vec3> corners = fill.vertices;
  std::vector<int> middle_id(n);
  for (int v = 0; v < n; ++v) {
    middle_id[v] = v;
    if (is_retracted(s, retracted, v)) {
      middle_id[v] = static_cast<int>(corners.size());
      corners.push_back(mesh::Vec3::Zero());
    }
  }
  for (std::size_t f = 0; f < s.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) corners[middle_id[s.faces[f][k]]] = s.middle_nodes[f][k];

  // Tets: the fill's, then the slab tets whose pillar is retracted.
  std::vector<std::array<int, 4>> tets = fill.tets;
  std::vector<std::pair<int, shell::SlabTet>> slab_of; // per slab tet (after the fill's): face, canonical tet
  AssemblyStats stats;
  stats.fill_tets = fill.num_tets();
  for (int f = 0; f < static_cast<int>(s.faces.size()); ++f) {
    const auto& face = s.faces[f];
    for (const auto& st : shell::canonical_split(face)) {
      if (!is_retracted(s, retracted, face[st.pillar])) continue;
      std::array<int, 4> ids;
      for (int j = 0; j < 4; ++j) {
        const int c = st.corners[j];
        ids[j] = c >= 3 ? middle_id[face[c - 3]] : face[c];
      }
      tets.push_back(ids);
      slab_of.emplace_back(f, st);
      ++stats.slab_tets;
    }
  }

  // Boundary triangle f: the one tet face whose corners are face f's middle
  // ends (a fill face where no corner of f is retracted, else a slab tet's).
  std::map<FaceKey, int> face_of;
  for (int f = 0; f < static_cast<int>(s.faces.size()); ++f) {
    const auto& g = s.faces[f];
    face_of.emplace(sorted({middle_id[g[0]], middle_id[g[1]], middle_id[g[2]]}), f);
  }
  std::vector<std::pair<int, int>> on_face(s.faces.size(), {-1, -1});
  for (int t = 0; t < static_cast<int>(tets.size()); ++t)
    for (int lf = 0; lf < 4; ++lf) {
      FaceKey k;
      for (int j = 0; j < 3; ++j) k[j] = tets[t][highorder::kTetFaces[lf][j]];
      const auto it = face_of.find(sorted(k));
      if (it == face_of.end()) continue;
      if (on_face[it->second].first >= 0) throw std::invalid_argument("assemble_retracted: a face has two tets");
      on_face[it->second] = {t, lf};
    }
  for (const auto& [t, lf] : on_face)
    if (t < 0) throw std::invalid_argument("assemble_retracted: a middle face bounds no tet");

  const auto numbering = highorder::number_tet_nodes(static_cast<int>(corners.size()), tets, order);
  const std::size_t per_tet = highorder::tet_node_count(order);
  mesh::TetMesh out;
  out.order = order;
  out.nodes.assign(numbering.num_nodes, mesh::Vec3::Zero());
  for (std::size_t t = 0; t < tets.size(); ++t)
    for (std::size_t i = 0; i < per_tet; ++i) {
      const auto lambda = highorder::tet_node_barycentric(order, static_cast<int>(i));
      mesh::Vec3 x = mesh::Vec3::Zero();
      for (int j = 0; j < 4; ++j) x += lambda[j] * corners[tets[t][j]];
      out.nodes[numbering.tet_nodes[t * per_tet + i]] = x;
    }
  for (std::size_t v = 0; v < corners.size(); ++v) out.nodes[v] = corners[v]; // bit for bit
  const std::vector<mesh::Vec3> straight = out.nodes;

  // Slab tets: the nodes the shell certifies (shell/slab_tet_nodes, a
  // corner that is not retracted taken as a pinched pillar).
  std::vector<char> fixed(out.nodes.size(), 0);
  for (std::size_t k = 0; k < slab_of.size(); ++k) {
    const auto& [f, st] = slab_of[k];
    shell::SlabPatch patch;
    patch.degree = s.degree;
    patch.middle_nodes = s.middle_nodes[f].data();
    patch.straight_parts = s.straight_slab_parts;
    for (int c = 0; c < 3; ++c) {
      patch.cap[c] = s.bottom[s.faces[f][c]];
      patch.pinched[c] = !is_retracted(s, retracted, s.faces[f][c]);
    }
    const auto nodes = shell::slab_tet_nodes(patch, st, order);
    const std::size_t t = fill.tets.size() + k;
    for (std::size_t i = 0; i < per_tet; ++i) {
      const int g = numbering.tet_nodes[t * per_tet + i];
      if (g >= static_cast<int>(corners.size())) out.nodes[g] = nodes[i];
      fixed[g] = 1;
    }
  }

  // Boundary nodes (edges included, corners kept) on their face's patch.
  for (int f = 0; f < static_cast<int>(s.faces.size()); ++f) {
    const auto [t, lf] = on_face[f];
    for (int i : highorder::tet_face_nodes(order, lf)) {
      const int g = numbering.tet_nodes[t * per_tet + i];
      out.boundary.push_back(g);
      fixed[g] = 1;
      const auto lambda = highorder::tet_node_barycentric(order, i);
      std::array<double, 3> w{};
      for (int j = 0; j < 4; ++j)
        for (int k = 0; k < 3; ++k)
          if (tets[t][j] == middle_id[s.faces[f][k]]) w[k] = lambda[j];
      if (std::max({w[0], w[1], w[2]}) == 1.0) continue;
      out.nodes[g] = highorder::triangle_point(s.degree, s.middle_nodes[f].data(), Eigen::Vector2d(w[1], w[2]));
    }
  }
  out.tets = numbering.tet_nodes;
  spread_displacement(out, straight, fixed);
  mesh::set_default_groups(out);
  stats.boundary_triangles = static_cast<int>(s.faces.size());
  if (stats_out) *stats_out = stats;
  return out;
}

bool assemble_on_middle(const CurvedMiddle& middle, int order, mesh::TetMesh& out, nlohmann::json& report) {
  const int n = static_cast<int>(middle.bottom.size());
  std::vector<char> retracted(n, 0);
  AssemblyStats stats;
  FillStats fill_stats; // of the fill the last round used
  int layered_rounds = 0;
  using clock = std::chrono::steady_clock;
  const auto seconds_since = [](clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); };
  for (int round = 0;; ++round) {
    const auto fill_start = clock::now();
    const auto surface = retracted_surface(middle, retracted);
    // The Delaunay fill, with interior grid points, else without (a grid
    // point may fall in the circumsphere of a large surface triangle); where
    // neither applies, the layered fill (offset layer and BSP, whose thin
    // layer is the interior's and free to collapse in the curved
    // optimization, unlike the slab assembly's bottom layer).
    std::optional<mesh::LinearTetMesh> filled;
    for (const double spacing : {kInteriorSpacing * mesh::mean_edge_length(surface), 0.0}) {
      FillOptions fo;
      fo.interior_spacing = spacing;
      FillStats attempt;
      filled = fill_direct(surface, OffsetSide::inward, fo, &attempt);
      if (filled && verify_tet_mesh(*filled, surface.faces).ok()) {
        fill_stats = attempt;
        break;
      }
      filled.reset();
    }
    if (!filled) {
      TetrahedralizeOptions to;
      to.direct = false;
      try {
        auto layered = tetrahedralize(surface, to);
        filled = std::move(layered.mesh);
        fill_stats = layered.interior;
        ++layered_rounds;
      } catch (const Error& e) {
        logger().debug("assembly on the middle surface, round {}: no fill ({})", round, e.what());
        report = {{"on", "middle"}, {"rounds", round + 1}, {"fill", false}};
        return false;
      }
    }
    const double fill_seconds = seconds_since(fill_start);
    const auto assemble_start = clock::now();
    out = assemble_retracted(middle, retracted, *filled, order, &stats);
    const double assemble_seconds = seconds_since(assemble_start);
    const auto certify_start = clock::now();
    int added = 0;
    const int bad = retract_uncertified(out, n, retracted, &added);
    logger().debug("assembly on the middle surface, round {}: {} tets not certified (fill {:.2f} s, nodes {:.2f} s, "
                   "certificate {:.2f} s)",
                   round, bad, fill_seconds, assemble_seconds, seconds_since(certify_start));
    if (bad == 0 || added == 0) {
      const auto count = std::count_if(retracted.begin(), retracted.end(), [](char c) { return c != 0; });
      report = {{"on", "middle"},   {"rounds", round + 1},          {"retracted_vertices", count},
                {"fill_tets", stats.fill_tets}, {"slab_tets", stats.slab_tets}, {"boundary_triangles", stats.boundary_triangles},
                {"uncertified_tets", bad}, {"layered_fill_rounds", layered_rounds},
                {"fill_rejected", fill_stats.rejected_json()}};
      return bad == 0;
    }
  }
}

} // namespace curvetet::volume
