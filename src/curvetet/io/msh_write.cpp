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

struct Layout {
  // Nodes on the boundary go to the surface entity, the others to the volume.
  std::vector<int> surface_nodes, volume_nodes;
  Eigen::Vector3d lo, hi;
};

Layout layout(const mesh::TetMesh& m) {
  Layout l;
  std::vector<char> on_surface(m.nodes.size(), 0);
  for (int id : m.boundary) on_surface[id] = 1;
  for (int i = 0; i < static_cast<int>(m.nodes.size()); ++i) (on_surface[i] ? l.surface_nodes : l.volume_nodes).push_back(i);
  l.lo = l.hi = m.nodes.empty() ? Eigen::Vector3d::Zero() : m.nodes.front();
  for (const auto& p : m.nodes) {
    l.lo = l.lo.cwiseMin(p);
    l.hi = l.hi.cwiseMax(p);
  }
  return l;
}

int tag_or_zero(const std::vector<int>& tags, int i) { return i < static_cast<int>(tags.size()) ? tags[i] : 0; }

// Physical tags of the surface and volume entities: every distinct tag used.
std::vector<int> distinct(const std::vector<int>& tags) {
  std::vector<int> out;
  for (int t : tags)
    if (t != 0 && std::find(out.begin(), out.end(), t) == out.end()) out.push_back(t);
  return out;
}

