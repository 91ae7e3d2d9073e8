#include "curvetet/check/verify_tet_mesh.hpp"

#include "curvetet/check/boundary_linearization.hpp"
#include "curvetet/check/closest_points.hpp"
#include "curvetet/check/curved_distance.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/highorder/quality.hpp"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

namespace curvetet::check {

namespace {

constexpr std::size_t kExamples = 20;

void check_positivity(const mesh::TetMesh& m, const TetMeshVerifyOptions& o, TetMeshVerification& r) {
  const int n = m.num_tets();
  r.validity.assign(n, highorder::Validity::undecided);
  r.min_det_lower.assign(n, 0);
  r.min_scaled_jacobian.assign(n, 0);
  r.max_amips.assign(n, 0);
  std::vector<double> upper(n, 0), mean(n, 0);
  tbb::parallel_for(0, n, [&](int t) {
    std::vector<Eigen::Vector3d> nodes(m.tet_nodes());
    m.tet_positions(t, nodes.data());
    auto c = highorder::certify_tet(m.order, nodes.data(), o.certificate);
    r.validity[t] = c.validity;
    r.min_det_lower[t] = c.min_det_lower;
    upper[t] = c.min_det_upper;
    auto q = highorder::tet_quality(m.order, nodes.data());
    r.min_scaled_jacobian[t] = q.min_scaled_jacobian;
    r.max_amips[t] = q.max_amips;
    mean[t] = q.mean_amips;
  });
  r.min_det_lower_bound = r.min_det_upper_bound = r.worst_scaled_jacobian = std::numeric_limits<double>::infinity();
  double sum = 0;
  for (int t = 0; t < n; ++t) {
    switch (r.validity[t]) {
      case highorder::Validity::positive: ++r.positive; break;
      case highorder::Validity::invalid:
        ++r.invalid;
        if (r.invalid_examples.size() < kExamples) r.invalid_examples.push_back(t);
        break;
      case highorder::Validity::undecided:
        ++r.undecided;
        if (r.undecided_examples.size() < kExamples) r.undecided_examples.push_back(t);
        break;
    }
    r.min_det_lower_bound = std::min(r.min_det_lower_bound, r.min_det_lower[t]);
    r.min_det_upper_bound = std::min(r.min_det_upper_bound, upper[t]);
    r.worst_scaled_jacobian = std::min(r.worst_scaled_jacobian, r.min_scaled_jacobian[t]);
    r.worst_amips = std::max(r.worst_amips, r.max_amips[t]);
    sum += mean[t];
  }
  r.mean_amips = n ? sum / n : 0;
  if (n == 0) r.min_det_lower_bound = r.min_det_upper_bound = r.worst_scaled_jacobian = 0;
}

// Boundary triangles split by the region they bound (with one region, all of
// them are the domain's), as meshes sharing the input's nodes.
struct RegionBoundaries {
  mesh::TetMesh domain; // nodes + the domain's boundary triangles
  mesh::TetMesh outer;  // nodes + the exterior's outer triangles (the box)
};

// A tet face's (tet, local face) on the side it is seen from.
struct FaceSide {
  int tet = -1, face = -1;
};

// Whether the listed triangle `tri` is `side`'s face with the same
// orientation and the same high-order nodes (counts the mismatch in r).
bool matches_face(const mesh::TetMesh& m, const int* tri, const FaceSide& side, TetMeshVerification& r) {
  const int* tet = m.tet(side.tet);
  const int f = side.face;
  int local[3]; // tet-local corner of the triangle's corners
  for (int k = 0; k < 3; ++k)
    for (int v = 0; v < 4; ++v)
      if (tet[v] == tri[k]) local[k] = v;
  int rot = 0;
  while (highorder::kTetFaces[f][rot] != local[0]) ++rot;
  if (highorder::kTetFaces[f][(rot + 1) % 3] != local[1]) {
    ++r.boundary_flipped;
    return false;
  }
  // Triangle node (a, b) sits at tet lattice point c0 + a/P (c1-c0) + b/P (c2-c0).
  const int p = m.order;
  const std::array<int, 3> corner[4] = {{0, 0, 0}, {p, 0, 0}, {0, p, 0}, {0, 0, p}};
  for (int i = 0; i < m.triangle_nodes(); ++i) {
    auto [a, bb] = highorder::triangle_node(p, i);
    std::array<int, 3> q;
    for (int k = 0; k < 3; ++k)
      q[k] = corner[local[0]][k] + (a * (corner[local[1]][k] - corner[local[0]][k]) +
                                    bb * (corner[local[2]][k] - corner[local[0]][k])) / p;
    if (tet[highorder::tet_node_index(p, q)] != tri[i]) {
      ++r.boundary_node_mismatch;
      return false;
    }
  }
  return true;
}

// Region faces: a face with exactly one domain tet bounds the domain (seen
// from that tet); a face used once by an exterior tet is an outer face. The
// listed triangles must be exactly these, seen from the right side.
RegionBoundaries check_conformity(const mesh::TetMesh& m, TetMeshVerification& r) {
  std::vector<char> exterior(m.num_tets(), 0);
  if (static_cast<int>(m.tet_tags.size()) == m.num_tets()) {
    const auto ext = std::count(m.tet_tags.begin(), m.tet_tags.end(), mesh::kExteriorTag);
    if (ext > 0 && ext < m.num_tets())
      for (int t = 0; t < m.num_tets(); ++t) exterior[t] = m.tet_tags[t] == mesh::kExteriorTag;
    r.exterior_tets = std::count(exterior.begin(), exterior.end(), 1);
  }
  struct Use {
    FaceSide side[2];
    int count = 0;
  };
  std::map<std::array<int, 3>, Use> faces;
  for (int t = 0; t < m.num_tets(); ++t)
    for (int f = 0; f < 4; ++f) {
      std::array<int, 3> c;
      for (int k = 0; k < 3; ++k) c[k] = m.tet(t)[highorder::kTetFaces[f][k]];
      std::sort(c.begin(), c.end());
      Use& u = faces[c];
      if (u.count < 2) u.side[u.count] = {t, f};
      if (++u.count == 3) ++r.overshared_faces;
    }
  // The side a listed triangle on this face must be seen from, or none.
  auto region_side = [&](const Use& u, bool& outer) -> std::optional<FaceSide> {
    outer = false;
    if (u.count == 1) {
      outer = exterior[u.side[0].tet];
      return u.side[0];
    }
    if (u.count == 2 && exterior[u.side[0].tet] != exterior[u.side[1].tet])
      return exterior[u.side[0].tet] ? u.side[1] : u.side[0];
    return std::nullopt;
  };

  RegionBoundaries out;
  out.domain.order = out.outer.order = m.order;
  out.domain.nodes = m.nodes;
  auto append = [&](mesh::TetMesh& to, const int* tri) { to.boundary.insert(to.boundary.end(), tri, tri + m.triangle_nodes()); };
  std::map<std::array<int, 3>, int> listed;
  bool any_outer = false;
  for (int b = 0; b < m.num_boundary(); ++b) {
    const int* tri = m.boundary_triangle(b);
    std::array<int, 3> c{tri[0], tri[1], tri[2]};
    std::sort(c.begin(), c.end());
    listed.emplace(c, b);
    auto it = faces.find(c);
    bool outer = false;
    const auto side = it == faces.end() ? std::nullopt : region_side(it->second, outer);
    if (!side) {
      ++r.boundary_extra;
      continue;
    }
    if (!matches_face(m, tri, *side, r)) continue;
    append(outer ? out.outer : out.domain, tri);
    any_outer |= outer;
  }
  const bool derive = m.num_boundary() == 0 && m.num_tets() > 0;
  r.boundary_listed = !derive;
  for (const auto& [key, use] : faces) {
    bool outer = false;
    const auto side = region_side(use, outer);
    if (!side) continue;
    if (outer)
      ++r.outer_triangles;
    else if (use.count == 2)
      ++r.interface_triangles;
    if (derive) {
      // No boundary listed: derive it.
      std::vector<int> tri;
      for (int n : highorder::tet_face_nodes(m.order, side->face)) tri.push_back(m.tet(side->tet)[n]);
      append(outer ? out.outer : out.domain, tri.data());
      any_outer |= outer;
    } else if (!listed.count(key)) {
      ++r.boundary_missing;
    }
  }
  if (any_outer) out.outer.nodes = m.nodes;
  return out;
}

void check_distances(const mesh::TetMesh& domain, const BoundaryLinearization& lin, const TetMeshVerifyOptions& o,
                     TetMeshVerification& r) {
  const mesh::SurfaceMesh& in = *o.input;
  r.has_input = true;
  r.epsilon = o.epsilon;
  double d = 1.0;
  auto stats = [&d](const std::vector<double>& v, double& max, double& mean) {
    max = 0;
    double sum = 0;
    for (double x : v) {
      max = std::max(max, x);
      sum += x;
    }
    max /= d;
    mean = v.empty() ? 0 : sum / v.size() / d;
  };
  // Input vertices that belong to a face (isolated ones are ignored, as in
  // the input preconditions).
  std::vector<char> used(in.vertices.size(), 0);
  for (const auto& f : in.faces)
    for (int v : f) used[v] = 1;
  std::vector<mesh::Vec3> points;
  for (std::size_t i = 0; i < used.size(); ++i)
    if (used[i]) points.push_back(in.vertices[i]);
  r.bbox_diagonal = mesh::bbox_diagonal(points);
  d = r.bbox_diagonal > 0 ? r.bbox_diagonal : 1.0;
  stats(distances_to_curved_boundary(domain, lin, points), r.input_to_boundary_max, r.input_to_boundary_mean);
  stats(distances_to_surface(in, lin.surface.vertices), r.boundary_to_input_max, r.boundary_to_input_mean);
}

std::string list(const std::vector<int>& ids) {
  std::string s;
  for (int id : ids) s += (s.empty() ? "" : ", ") + std::to_string(id);
  return s;
}

} // namespace

TetMeshVerification verify_tet_mesh(const mesh::TetMesh& m, const TetMeshVerifyOptions& o) {
  TetMeshVerification r;
  r.order = m.order;
  r.num_nodes = m.nodes.size();
  r.num_tets = m.num_tets();
  r.num_boundary = m.num_boundary();
  check_positivity(m, o, r);
  RegionBoundaries boundaries = check_conformity(m, r);
  r.segments_per_edge = o.segments_per_edge > 0 ? o.segments_per_edge : 2 * m.order;
  if (boundaries.outer.num_boundary() > 0)
    r.outer_surface =
        check_preconditions(mesh::to_soup(linearize_boundary(boundaries.outer, r.segments_per_edge).surface));
  BoundaryLinearization lin = linearize_boundary(boundaries.domain, r.segments_per_edge);
  r.linearized_faces = lin.surface.faces.size();
  r.surface = check_preconditions(mesh::to_soup(lin.surface));
  if (r.surface.ok()) {
    r.curved_boundary = certify_curved_boundary(boundaries.domain);
    r.curved_boundary_checked = true;
  }
  if (o.input) check_distances(boundaries.domain, lin, o, r);
  return r;
}

std::string TetMeshVerification::text() const {
  std::string s = fmt::format("{}: order {}, {} nodes, {} tets, {} boundary triangles\n", ok() ? "VALID" : "INVALID",
                              order, num_nodes, num_tets, num_boundary);
  s += fmt::format("  positivity: {} positive, {} invalid, {} undecided; min det J in [{:.6g}, {:.6g}]{}\n", positive,
                   invalid, undecided, min_det_lower_bound, min_det_upper_bound, positivity_ok() ? "" : "  FAIL");
  if (!invalid_examples.empty()) s += "    invalid tets (0-based): " + list(invalid_examples) + "\n";
  if (!undecided_examples.empty()) s += "    undecided tets (0-based): " + list(undecided_examples) + "\n";
  s += fmt::format("  quality: min scaled Jacobian {:.4g}, AMIPS max {:.4g}, mean {:.4g}\n", worst_scaled_jacobian,
                   worst_amips, mean_amips);
  s += fmt::format(
      "  conformity: {} faces shared by >2 tets, boundary: {} missing, {} extra, {} flipped, {} with other nodes{}{}\n",
      overshared_faces, boundary_missing, boundary_extra, boundary_flipped, boundary_node_mismatch,
      boundary_listed ? "" : " (no boundary in the file: derived from the tets)", conformity_ok() ? "" : "  FAIL");
  s += fmt::format("  boundary surface ({} segments per edge, {} flat triangles): {}\n", segments_per_edge,
                   linearized_faces, surface.ok() ? "closed, manifold, oriented, no self-intersection" : "FAIL");
  if (!surface.ok())
    for (const auto& d : surface.defects) s += "    " + d.message + "\n";
  if (curved_boundary_checked) {
    const auto& c = curved_boundary;
    s += fmt::format("  curved boundary: {} triangles, {} close pairs: {} ({} piece proofs, up to {} splits)\n",
                     c.patches, c.pairs,
                     c.ok() ? "certified to meet only at shared corners and edges"
                            : fmt::format("FAIL, {} not settled", c.unsettled.size()),
                     c.piece_tests, c.deepest);
    if (!c.ok()) {
      std::string pairs;
      for (std::size_t k = 0; k < std::min<std::size_t>(c.unsettled.size(), 10); ++k)
        pairs += fmt::format("{}({}, {})", k ? ", " : "", c.unsettled[k].first, c.unsettled[k].second);
      s += "    boundary triangle pairs (0-based; (i, i): triangle i alone): " + pairs + "\n";
    }
  }
  if (exterior_tets > 0) {
    s += fmt::format("  exterior region: {} tets, {} interface triangles, {} outer triangles: {}\n", exterior_tets,
                     interface_triangles, outer_triangles,
                     outer_surface.ok() ? "outer surface closed, manifold, oriented, no self-intersection" : "FAIL");
    for (const auto& d : outer_surface.defects) s += "    " + d.message + "\n";
  }
  if (has_input)
    s += fmt::format(
        "  distance (relative to input bbox diagonal {:.6g}): input->boundary max {:.3g} mean {:.3g}, "
        "boundary->input max {:.3g} mean {:.3g}; epsilon {:.3g}{}\n",
        bbox_diagonal, input_to_boundary_max, input_to_boundary_mean, boundary_to_input_max, boundary_to_input_mean,
        epsilon,
        distance_ok()            ? ""
        : !input_to_boundary_ok() && !boundary_to_input_ok() ? "  FAIL (both directions exceed epsilon)"
        : !input_to_boundary_ok() ? "  FAIL (input->boundary exceeds epsilon)"
                                  : "  FAIL (boundary->input exceeds epsilon)");
  return s;
}

nlohmann::json TetMeshVerification::json() const {
  nlohmann::json j;
  j["valid"] = ok();
  j["order"] = order;
  j["nodes"] = num_nodes;
  j["tets"] = num_tets;
  j["boundary_triangles"] = num_boundary;
  j["positivity"] = {{"ok", positivity_ok()},
                     {"positive", positive},
                     {"invalid", invalid},
                     {"undecided", undecided},
                     {"invalid_examples", invalid_examples},
                     {"undecided_examples", undecided_examples},
                     {"min_det_lower_bound", min_det_lower_bound},
                     {"min_det_upper_bound", min_det_upper_bound}};
  j["quality"] = {{"min_scaled_jacobian", worst_scaled_jacobian}, {"max_amips", worst_amips}, {"mean_amips", mean_amips}};
  j["conformity"] = {{"ok", conformity_ok()},
                     {"faces_shared_by_more_than_two_tets", overshared_faces},
                     {"boundary_listed", boundary_listed},
                     {"boundary_missing", boundary_missing},
                     {"boundary_extra", boundary_extra},
                     {"boundary_flipped", boundary_flipped},
                     {"boundary_node_mismatch", boundary_node_mismatch}};
  j["boundary_surface"] = surface.json();
  j["boundary_surface"]["segments_per_edge"] = segments_per_edge;
  j["boundary_surface"]["ok"] = surface_ok();
  if (curved_boundary_checked) {
    nlohmann::json unsettled = nlohmann::json::array();
    for (const auto& [a, b] : curved_boundary.unsettled) unsettled.push_back({a, b});
    j["boundary_surface"]["curved"] = {{"ok", curved_boundary.ok()},
                                       {"triangles", curved_boundary.patches},
                                       {"close_pairs", curved_boundary.pairs},
                                       {"piece_proofs", curved_boundary.piece_tests},
                                       {"deepest_split", curved_boundary.deepest},
                                       {"unsettled_pairs", unsettled}};
  }
  if (exterior_tets > 0)
    j["exterior"] = {{"tets", exterior_tets},
                     {"interface_triangles", interface_triangles},
                     {"outer_triangles", outer_triangles},
                     {"outer_surface", outer_surface.json()}};
  j["boundary_surface"]["linearization"] =
      "exact predicates on a conforming flat triangulation of the curved boundary (segments_per_edge^2 per face); "
      "input_to_boundary on the curved triangles themselves (check/curved_distance.hpp)";
  if (has_input)
    j["distance"] = {{"ok", distance_ok()},
                     {"input_to_boundary_ok", input_to_boundary_ok()},
                     {"boundary_to_input_ok", boundary_to_input_ok()},
                     {"epsilon_relative", epsilon},
                     {"bbox_diagonal", bbox_diagonal},
                     {"input_to_boundary_max", input_to_boundary_max},
                     {"input_to_boundary_mean", input_to_boundary_mean},
                     {"boundary_to_input_max", boundary_to_input_max},
                     {"boundary_to_input_mean", boundary_to_input_mean}};
  return j;
}

} // namespace curvetet::check
