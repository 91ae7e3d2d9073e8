#pragma once
// One prism as plain data (its 9 corner positions and 3 global vertex ids),
// and the per-prism geometry the coarsening checks need. Works the same for
// a prism of the shell and for a candidate prism an operation proposes, so
// the operations never copy the shell (STYLE.md 1).
//
// Conventions (shell.hpp, prism_tets.hpp): corners k = 0,1,2 of the face are
// counter-clockwise seen from the top; slab corner c < 3 is the lower corner
// k = c, c >= 3 the upper corner of k = c - 3. A pillar is zero exactly when
// its ends are bitwise equal; tets holding a zero pillar are skipped.
// Decisions (positivity, meets, section) are exact (geometry/predicates.hpp,
// shell/exact_dot.hpp); projection and parametric areas are double.
#include "curvetet/shell/invariants.hpp"
#include "curvetet/shell/shell.hpp"

#include <Eigen/LU>

#include <array>
#include <optional>
#include <span>

namespace curvetet::shell {

struct PrismGeom {
  Tri ids{};                         // global vertex ids (decide the canonical split)
  std::array<Vec3, 3> bottom, middle, top;

  const Vec3& lower(Slab s, int k) const { return s == Slab::bottom ? bottom[k] : middle[k]; }
  const Vec3& upper(Slab s, int k) const { return s == Slab::bottom ? middle[k] : top[k]; }
  const Vec3& corner(Slab s, int c) const { return c < 3 ? lower(s, c) : upper(s, c - 3); }
  bool zero_pillar(Slab s, int k) const { return lower(s, k) == upper(s, k); }
};

PrismGeom prism_geom(const Shell& s, int prism);

// Invariant 1 on one prism: all 12 tets of both slabs positive (zero pillars
// skipped). Same rule as shell::prism_positive.
bool positive(const PrismGeom& g);

// Exact: p lies in the closed prism (the union of its canonical tets over
// non-zero pillars; they are positive by invariant 1).
bool prism_contains(const PrismGeom& g, const Vec3& p);

// Exact: the closed triangle (a, b, c) meets the closed prism (union of the
// canonical tets of both slabs).
bool triangle_meets_prism(const PrismGeom& g, const Vec3& a, const Vec3& b, const Vec3& c);

// Exact section condition of input triangle (a, b, c) in this prism (same
// rule as shell::prism_section_valid without its containment part): for each
// non-zero pillar whose direction has a non-positive dot product with the
// triangle's normal, the triangle meets none of the tets holding that pillar
// (contact confined to their lateral middle corners or edge excepted:
// section_allowed_corners).
bool section_condition(const PrismGeom& g, const Vec3& a, const Vec3& b, const Vec3& c);

// Π restricted to the prism: (u, v) of the fiber through p, and its depth
// (min barycentric of p in the best tet; >= -tol means inside). nullopt when
// p is outside by more than tol. A p bitwise equal to middle[k] gets corner
// k exactly ((0,0), (1,0), (0,1)), depth 0.
std::optional<std::array<double, 2>> project_in(const PrismGeom& g, const Vec3& p, double tol, double* depth = nullptr);

// project_in for many points of one prism: its tets' LU factors are computed
// once (the fits and Π of a star project hundreds of points per prism). Same
// arithmetic as project_in, so the same results bit for bit.
class PrismProjection {
 public:
  explicit PrismProjection(const PrismGeom& g);
  std::optional<std::array<double, 2>> operator()(const Vec3& p, double tol, double* depth = nullptr) const;

 private:
  struct Tet {
    Vec3 origin;                             // corner 0 in space
    std::array<Vec3, 4> reference;           // corners in the prism's (u, v, w)
    Eigen::PartialPivLU<Eigen::Matrix3d> lu; // of the edge vectors from corner 0
  };
  std::array<Vec3, 3> middle_;
  std::array<Tet, 6> tets_;
  int count_ = 0;
};

// Π⁻¹ restricted to the prism: where the fiber of (u, v) meets triangle
// (a, b, c), if it does (within a 1e-9 barycentric slack). `depth` receives
// the hit's min barycentric coordinate in (a, b, c) (the deepest hit wins).
// A fiber over a pinched pillar is a point: a hit when it lies on the plane.
std::optional<Vec3> fiber_hit(const PrismGeom& g, double u, double v, const Vec3& a, const Vec3& b, const Vec3& c,
                              double* depth = nullptr);

// Parametric image of triangle (a, b, c) under Π in this prism: the triangle
// is clipped to each canonical tet and the pieces' (u, v) shadows measured.
// area = sum of the signed piece areas, in units of the middle triangle
// (1 = the whole triangle); min_piece = smallest signed piece area (same
// units; < 0 means a piece maps with reversed orientation).
// Accuracy: the corners' barycentric coordinates in each tet are volume
// ratios with a small relative error (orient3d_value, exact fallback), so a
// nearly degenerate configuration (a corner 1e-19 off a tet face) costs no
// accuracy: the area errs by ~1e-14, not by the size of a mis-clipped
// sliver. A triangle lying exactly in a face shared by two tets (a flat
// region's middle triangle) counts once, for the tet on its positive side.
struct ImageArea {
  double area = 0, min_piece = 0;
};
ImageArea image_area(const PrismGeom& g, const Vec3& a, const Vec3& b, const Vec3& c);
// The same summed over input faces `faces` of `input` (area = sum, min_piece
// = min), each input vertex's barycentric coordinates computed once.
ImageArea image_area_sum(const PrismGeom& g, const mesh::SurfaceMesh& input, std::span<const int> faces);

// The same sum in exact rationals (barycentric coordinates as ratios of exact
// determinants, exact clipping and areas): the map is a bijection onto the
// middle triangle exactly when the pieces tile it, i.e. sum to exactly 1
// with no negative piece. `error` and `min_piece` are the doubles nearest
// |sum - 1| and the smallest piece, for reports.
struct ExactImageArea {
  bool tiles = false, positive = false;
  double error = 0, min_piece = 0;
};
ExactImageArea exact_image_area_sum(const PrismGeom& g, const mesh::SurfaceMesh& input, std::span<const int> faces);

} // namespace curvetet::shell
