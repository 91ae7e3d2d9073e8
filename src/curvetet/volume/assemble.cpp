#include "curvetet/volume/assemble.hpp"

#include "curvetet/highorder/conforming_nodes.hpp"
#include "curvetet/highorder/element_map.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/shell/prism_tets.hpp"
#include "curvetet/shell/slab_tet_nodes.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>

namespace curvetet::volume {
namespace {

// Which linear cap a slab has beside the curved middle: bottom slabs run
// B (w = 0) -> middle (w = 1), top slabs middle (w = 0) -> T (w = 1).
enum class Cap { bottom, top };

// How to place the order-P nodes of one tet: barycentric in its four
// corners (fill, face = -1), or as canonical tet `tet` of the slab of face
// `face` (shell::slab_tet_nodes, the placement the shell certifies).
struct TetSource {
  int face = -1;
  Cap cap = Cap::bottom;
  shell::SlabTet tet{};
};

shell::SlabPatch slab_patch(const CurvedMiddle& s, int face, Cap cap) {
  const auto& f = s.faces[face];
  const auto& caps = cap == Cap::bottom ? s.bottom : s.top;
  shell::SlabPatch p;
  p.degree = s.degree;
  p.middle_nodes = s.middle_nodes[face].data();
  p.bottom = cap == Cap::bottom;
  p.straight_parts = s.straight_slab_parts;
  for (int k = 0; k < 3; ++k) {
    p.cap[k] = caps[f[k]];
    p.pinched[k] = s.singular[f[k]];
  }
  return p;
}

// The 3 canonical tets of every slab on one side of the middle, appended to
// `tets` / `sources`. lower[v] / upper[v]: corner ids of shell vertex v's
// pillar ends in this slab. Bottom slabs also report their middle faces (the
// domain's boundary) in `middle_faces` as (tet, local face).
void add_slab_tets(const CurvedMiddle& s, Cap cap, const std::vector<int>& lower, const std::vector<int>& upper,
                   std::vector<std::array<int, 4>>& tets, std::vector<TetSource>& sources, int& count, int& pinched,
                   std::vector<std::pair<int, int>>* middle_faces) {
  const std::vector<int>& on_middle_ids = cap == Cap::bottom ? upper : lower;
  for (int f = 0; f < static_cast<int>(s.faces.size()); ++f) {
    const auto& face = s.faces[f];
    const std::array<int, 3> mid = {on_middle_ids[face[0]], on_middle_ids[face[1]], on_middle_ids[face[2]]};
    for (const auto& st : shell::canonical_split(face)) {
      if (s.singular[face[st.pillar]]) {
        ++pinched;
        continue;
      }
      std::array<int, 4> ids;
      for (int j = 0; j < 4; ++j) {
        const int c = st.corners[j];
        ids[j] = c >= 3 ? upper[face[c - 3]] : lower[face[c]];
      }
      const TetSource src{f, cap, st};
      if (middle_faces)
        for (int lf = 0; lf < 4; ++lf) {
          int on = 0;
          for (int c : highorder::kTetFaces[lf]) on += std::count(mid.begin(), mid.end(), ids[c]) > 0;
          if (on == 3) middle_faces->emplace_back(static_cast<int>(tets.size()), lf);
        }
      tets.push_back(ids);
      sources.push_back(src);
      ++count;
    }
  }
}

// Faces of `ext` used by one tet whose corners are not all top vertices
// (ids < num_top): the box, as (tet, local face), outward.
std::vector<std::pair<int, int>> box_faces(const mesh::LinearTetMesh& ext, int num_top) {
  std::map<std::array<int, 3>, std::pair<int, int>> once;
  for (int t = 0; t < ext.num_tets(); ++t)
    for (int lf = 0; lf < 4; ++lf) {
      std::array<int, 3> key;
      for (int k = 0; k < 3; ++k) key[k] = ext.tets[t][highorder::kTetFaces[lf][k]];
      std::sort(key.begin(), key.end());
      auto [it, inserted] = once.emplace(key, std::make_pair(t, lf));
      if (!inserted) once.erase(it);
    }
  std::vector<std::pair<int, int>> out;
  for (const auto& [key, use] : once)
    if (key[2] >= num_top) out.push_back(use);
  std::sort(out.begin(), out.end());
  return out;
}

} // namespace

mesh::TetMesh assemble_curved_mesh(const CurvedMiddle& s, const mesh::LinearTetMesh& fill, int order,
                                   AssemblyStats* stats_out, const mesh::LinearTetMesh* exterior) {
  const int nb = static_cast<int>(s.bottom.size());
  if (fill.num_vertices() < nb) throw std::invalid_argument("assemble: fill lacks the bottom vertices");
  if (exterior && (static_cast<int>(s.top.size()) != nb || exterior->num_vertices() < nb))
    throw std::invalid_argument("assemble: the exterior needs the top vertices");
  AssemblyStats stats;

  // Corner vertices: the fill's, then one middle vertex per non-singular
  // shell vertex (a singular vertex's middle is its bottom), then with an
  // exterior one top vertex per non-singular shell vertex and the exterior
  // fill's own vertices.
  std::vector<mesh::Vec3> corners = fill.vertices;
  std::vector<int> bottom_id(nb), middle_id(nb), top_id(nb);
  for (int v = 0; v < nb; ++v) {
    bottom_id[v] = v;
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
  std::vector<std::pair<int, int>> boundary_faces, outer_faces;
  add_slab_tets(s, Cap::bottom, bottom_id, middle_id, tets, sources, stats.slab_tets, stats.pinched_slab_tets,
                &boundary_faces);
  const int interior_tets = static_cast<int>(tets.size());

  if (exterior) {
    std::vector<int> ext_id(exterior->num_vertices());
    for (int v = 0; v < nb; ++v) {
      top_id[v] = s.singular[v] ? middle_id[v] : static_cast<int>(corners.size());
      if (!s.singular[v]) corners.push_back(s.top[v]);
      ext_id[v] = top_id[v];
    }
    for (int v = nb; v < exterior->num_vertices(); ++v) {
      ext_id[v] = static_cast<int>(corners.size());
      corners.push_back(exterior->vertices[v]);
    }
    const int first = static_cast<int>(tets.size());
    for (const auto& t : exterior->tets) tets.push_back({ext_id[t[0]], ext_id[t[1]], ext_id[t[2]], ext_id[t[3]]});
    sources.resize(tets.size());
    stats.exterior_fill_tets = exterior->num_tets();
    for (const auto& [t, lf] : box_faces(*exterior, nb)) outer_faces.emplace_back(first + t, lf);
    int pinched_top = 0;
    add_slab_tets(s, Cap::top, middle_id, top_id, tets, sources, stats.top_slab_tets, pinched_top, nullptr);
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
    // A flat middle needs no slab map: slab_tet_nodes then gives the
    // straight canonical tets that invariant 1 proves positive.
    const std::vector<mesh::Vec3> slab =
        src.face < 0 ? std::vector<mesh::Vec3>{} : shell::slab_tet_nodes(slab_patch(s, src.face, src.cap), src.tet, order);
    for (int i = 0; i < per_tet; ++i) {
      const int g = numbering.tet_nodes[t * per_tet + i];
      mesh::Vec3 x = mesh::Vec3::Zero();
      if (src.face < 0) {
        const auto lambda = highorder::tet_node_barycentric(order, i);
        for (int j = 0; j < 4; ++j) x += lambda[j] * corners[tets[t][j]];
      } else {
        x = slab[i];
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
  for (const auto& faces : {boundary_faces, outer_faces})
    for (const auto& [t, lf] : faces)
      for (int i : highorder::tet_face_nodes(order, lf)) out.boundary.push_back(numbering.tet_nodes[t * per_tet + i]);
  stats.boundary_triangles = static_cast<int>(boundary_faces.size());
  stats.box_triangles = static_cast<int>(outer_faces.size());
  mesh::set_default_groups(out);
  if (exterior) {
    std::fill(out.tet_tags.begin() + interior_tets, out.tet_tags.end(), mesh::kExteriorTag);
    std::fill(out.boundary_tags.begin() + stats.boundary_triangles, out.boundary_tags.end(), mesh::kBoxTag);
    mesh::add_exterior_groups(out);
  }
  if (stats_out) *stats_out = stats;
  return out;
}

} // namespace curvetet::volume
