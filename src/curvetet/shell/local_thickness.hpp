#pragma once
// Local thickness of the solid at the shell's vertices, for the coarsening's
// sizing rule (star_invariants.hpp, Thickness): a middle triangle much longer
// than the solid is thick under it leaves only flat tets to fill that part
// (a 5 x 1 face of a box 1 thick: no apex inside gives a tet of AMIPS below
// 9.8; a 2.5 x 1 face: 4.8).
//
// thickness[v] = distance from middle[v] along the pillar's inward direction
// (bottom - top) to the first input triangle hit beyond `skip` (the input's
// own faces around the vertex lie within epsilon of the middle surface);
// +inf for singular vertices and rays that leave the solid unhit. A
// heuristic in double precision: it ranks coarsenings, it guarantees nothing.
#include "curvetet/shell/shell.hpp"

#include <memory>
#include <vector>

namespace curvetet::shell {

class ThicknessProbe {
 public:
  explicit ThicknessProbe(const mesh::SurfaceMesh& input);
  ~ThicknessProbe();
  ThicknessProbe(const ThicknessProbe&) = delete;
  ThicknessProbe& operator=(const ThicknessProbe&) = delete;

  // Distance from p along unit direction d to the first input triangle hit
  // farther than skip, or +inf.
  double depth(const Vec3& p, const Vec3& d, double skip) const;
  // thickness[v] for every shell vertex (in parallel).
  std::vector<double> at_vertices(const Shell& s, double skip) const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

} // namespace curvetet::shell
