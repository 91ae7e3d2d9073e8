#include "curvetet/check/preconditions.hpp"

#include "curvetet/check/self_intersection.hpp"
#include "curvetet/check/solid_orientation.hpp"
#include "curvetet/geometry/predicates.hpp"
#include "curvetet/mesh/edge_topology.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>

namespace curvetet::check {
namespace {

using Ids = std::vector<long long>;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string format_example(const Ids& ids) {
  return ids.size() == 1 ? fmt::format("{}", ids[0]) : fmt::format("({})", fmt::join(ids, ", "));
}

// Adds a defect if `examples` is not empty; `total` may exceed the number kept.
void add(PreconditionReport& r, InputDefect kind, std::string element, std::string what, std::vector<Ids> examples,
         std::size_t total = 0) {
  if (examples.empty()) return;
  Defect d;
  d.kind = kind;
  d.count = std::max(total, examples.size());
  d.element = std::move(element);
  std::vector<std::string> shown;
  for (std::size_t i = 0; i < std::min<std::size_t>(examples.size(), 8); ++i) shown.push_back(format_example(examples[i]));
  const std::string noun = d.count == 1 ? d.element : d.element == "vertex" ? "vertices" : d.element + "s";
  d.message = fmt::format("{}: {} {} {}: {}{}", to_string(kind), d.count, noun, what,
                          fmt::join(shown, ", "), d.count > shown.size() ? ", ..." : "");
  if (examples.size() > kMaxExamples) examples.resize(kMaxExamples);
  d.examples = std::move(examples);
  r.defects.push_back(std::move(d));
}

// Stage 1: what can be wrong with a polygon soup before it is a mesh.
bool check_soup(const mesh::PolygonSoup& s, PreconditionReport& r) {
  if (s.points.empty() || s.polygons.empty()) {
    add(r, InputDefect::unreadable, "file", "holds no vertices or no faces (empty mesh)", {{0}});
    return false;
  }
  std::vector<Ids> non_finite, non_tri, out_of_range;
  for (std::size_t v = 0; v < s.points.size(); ++v)
    if (!s.points[v].allFinite()) non_finite.push_back({static_cast<long long>(v)});
  const auto nv = static_cast<std::int64_t>(s.points.size());
  for (std::size_t f = 0; f < s.polygons.size(); ++f) {
    const auto& poly = s.polygons[f];
    if (poly.size() != 3) non_tri.push_back({static_cast<long long>(f), static_cast<long long>(poly.size())});
    if (std::any_of(poly.begin(), poly.end(), [&](std::int64_t i) { return i < 0 || i >= nv; }))
      out_of_range.push_back({static_cast<long long>(f)});
  }
  add(r, InputDefect::non_finite, "vertex", "with a NaN or infinite coordinate (vertex ids)", non_finite);
  add(r, InputDefect::index_out_of_range, "face",
      fmt::format("referring to a vertex index outside 0..{} (face ids)", nv - 1), out_of_range);
  add(r, InputDefect::non_triangle, "face", "that are not triangles ((face id, corner count))", non_tri);
  return r.defects.empty();
}

// Stage 2: duplicate and exactly degenerate faces; smallest area as info.
void check_faces(const mesh::SurfaceMesh& m, PreconditionReport& r, std::vector<bool>& degenerate) {
  std::vector<std::pair<mesh::Tri, int>> sorted;
  sorted.reserve(m.faces.size());
  for (int f = 0; f < m.num_faces(); ++f) {
    auto t = m.faces[f];
    std::sort(t.begin(), t.end());
    sorted.emplace_back(t, f);
  }
  std::sort(sorted.begin(), sorted.end());
  std::vector<Ids> duplicates;
  for (std::size_t i = 1; i < sorted.size(); ++i)
    if (sorted[i].first == sorted[i - 1].first) duplicates.push_back({sorted[i - 1].second, sorted[i].second});
  add(r, InputDefect::duplicate_face, "face pair", "on the same three vertices ((face, face))", duplicates);

  degenerate.assign(m.faces.size(), false);
  std::vector<Ids> degen;
  const double d2 = r.bbox_diagonal * r.bbox_diagonal;
  r.min_relative_area = std::numeric_limits<double>::infinity();
  for (int f = 0; f < m.num_faces(); ++f) {
    const auto& t = m.faces[f];
    const auto &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
    if (geometry::collinear(a, b, c)) {
      degenerate[f] = true;
      degen.push_back({f});
      continue;
    }
    double rel = d2 > 0 ? geometry::triangle_area(a, b, c) / d2 : 0.0;
    if (rel < r.min_relative_area) {
      r.min_relative_area = rel;
      r.min_area_face = f;
    }
  }
  add(r, InputDefect::degenerate_triangle, "face", "with exactly zero area (collinear or coincident corners; face ids)",
      degen);
}

// v is non-manifold when its faces fall into several groups connected through
// shared edges at v (a "bow-tie"), or when an edge at v is non-manifold.
bool is_nonmanifold_vertex(int v, const mesh::SurfaceMesh& m, const mesh::EdgeTopology& topo,
                           const mesh::VertexFaces& vf, std::vector<std::pair<int, int>>& scratch) {
  const int begin = vf.offsets[v], end = vf.offsets[v + 1];
  if (end - begin <= 1) return false;
  scratch.clear(); // (edge at v, local face index)
  for (int i = begin; i < end; ++i) {
    int f = vf.faces[i];
    for (int k = 0; k < 3; ++k)
      if (m.faces[f][k] != v) {
        const int e = topo.face_edges[f][k];
        if (topo.num_faces_of(e) > 2) return true; // its link is not a single disk
        scratch.emplace_back(e, i - begin);
      }
  }
  std::sort(scratch.begin(), scratch.end());
  std::vector<int> parent(end - begin);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  int groups = end - begin;
  for (std::size_t i = 1; i < scratch.size(); ++i)
    if (scratch[i].first == scratch[i - 1].first) {
      int a = find(scratch[i].second), b = find(scratch[i - 1].second);
      if (a != b) {
        parent[a] = b;
        --groups;
      }
    }
  return groups > 1;
}

// Stage 3: topology. Returns true if the mesh is a closed oriented manifold.
bool check_topology(const mesh::SurfaceMesh& m, PreconditionReport& r) {
  auto topo = mesh::build_edge_topology(m.faces);
  std::vector<Ids> nonmanifold_edges, open_edges, misoriented;
  for (int e = 0; e < topo.num_edges(); ++e) {
    const int n = topo.num_faces_of(e);
    const Ids ends = {topo.edges[e][0], topo.edges[e][1]};
    if (n > 2) nonmanifold_edges.push_back(ends);
    if (n == 1) open_edges.push_back(ends);
    if (n != 2) continue;
    // Direction of edge e in a face: +1 if it runs edges[e][0] -> [1].
    auto direction = [&](int f) {
      const auto& t = m.faces[f];
      for (int k = 0; k < 3; ++k)
        if (t[k] == topo.edges[e][0]) return t[(k + 1) % 3] == topo.edges[e][1] ? 1 : -1;
      return 0;
    };
    if (direction(topo.faces_of(e)[0]) == direction(topo.faces_of(e)[1])) misoriented.push_back(ends);
  }
  auto vf = mesh::build_vertex_faces(m.num_vertices(), m.faces);
  std::vector<Ids> nonmanifold_vertices;
  std::vector<std::pair<int, int>> scratch;
  for (int v = 0; v < m.num_vertices(); ++v) {
    if (vf.offsets[v] == vf.offsets[v + 1]) ++r.isolated_vertices;
    if (is_nonmanifold_vertex(v, m, topo, vf, scratch)) nonmanifold_vertices.push_back({v});
  }
  int components = 0;
  mesh::face_components(m.faces, topo, &components);
  r.num_components = static_cast<std::size_t>(components);

  add(r, InputDefect::nonmanifold_edge, "edge", "shared by more than two faces ((vertex, vertex))", nonmanifold_edges);
  add(r, InputDefect::nonmanifold_vertex, "vertex", "whose faces do not form one fan (bow-tie, or on a non-manifold edge; vertex ids)", nonmanifold_vertices);
  add(r, InputDefect::open_boundary, "edge", "with only one face: the surface is not closed ((vertex, vertex))",
      open_edges);
  add(r, InputDefect::inconsistent_orientation, "edge",
      "traversed in the same direction by both faces ((vertex, vertex))", misoriented);
  return nonmanifold_edges.empty() && nonmanifold_vertices.empty() && open_edges.empty() && misoriented.empty();
}

// When nesting is undefined (intersecting components), still tell the user
// which components enclose a negative volume on their own: each is either a
// cavity or an inverted solid. Information only (double arithmetic).
void note_inward_components(const mesh::SurfaceMesh& m, PreconditionReport& r) {
  auto topo = mesh::build_edge_topology(m.faces);
  int count = 0;
  auto comp = mesh::face_components(m.faces, topo, &count);
  std::vector<double> volume(count, 0.0);
  std::vector<int> first(count, -1);
  for (int f = 0; f < m.num_faces(); ++f) {
    const auto& t = m.faces[f];
    volume[comp[f]] += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6.0;
    if (first[comp[f]] < 0) first[comp[f]] = f;
  }
  for (int c = 0; c < count; ++c)
    if (volume[c] < 0) r.inward_components.push_back(first[c]);
}

} // namespace

int PreconditionReport::exit_code() const {
  if (defects.empty()) return 0;
  auto first = std::min_element(defects.begin(), defects.end(),
                                [](const Defect& a, const Defect& b) { return a.kind < b.kind; });
  return curvetet::exit_code(first->kind);
}

std::string PreconditionReport::text() const {
  std::string out;
  if (ok()) {
    out = fmt::format("valid input: {} vertices, {} faces, {} component{}", num_vertices, num_faces, num_components,
                      num_components == 1 ? "" : "s");
  } else {
    out = fmt::format("invalid input ({} defect class{}, exit code {}):", defects.size(), defects.size() == 1 ? "" : "es",
                      exit_code());
    for (const auto& d : defects) out += "\n  " + d.message;
  }
  if (min_area_face >= 0)
    out += fmt::format("\n  info: smallest triangle area {:.3g} x bbox diagonal^2 (face {}); tiny triangles are valid",
                       min_relative_area, min_area_face);
  if (!inward_components.empty())
    out += fmt::format("\n  info: {} components face inward (cavities or inverted solids; first faces {}{})",
                       inward_components.size(),
                       fmt::join(inward_components.begin(),
                                 inward_components.begin() + std::min<std::size_t>(inward_components.size(), 8), ", "),
                       inward_components.size() > 8 ? ", ..." : "");
  if (isolated_vertices) out += fmt::format("\n  info: {} vertices belong to no face (ignored)", isolated_vertices);
  for (const auto& s : skipped) out += "\n  not checked: " + s;
  return out;
}

nlohmann::json PreconditionReport::json() const {
  nlohmann::json j;
  j["valid"] = ok();
  j["exit_code"] = exit_code();
  j["vertices"] = num_vertices;
  j["faces"] = num_faces;
  j["components"] = num_components;
  j["isolated_vertices"] = isolated_vertices;
  j["bbox_diagonal"] = bbox_diagonal;
  if (min_area_face >= 0) j["min_relative_area"] = {{"value", min_relative_area}, {"face", min_area_face}};
  j["defects"] = nlohmann::json::array();
  for (const auto& d : defects)
    j["defects"].push_back({{"class", to_string(d.kind)},
                            {"exit_code", curvetet::exit_code(d.kind)},
                            {"element", d.element},
                            {"count", d.count},
                            {"examples", d.examples},
                            {"message", d.message}});
  j["not_checked"] = skipped;
  if (!inward_components.empty()) j["inward_components_first_faces"] = inward_components;
  j["timings_s"] = {{"topology", seconds_topology},
                    {"self_intersection", seconds_self_intersection},
                    {"orientation", seconds_orientation}};
  return j;
}

PreconditionReport check_preconditions(const mesh::PolygonSoup& soup) {
  PreconditionReport r;
  r.num_vertices = soup.points.size();
  r.num_faces = soup.polygons.size();
  if (!check_soup(soup, r)) {
    r.skipped = {"faces, topology, self-intersection and orientation (the faces are not valid triangles)"};
    return r;
  }
  r.bbox_diagonal = mesh::bbox_diagonal(soup.points);
  const auto mesh = mesh::to_surface_mesh(soup);

  auto t0 = std::chrono::steady_clock::now();
  std::vector<bool> degenerate;
  check_faces(mesh, r, degenerate);
  const bool faces_ok = r.defects.empty();
  const bool manifold = check_topology(mesh, r);
  r.seconds_topology = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  auto pairs = self_intersections(mesh, degenerate);
  r.seconds_self_intersection = seconds_since(t0);
  std::vector<Ids> pair_ids;
  for (const auto& [f, g] : pairs) pair_ids.push_back({f, g});
  add(r, InputDefect::self_intersection, "face pair", "intersect improperly ((face, face))", pair_ids);

  if (!faces_ok || !manifold || !pairs.empty()) {
    r.skipped.push_back("solid orientation (needs a closed manifold without degenerate or intersecting faces)");
    if (manifold) note_inward_components(mesh, r);
    return r;
  }
  t0 = std::chrono::steady_clock::now();
  std::vector<Ids> wrong;
  for (const auto& c : solid_orientation(mesh))
    if (!c.correct()) wrong.push_back({c.first_face, c.nesting_level});
  r.seconds_orientation = seconds_since(t0);
  add(r, InputDefect::wrong_orientation, "component",
      "facing the wrong way: outer shells must face outward, cavities inward ((first face, nesting level))", wrong);
  return r;
}

mesh::SurfaceMesh require_valid_surface(const mesh::PolygonSoup& soup, PreconditionReport* report) {
  PreconditionReport r = check_preconditions(soup);
  if (report) *report = r;
  if (!r.ok()) {
    auto first = std::min_element(r.defects.begin(), r.defects.end(),
                                  [](const Defect& a, const Defect& b) { return a.kind < b.kind; });
    throw Error(first->kind, r.text());
  }
  return mesh::to_surface_mesh(soup);
}

} // namespace curvetet::check
