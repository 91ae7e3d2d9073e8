#include "curvetet/core/error.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/io/msh.hpp"
#include "curvetet/io/write_surface.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <ostream>

namespace curvetet::io {

namespace {

// Gmsh element types of Lagrange lines of order 1..8.
int gmsh_line_type(int order) {
  constexpr int kTypes[8] = {1, 8, 26, 27, 28, 62, 63, 64};
  return kTypes[order - 1];
}

int tag_or_zero(const std::vector<int>& tags, int i) { return i < static_cast<int>(tags.size()) ? tags[i] : 0; }

// Distinct physical tags in order of first use (0 = none counts as a tag, so
// every element has an entity).
std::vector<int> distinct(const std::vector<int>& tags, int count) {
  std::vector<int> out;
  for (int i = 0; i < count; ++i) {
    const int t = tag_or_zero(tags, i);
    if (std::find(out.begin(), out.end(), t) == out.end()) out.push_back(t);
  }
  return out;
}

int index_of(const std::vector<int>& v, int x) { return static_cast<int>(std::find(v.begin(), v.end(), x) - v.begin()); }

// One geometric entity per physical tag and dimension: surfaces (dim 2,
// entity tags 1..S) for the boundary triangles, volumes (dim 3, entity tags
// 1..V) for the tets. A node belongs to the first entity, surfaces first,
// whose elements use it (unused nodes go to the first volume).
struct Layout {
  std::vector<int> line_phys, surface_phys, volume_phys;
  std::vector<int> line_entity;                     // 0-based curve entity per line
  std::vector<int> triangle_entity, tet_entity;     // 0-based entity index per element
  std::vector<std::vector<int>> surface_nodes, volume_nodes;
  Eigen::Vector3d lo, hi;
};

Layout layout(const mesh::TetMesh& m) {
  Layout l;
  l.line_phys = distinct(m.line_tags, m.num_lines());
  for (int e = 0; e < m.num_lines(); ++e) l.line_entity.push_back(index_of(l.line_phys, tag_or_zero(m.line_tags, e)));
  l.surface_phys = distinct(m.boundary_tags, m.num_boundary());
  l.volume_phys = distinct(m.tet_tags, m.num_tets());
  if (l.volume_phys.empty()) l.volume_phys.push_back(0);
  l.surface_nodes.resize(l.surface_phys.size());
  l.volume_nodes.resize(l.volume_phys.size());
  std::vector<int> owner(m.nodes.size(), -1); // entity: s for surfaces, S + v for volumes
  const int S = static_cast<int>(l.surface_phys.size());
  for (int b = 0; b < m.num_boundary(); ++b) {
    l.triangle_entity.push_back(index_of(l.surface_phys, tag_or_zero(m.boundary_tags, b)));
    for (int i = 0; i < m.triangle_nodes(); ++i) {
      int& o = owner[m.boundary_triangle(b)[i]];
      if (o < 0) o = l.triangle_entity.back();
    }
  }
  for (int t = 0; t < m.num_tets(); ++t) {
    l.tet_entity.push_back(index_of(l.volume_phys, tag_or_zero(m.tet_tags, t)));
    for (int i = 0; i < m.tet_nodes(); ++i) {
      int& o = owner[m.tet(t)[i]];
      if (o < 0) o = S + l.tet_entity.back();
    }
  }
  for (int i = 0; i < static_cast<int>(m.nodes.size()); ++i) {
    const int o = std::max(owner[i], S);
    (o < S ? l.surface_nodes[o] : l.volume_nodes[o - S]).push_back(i);
  }
  l.lo = l.hi = m.nodes.empty() ? Eigen::Vector3d::Zero() : m.nodes.front();
  for (const auto& p : m.nodes) {
    l.lo = l.lo.cwiseMin(p);
    l.hi = l.hi.cwiseMax(p);
  }
  return l;
}

void check_mesh(const mesh::TetMesh& m) {
  if (m.order < 1 || m.order > highorder::kMaxOrder)
    throw Error(ExitCode::internal, fmt::format("write_msh: order {} not supported (1..8)", m.order));
}

void write_physical_names(std::ostream& o, const mesh::TetMesh& m) {
  if (m.groups.empty()) return;
  o << "$PhysicalNames\n" << m.groups.size() << '\n';
  for (const auto& g : m.groups) o << g.dim << ' ' << g.tag << " \"" << g.name << "\"\n";
  o << "$EndPhysicalNames\n";
}

template <class T>
void put(std::ostream& o, T v) {
  o.write(reinterpret_cast<const char*>(&v), sizeof(T));
}

// Writes integers/doubles as text (space separated) or binary (given type).
class Out {
 public:
  Out(std::ostream& o, bool binary) : o_(o), binary_(binary) {}
  template <class T>
  Out& num(T v) {
    if (binary_)
      put<T>(o_, v);
    else
      o_ << (first_ ? "" : " ") << v;
    first_ = false;
    return *this;
  }
  Out& real(double v) {
    if (binary_)
      put<double>(o_, v);
    else
      o_ << (first_ ? "" : " ") << fmt::format("{:.17g}", v);
    first_ = false;
    return *this;
  }
  void endl() {
    if (!binary_) o_ << '\n';
    first_ = true;
  }
  void end_section() {
    if (binary_) o_ << '\n';
  }

