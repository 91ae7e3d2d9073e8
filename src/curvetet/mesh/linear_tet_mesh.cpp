#include "curvetet/mesh/linear_tet_mesh.hpp"

#include <algorithm>
#include <stdexcept>

namespace curvetet::mesh {

TetMesh to_order1_mesh(const LinearTetMesh& m, const std::vector<std::string>& names) {
  TetMesh out;
  out.order = 1;
  out.nodes = m.vertices;
  std::vector<int> used;
  for (int t = 0; t < m.num_tets(); ++t) {
    out.tets.insert(out.tets.end(), m.tets[t].begin(), m.tets[t].end());
    const int tag = m.tags.empty() ? 1 : std::max(1, m.tags[t]);
    out.tet_tags.push_back(tag);
    if (std::find(used.begin(), used.end(), tag) == used.end()) used.push_back(tag);
  }
  std::sort(used.begin(), used.end());
  for (int tag : used)
    out.groups.push_back({3, tag, tag < static_cast<int>(names.size()) && !names[tag].empty()
                                      ? names[tag]
                                      : "region" + std::to_string(tag)});
  return out;
}

LinearTetMesh to_linear_mesh(const TetMesh& m) {
  if (m.order != 1) throw std::invalid_argument("to_linear_mesh: order-1 mesh expected");
  LinearTetMesh out;
  out.vertices = m.nodes;
  for (int t = 0; t < m.num_tets(); ++t) {
    out.tets.push_back({m.tet(t)[0], m.tet(t)[1], m.tet(t)[2], m.tet(t)[3]});
    out.tags.push_back(t < static_cast<int>(m.tet_tags.size()) ? m.tet_tags[t] : 0);
  }
  return out;
}

} // namespace curvetet::mesh
