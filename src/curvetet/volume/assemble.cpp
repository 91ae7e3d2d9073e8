#include "curvetet/volume/assemble.hpp"

#include "curvetet/highorder/conforming_nodes.hpp"
#include "curvetet/highorder/element_map.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/shell/prism_tets.hpp"

#include <algorithm>
#include <stdexcept>

namespace curvetet::volume {
namespace {

// How to place the order-P nodes of one tet: either barycentric in its four
// corners (fill), or through the curved slab map of face `face` at the
// reference corners `ref` (slab tets).
struct TetSource {
  int face = -1;                             // -1: linear fill tet
  std::array<std::array<double, 3>, 4> ref{}; // reference (u, v, w) of each corner
  std::array<bool, 4> on_middle{};            // corner is on the middle surface
  std::array<bool, 4> pinched{};              // corner is a singular vertex
};

mesh::Vec3 slab_point(const CurvedMiddle& s, int face, const std::array<double, 3>& uvw) {
  const auto& f = s.faces[face];
  const double u = uvw[0], v = uvw[1], w = uvw[2];
  const mesh::Vec3 bottom = (1 - u - v) * s.bottom[f[0]] + u * s.bottom[f[1]] + v * s.bottom[f[2]];
  const mesh::Vec3 middle = highorder::triangle_point(s.degree, s.middle_nodes[face].data(), Eigen::Vector2d(u, v));
  return (1 - w) * bottom + w * middle;
}

// The slab map has a zero w-derivative on a pinched pillar, so a tet placed
// through it is degenerate (det J = 0) at the pinched corner. Nodes whose
// carrier (the corners with non-zero weight) holds a pinched corner are
// therefore placed on the straight simplex instead, unless they lie on the
// middle surface, which must follow the curved patch. The rule depends only
// on the node's carrier, so every tet sharing the node agrees on it.
bool straight_near_pinch(const TetSource& src, const std::array<double, 4>& lambda) {
  bool pinched = false, on_middle = true;
  for (int j = 0; j < 4; ++j)
    if (lambda[j] > 0) {
      pinched |= src.pinched[j];
      on_middle &= src.on_middle[j];
    }
  return pinched && !on_middle;
}

} // namespace

mesh::TetMesh assemble_curved_mesh(const CurvedMiddle& s, const mesh::LinearTetMesh& fill, int order,
                                   AssemblyStats* stats_out) {
  const int nb = static_cast<int>(s.bottom.size());
  if (fill.num_vertices() < nb) throw std::invalid_argument("assemble: fill lacks the bottom vertices");
  AssemblyStats stats;

  // Corner vertices: the fill's, then one middle vertex per non-singular
  // shell vertex (a singular vertex's middle is its bottom).
  std::vector<mesh::Vec3> corners = fill.vertices;
  std::vector<int> middle_id(nb);
  for (int v = 0; v < nb; ++v) {
    if (s.singular[v]) {
      middle_id[v] = v;
      continue;
    }
    middle_id[v] = static_cast<int>(corners.size());
    corners.push_back(mesh::Vec3::Zero()); // placed from the middle patches below
  }
  for (int f = 0; f < static_cast<int>(s.faces.size()); ++f)
    for (int k = 0; k < 3; ++k) corners[middle_id[s.faces[f][k]]] = s.middle_nodes[f][k];

  std::vector<std::array<int, 4>> tets = fill.tets;
  std::vector<TetSource> sources(tets.size());
  stats.fill_tets = static_cast<int>(tets.size());
  std::vector<std::pair<int, int>> boundary_faces;
  for (int f = 0; f < static_cast<int>(s.faces.size()); ++f) {
    const auto& face = s.faces[f];
    const std::array<int, 3> top = {middle_id[face[0]], middle_id[face[1]], middle_id[face[2]]};
    for (const auto& st : shell::canonical_split(face)) {
      if (s.singular[face[st.pillar]]) {
        ++stats.pinched_slab_tets;
        continue;
      }
      std::array<int, 4> ids;
      TetSource src;
      src.face = f;
      for (int j = 0; j < 4; ++j) {
        const int c = st.corners[j];
        ids[j] = c < 3 ? face[c] : middle_id[face[c - 3]];
        src.ref[j] = shell::reference_corner(c);
        src.pinched[j] = s.singular[face[c % 3]];
        src.on_middle[j] = c >= 3 || src.pinched[j];
        // A pinched corner is its upper corner too: evaluate it at w = 1 so
        // that middle-surface nodes through it land on the curved patch.
        if (src.pinched[j]) src.ref[j][2] = 1.0;
      }
      // The tet face whose corners are the three middle vertices lies on the
      // middle surface: it is a boundary triangle.
      for (int lf = 0; lf < 4; ++lf) {
        int on_top = 0;
        for (int c : highorder::kTetFaces[lf]) on_top += std::count(top.begin(), top.end(), ids[c]) > 0;
        if (on_top == 3) boundary_faces.emplace_back(static_cast<int>(tets.size()), lf);
      }
      tets.push_back(ids);
      sources.push_back(src);
      ++stats.slab_tets;
    }
  }

  const auto numbering = highorder::number_tet_nodes(static_cast<int>(corners.size()), tets, order);
  const int per_tet = highorder::tet_node_count(order);
  mesh::TetMesh out;
  out.order = order;
  out.nodes.assign(numbering.num_nodes, mesh::Vec3::Zero());
  std::vector<char> placed(numbering.num_nodes, 0);
  for (std::size_t c = 0; c < corners.size(); ++c) {
    out.nodes[c] = corners[c];
    placed[c] = 1;
  }
  for (std::size_t t = 0; t < tets.size(); ++t) {
    const auto& src = sources[t];
    for (int i = 0; i < per_tet; ++i) {
      const int g = numbering.tet_nodes[t * per_tet + i];
      const auto lambda = highorder::tet_node_barycentric(order, i);
      mesh::Vec3 x = mesh::Vec3::Zero();
      // A flat middle needs no slab map: the straight canonical tets are the
      // ones invariant 1 proves positive, while the bilinear slab map of a
      // non-planar quad can fold them.
      if (src.face < 0 || s.degree == 1) {
        for (int j = 0; j < 4; ++j) x += lambda[j] * corners[tets[t][j]];
      } else if (straight_near_pinch(src, lambda)) {
        for (int j = 0; j < 4; ++j) x += lambda[j] * corners[tets[t][j]];
      } else {
        std::array<double, 3> uvw{0, 0, 0};
        for (int j = 0; j < 4; ++j)
          for (int d = 0; d < 3; ++d) uvw[d] += lambda[j] * src.ref[j][d];
        x = slab_point(s, src.face, uvw);
      }
      if (!placed[g]) {
        out.nodes[g] = x;
        placed[g] = 1;
      } else if (g >= static_cast<int>(corners.size())) {
        stats.max_shared_node_mismatch = std::max(stats.max_shared_node_mismatch, (out.nodes[g] - x).norm());
      }
    }
  }
  out.tets = numbering.tet_nodes;
  out.tet_tags.assign(tets.size(), mesh::kDomainTag);

  for (const auto& [t, lf] : boundary_faces)
    for (int i : highorder::tet_face_nodes(order, lf)) out.boundary.push_back(numbering.tet_nodes[t * per_tet + i]);
  out.boundary_tags.assign(boundary_faces.size(), mesh::kBoundaryTag);
  stats.boundary_triangles = static_cast<int>(boundary_faces.size());
  mesh::set_default_groups(out);
  if (stats_out) *stats_out = stats;
  return out;
}

} // namespace curvetet::volume
