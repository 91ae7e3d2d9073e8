#include "curvetet/mesh/tet_mesh.hpp"

namespace curvetet::mesh {

void set_default_groups(TetMesh& m) {
  m.groups = {{2, kBoundaryTag, "boundary"}, {3, kDomainTag, "domain"}};
  m.tet_tags.assign(m.num_tets(), kDomainTag);
  m.boundary_tags.assign(m.num_boundary(), kBoundaryTag);
}

void add_exterior_groups(TetMesh& m) {
  m.groups.push_back({2, kBoxTag, "box"});
  m.groups.push_back({3, kExteriorTag, "exterior"});
}

} // namespace curvetet::mesh