void check_mesh(const mesh::TetMesh& m) {
  if (m.order < 1 || m.order > highorder::kMaxOrder)
    throw Error(ExitCode::internal, fmt::format("write_msh: order {} not supported (1..8)", m.order));
  if (distinct(m.tet_tags).size() > 1 || distinct(m.boundary_tags).size() > 1)
    throw Error(ExitCode::internal, "write_msh: one physical tag per element dimension is supported");
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

void write_v41(std::ostream& o, const mesh::TetMesh& m, bool binary) {
  const Layout l = layout(m);
  const auto surf_phys = distinct(m.boundary_tags), vol_phys = distinct(m.tet_tags);
  const int tri_type = highorder::gmsh_triangle_type(m.order), tet_type = highorder::gmsh_tet_type(m.order);
  const int nt = m.triangle_nodes(), nv = m.tet_nodes();
  const std::size_t num_nodes = m.nodes.size();
  const std::size_t num_elements = static_cast<std::size_t>(m.num_boundary()) + m.num_tets();
  const bool has_surface = m.num_boundary() > 0;

  o << "$MeshFormat\n4.1 " << (binary ? 1 : 0) << " 8\n";
  if (binary) {
    put<int>(o, 1);
    o << '\n';
  }
  o << "$EndMeshFormat\n";
  write_physical_names(o, m);

  o << "$Entities\n";
  if (!binary) {
    o << "0 0 " << (has_surface ? 1 : 0) << " 1\n";
    auto box = fmt::format("{:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g}", l.lo.x(), l.lo.y(), l.lo.z(), l.hi.x(),
                           l.hi.y(), l.hi.z());
    if (has_surface) {
      o << "1 " << box << ' ' << surf_phys.size();
      for (int t : surf_phys) o << ' ' << t;
      o << " 0\n";
    }
    o << "1 " << box << ' ' << vol_phys.size();
    for (int t : vol_phys) o << ' ' << t;
    o << ' ' << (has_surface ? "1 1" : "0") << '\n';
  } else {
    put<std::uint64_t>(o, 0);
    put<std::uint64_t>(o, 0);
    put<std::uint64_t>(o, has_surface ? 1 : 0);
    put<std::uint64_t>(o, 1);
    auto box = [&] {
      for (int k = 0; k < 3; ++k) put<double>(o, l.lo[k]);
      for (int k = 0; k < 3; ++k) put<double>(o, l.hi[k]);
    };
    if (has_surface) {
      put<int>(o, 1);
      box();
      put<std::uint64_t>(o, surf_phys.size());
      for (int t : surf_phys) put<int>(o, t);
      put<std::uint64_t>(o, 0);
    }
    put<int>(o, 1);
    box();
    put<std::uint64_t>(o, vol_phys.size());
    for (int t : vol_phys) put<int>(o, t);
    put<std::uint64_t>(o, has_surface ? 1 : 0);
    if (has_surface) put<int>(o, 1);
    o << '\n';
  }
  o << "$EndEntities\n";

  // Nodes: one block per entity holding nodes.
  struct Block {
    int dim;
    const std::vector<int>* ids;
  };
  std::vector<Block> blocks;
  if (!l.surface_nodes.empty()) blocks.push_back({2, &l.surface_nodes});
  if (!l.volume_nodes.empty()) blocks.push_back({3, &l.volume_nodes});
  o << "$Nodes\n";
  if (!binary) {
    o << blocks.size() << ' ' << num_nodes << ' ' << (num_nodes ? 1 : 0) << ' ' << num_nodes << '\n';
    for (const auto& b : blocks) {
      o << b.dim << " 1 0 " << b.ids->size() << '\n';
      for (int id : *b.ids) o << id + 1 << '\n';
      for (int id : *b.ids) {
        const auto& p = m.nodes[id];
        o << fmt::format("{:.17g} {:.17g} {:.17g}\n", p.x(), p.y(), p.z());
      }
    }
  } else {
    put<std::uint64_t>(o, blocks.size());
    put<std::uint64_t>(o, num_nodes);
    put<std::uint64_t>(o, num_nodes ? 1 : 0);
    put<std::uint64_t>(o, num_nodes);
    for (const auto& b : blocks) {
      put<int>(o, b.dim);
      put<int>(o, 1);
      put<int>(o, 0);
      put<std::uint64_t>(o, b.ids->size());
      for (int id : *b.ids) put<std::uint64_t>(o, static_cast<std::uint64_t>(id) + 1);
      for (int id : *b.ids)
        for (int k = 0; k < 3; ++k) put<double>(o, m.nodes[id][k]);
    }
    o << '\n';
  }
  o << "$EndNodes\n";

  o << "$Elements\n";
  const std::size_t num_blocks = (has_surface ? 1 : 0) + (m.num_tets() > 0 ? 1 : 0);
  std::uint64_t tag = 1;
  if (!binary) {
    o << num_blocks << ' ' << num_elements << ' ' << (num_elements ? 1 : 0) << ' ' << num_elements << '\n';
    if (has_surface) {
      o << "2 1 " << tri_type << ' ' << m.num_boundary() << '\n';
      for (int b = 0; b < m.num_boundary(); ++b) {
        o << tag++;
        for (int i = 0; i < nt; ++i) o << ' ' << m.boundary_triangle(b)[i] + 1;
        o << '\n';
      }
    }
    if (m.num_tets() > 0) {
      o << "3 1 " << tet_type << ' ' << m.num_tets() << '\n';
      for (int t = 0; t < m.num_tets(); ++t) {
        o << tag++;
        for (int i = 0; i < nv; ++i) o << ' ' << m.tet(t)[i] + 1;
        o << '\n';
      }
    }
  } else {
    put<std::uint64_t>(o, num_blocks);
    put<std::uint64_t>(o, num_elements);
    put<std::uint64_t>(o, num_elements ? 1 : 0);
    put<std::uint64_t>(o, num_elements);
    if (has_surface) {
      put<int>(o, 2);
      put<int>(o, 1);
      put<int>(o, tri_type);
      put<std::uint64_t>(o, m.num_boundary());
      for (int b = 0; b < m.num_boundary(); ++b) {
        put<std::uint64_t>(o, tag++);
        for (int i = 0; i < nt; ++i) put<std::uint64_t>(o, static_cast<std::uint64_t>(m.boundary_triangle(b)[i]) + 1);
      }
    }
    if (m.num_tets() > 0) {
      put<int>(o, 3);
      put<int>(o, 1);
      put<int>(o, tet_type);
      put<std::uint64_t>(o, m.num_tets());
      for (int t = 0; t < m.num_tets(); ++t) {
        put<std::uint64_t>(o, tag++);
        for (int i = 0; i < nv; ++i) put<std::uint64_t>(o, static_cast<std::uint64_t>(m.tet(t)[i]) + 1);
      }
    }
    o << '\n';
  }
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
  o << "$EndNodes\n$Elements\n" << m.num_boundary() + m.num_tets() << '\n';
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