 private:
  std::ostream& o_;
  bool binary_;
  bool first_ = true;
};

void write_v41(std::ostream& o, const mesh::TetMesh& m, bool binary) {
  const Layout l = layout(m);
  const int tri_type = highorder::gmsh_triangle_type(m.order), tet_type = highorder::gmsh_tet_type(m.order);
  const std::size_t num_nodes = m.nodes.size();
  const std::size_t num_elements = static_cast<std::size_t>(m.num_boundary()) + m.num_tets() + m.num_lines();
  const std::size_t C = l.line_phys.size(), S = l.surface_phys.size(), V = l.volume_phys.size();
  Out out(o, binary);

  o << "$MeshFormat\n4.1 " << (binary ? 1 : 0) << " 8\n";
  if (binary) {
    put<int>(o, 1);
    o << '\n';
  }
  o << "$EndMeshFormat\n";
  write_physical_names(o, m);

  o << "$Entities\n";
  out.num<std::uint64_t>(0).num<std::uint64_t>(C).num<std::uint64_t>(S).num<std::uint64_t>(V);
  out.endl();
  auto entity = [&](int tag, int phys, std::size_t bounding) {
    out.num<int>(tag);
    for (int k = 0; k < 3; ++k) out.real(l.lo[k]);
    for (int k = 0; k < 3; ++k) out.real(l.hi[k]);
    out.num<std::uint64_t>(phys != 0 ? 1 : 0);
    if (phys != 0) out.num<int>(phys);
    out.num<std::uint64_t>(bounding);
    for (std::size_t s = 0; s < bounding; ++s) out.num<int>(static_cast<int>(s + 1));
    out.endl();
  };
  // Curves (feature lines) have no bounding points; their nodes are owned
  // by the surfaces (every line is an edge of boundary triangles).
  for (std::size_t c = 0; c < C; ++c) entity(static_cast<int>(c + 1), l.line_phys[c], 0);
  for (std::size_t s = 0; s < S; ++s) entity(static_cast<int>(s + 1), l.surface_phys[s], 0);
  for (std::size_t v = 0; v < V; ++v) entity(static_cast<int>(v + 1), l.volume_phys[v], V == 1 ? S : 0);
  out.end_section();
  o << "$EndEntities\n";

  // Nodes: one block per entity holding nodes.
  struct Block {
    int dim, tag;
    const std::vector<int>* ids;
  };
  std::vector<Block> blocks;
  for (std::size_t s = 0; s < S; ++s)
    if (!l.surface_nodes[s].empty()) blocks.push_back({2, static_cast<int>(s + 1), &l.surface_nodes[s]});
  for (std::size_t v = 0; v < V; ++v)
    if (!l.volume_nodes[v].empty()) blocks.push_back({3, static_cast<int>(v + 1), &l.volume_nodes[v]});
  o << "$Nodes\n";
  out.num<std::uint64_t>(blocks.size()).num<std::uint64_t>(num_nodes).num<std::uint64_t>(num_nodes ? 1 : 0);
  out.num<std::uint64_t>(num_nodes);
  out.endl();
  for (const auto& b : blocks) {
    out.num<int>(b.dim).num<int>(b.tag).num<int>(0).num<std::uint64_t>(b.ids->size());
    out.endl();
    for (int id : *b.ids) {
      out.num<std::uint64_t>(static_cast<std::uint64_t>(id) + 1);
      out.endl();
    }
    for (int id : *b.ids) {
      for (int k = 0; k < 3; ++k) out.real(m.nodes[id][k]);
      out.endl();
    }
  }
  out.end_section();
  o << "$EndNodes\n";

  // Elements: one block per entity, boundary triangles first, then tets.
  o << "$Elements\n";
  std::vector<std::vector<int>> tri_of(S), tet_of(V), line_of(C);
  for (int e = 0; e < m.num_lines(); ++e) line_of[l.line_entity[e]].push_back(e);
  for (int b = 0; b < m.num_boundary(); ++b) tri_of[l.triangle_entity[b]].push_back(b);
  for (int t = 0; t < m.num_tets(); ++t) tet_of[l.tet_entity[t]].push_back(t);
  std::size_t num_blocks = 0;
  for (const auto& x : tri_of) num_blocks += !x.empty();
  for (const auto& x : tet_of) num_blocks += !x.empty();
  for (const auto& x : line_of) num_blocks += !x.empty();
  out.num<std::uint64_t>(num_blocks).num<std::uint64_t>(num_elements).num<std::uint64_t>(num_elements ? 1 : 0);
  out.num<std::uint64_t>(num_elements);
  out.endl();
  // Element tag = position in the mesh (triangles first, then tets, then
  // lines): readers restore the order from it across blocks.
  auto element_block = [&](int dim, int entity_tag, int type, const std::vector<int>& ids, int per, auto nodes_of) {
    if (ids.empty()) return;
    const std::uint64_t first_tag = dim == 2   ? 1
                                    : dim == 3 ? static_cast<std::uint64_t>(m.num_boundary()) + 1
                                               : static_cast<std::uint64_t>(m.num_boundary()) + m.num_tets() + 1;
    out.num<int>(dim).num<int>(entity_tag).num<int>(type).num<std::uint64_t>(ids.size());
    out.endl();
    for (int e : ids) {
      out.num<std::uint64_t>(first_tag + e);
      for (int i = 0; i < per; ++i) out.num<std::uint64_t>(static_cast<std::uint64_t>(nodes_of(e)[i]) + 1);
      out.endl();
    }
  };
  for (std::size_t s = 0; s < S; ++s)
    element_block(2, static_cast<int>(s + 1), tri_type, tri_of[s], m.triangle_nodes(),
                  [&](int b) { return m.boundary_triangle(b); });
  for (std::size_t v = 0; v < V; ++v)
    element_block(3, static_cast<int>(v + 1), tet_type, tet_of[v], m.tet_nodes(), [&](int t) { return m.tet(t); });
  for (std::size_t c = 0; c < C; ++c)
    element_block(1, static_cast<int>(c + 1), gmsh_line_type(m.order), line_of[c], m.line_nodes(),
                  [&](int e) { return m.line(e); });
  out.end_section();
  o << "$EndElements\n";
}

void write_v22(std::ostream& o, const mesh::TetMesh& m) {
  const int tri_type = highorder::gmsh_triangle_type(m.order), tet_type = highorder::gmsh_tet_type(m.order);
  o << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
  write_physical_names(o, m);
  o << "$Nodes\n" << m.nodes.size() << '\n';
  for (std::size_t i = 0; i < m.nodes.size(); ++i) {
    const auto& p = m.nodes[i];
    o << fmt::format("{} {:.17g} {:.17g} {:.17g}\n", i + 1, p.x(), p.y(), p.z());
  }
  o << "$EndNodes\n$Elements\n" << m.num_boundary() + m.num_tets() + m.num_lines() << '\n';
  int tag = 1;
  // Tags: physical group, then elementary entity (surface 1 / volume 1).
  for (int b = 0; b < m.num_boundary(); ++b) {
    o << tag++ << ' ' << tri_type << " 2 " << tag_or_zero(m.boundary_tags, b) << " 1";
    for (int i = 0; i < m.triangle_nodes(); ++i) o << ' ' << m.boundary_triangle(b)[i] + 1;
    o << '\n';
  }
  for (int t = 0; t < m.num_tets(); ++t) {
    o << tag++ << ' ' << tet_type << " 2 " << tag_or_zero(m.tet_tags, t) << " 1";
    for (int i = 0; i < m.tet_nodes(); ++i) o << ' ' << m.tet(t)[i] + 1;
    o << '\n';
  }
  for (int e = 0; e < m.num_lines(); ++e) {
    o << tag++ << ' ' << gmsh_line_type(m.order) << " 2 " << tag_or_zero(m.line_tags, e) << " 1";
    for (int i = 0; i < m.line_nodes(); ++i) o << ' ' << m.line(e)[i] + 1;
    o << '\n';
  }
  o << "$EndElements\n";
}

} // namespace

void write_msh(const std::string& path, const mesh::TetMesh& mesh, MshFormat format) {
  check_mesh(mesh);
  AtomicFile file(path, format == MshFormat::v41_binary);
  switch (format) {
    case MshFormat::v41_ascii: write_v41(file.stream(), mesh, false); break;
    case MshFormat::v41_binary: write_v41(file.stream(), mesh, true); break;
    case MshFormat::v22_ascii: write_v22(file.stream(), mesh); break;
  }
  file.commit();
}

} // namespace curvetet::io
