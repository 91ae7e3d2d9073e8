#pragma once
// Whether each surface component bounds a solid with the right orientation:
// a component nested inside an even number of others (an outer shell) must
// face outward, one inside an odd number (a cavity wall) inward.
// Precondition: closed, manifold, consistently oriented, no self-intersection
// (the nesting of components is only defined then). Exact predicates (CGAL
// volume_connected_components with Epick).
#include "curvetet/mesh/surface_mesh.hpp"

#include <vector>

namespace curvetet::check {

struct ComponentOrientation {
  int first_face;      // smallest face id of the component
  int nesting_level;   // number of components enclosing it
  bool outward;        // its normals point away from the volume it bounds
  bool correct() const { return outward == (nesting_level % 2 == 0); }
};

// One entry per edge-connected component, ordered by first_face.
std::vector<ComponentOrientation> solid_orientation(const mesh::SurfaceMesh& m);

} // namespace curvetet::check
