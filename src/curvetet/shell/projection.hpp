#pragma once
// The shell projection Π and its inverse (DESIGN.md §3.3; Jiang et al. 2020).
//
// Each slab of prism f is cut into 3 tets by canonical_split(faces[f]) (the
// cut depends only on global vertex ids, so neighbouring prisms agree on
// shared quads). A tet holds exactly one pillar and carries its direction as
// a constant field. Equivalently: each tet is the affine image of the same
// tet of the reference slab (u, v, w) (prism_tets.hpp), and the field is the
// image of the vertical direction; so the fiber of a middle point (u, v) is
// the image of the vertical line over (u, v), and
//   Π(p) = (u, v) of the reference point of p in the tet that contains it,
//   Π⁻¹(f, u, v) = the point where that fiber meets an input face tracked by f.
// Both slabs give the same (u, v) on their shared middle triangle. Tets whose
// pillar is pinched have no volume and are skipped.
//
// Numerics: point location and fiber/face intersection are done in double
// with a small barycentric tolerance; they give answers on a valid shell
// (whose validity is decided exactly elsewhere).
#include "curvetet/shell/shell.hpp"

#include <optional>
#include <vector>

namespace curvetet::shell {

class Projector {
 public:
  explicit Projector(const Shell& s);

  // Π restricted to prism f: the (u, v) of the fiber through p, or nullopt
  // when p is outside the prism (by more than `tol` in barycentric terms).
  std::optional<MapPoint> project_in_prism(int prism, const Vec3& p, double tol = 1e-9) const;

  // Π of a point p of input face `input_face`: looks in the prisms tracking
  // that face (the one containing p most deeply wins). Throws
  // Error(ExitCode::internal) if none contains p.
  MapPoint project(const Vec3& p, int input_face) const;

  // Π⁻¹: where the fiber of m meets an input face tracked by m.prism; nullopt
  // if it meets none. `input_face` (optional) receives that face's id.
  std::optional<Vec3> unproject(const MapPoint& m, int* input_face = nullptr) const;

  // The point of the (linear) middle surface at m.
  Vec3 middle_point(const MapPoint& m) const;

  // Recomputes points[i].image for every tracked point (after a change of
  // the prisms tracking its input face). Returns how many failed (image
  // left unchanged): 0 on a valid shell.
  int remap_points(Shell& s) const;

 private:
  const Shell& s_;
  std::vector<std::vector<int>> trackers_; // input face -> prisms
};

} // namespace curvetet::shell
