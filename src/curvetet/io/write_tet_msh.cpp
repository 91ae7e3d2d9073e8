#include "curvetet/io/write_tet_msh.hpp"

#include "curvetet/io/write_surface.hpp"

#include <fmt/format.h>
#include <map>

namespace curvetet::io {

void write_tet_msh(const std::string& path, const mesh::TetMesh& m) {
  std::map<int, std::vector<int>> by_tag; // tag -> tets
  for (int t = 0; t < m.num_tets(); ++t) by_tag[m.tags.empty() ? 1 : std::max(1, m.tags[t])].push_back(t);
  if (by_tag.empty()) by_tag[1];
  AtomicFile file(path);
  auto& out = file.stream();
  out << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  out << "$PhysicalNames\n" << by_tag.size() << "\n";
  for (const auto& [tag, tets] : by_tag) out << fmt::format("3 {} \"region{}\"\n", tag, tag);
  out << "$EndPhysicalNames\n";
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
  if (!m.vertices.empty()) lo = hi = m.vertices[0];
  for (const auto& p : m.vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  out << "$Entities\n0 0 0 " << by_tag.size() << "\n";
  for (const auto& [tag, tets] : by_tag)
    out << fmt::format("{} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} 1 {} 0\n", tag, lo.x(), lo.y(), lo.z(),
                       hi.x(), hi.y(), hi.z(), tag);
  out << "$EndEntities\n";
  // All nodes in the first volume entity.
  const int first = by_tag.begin()->first;
  const auto n = m.vertices.size();
  out << "$Nodes\n1 " << n << " 1 " << n << "\n3 " << first << " 0 " << n << "\n";
  for (std::size_t i = 1; i <= n; ++i) out << i << "\n";
  for (const auto& p : m.vertices) out << fmt::format("{:.17g} {:.17g} {:.17g}\n", p.x(), p.y(), p.z());
  out << "$EndNodes\n";
  out << "$Elements\n" << by_tag.size() << " " << m.tets.size() << " 1 " << m.tets.size() << "\n";
  std::size_t id = 1;
  for (const auto& [tag, tets] : by_tag) {
    out << "3 " << tag << " 4 " << tets.size() << "\n";
    for (int t : tets) {
      const auto& q = m.tets[t];
      out << fmt::format("{} {} {} {} {}\n", id++, q[0] + 1, q[1] + 1, q[2] + 1, q[3] + 1);
    }
  }
  out << "$EndElements\n";
  file.commit();
}

} // namespace curvetet::io
