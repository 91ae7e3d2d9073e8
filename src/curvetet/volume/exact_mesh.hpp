#pragma once
// INTERNAL to src/curvetet/volume/*.cpp (never include it elsewhere: it
// brings GMP in). Rational points and the exact tet mesh that steps 2-4 of
// the volume stage build before rounding (paper §4.3).
#include "curvetet/mesh/surface_mesh.hpp"

#include <gmpxx.h>

#include <array>
#include <vector>

namespace curvetet::volume::exact {

using mesh::Vec3;

struct QPoint {
  mpq_class c[3];
};

QPoint to_q(const Vec3& p);
// The double nearest to each coordinate.
Vec3 nearest_double(const QPoint& p);
// Exactly representable as doubles?
bool is_double(const QPoint& p);
// orient3d convention of geometry/predicates.hpp, exact.
int orient3d(const QPoint& a, const QPoint& b, const QPoint& c, const QPoint& d);

// Vertices hold an exact position q and a double d; when exact[v] is true, d
// is q exactly and the fast double predicates apply; otherwise d is q rounded
// toward zero (within 2u|q| per coordinate), used by the floating filters.
struct Vertices {
  std::vector<QPoint> q;
  std::vector<Vec3> d;
  std::vector<char> exact;

  int size() const { return static_cast<int>(q.size()); }
  int add(const QPoint& p);
  int add(const Vec3& p);
  // Moves v to the double position p (q follows).
  void set(int v, const Vec3& p);
  void set(int v, const QPoint& p);
  int orient(int a, int b, int c, int d) const;
  // Orientation with vertex v placed at p (a double point).
  int orient_at(const std::array<int, 4>& t, int v, const Vec3& p) const;
};

// Tets are positive. Vertices [0, num_frozen) are the input surface; they
// never move and are never removed; frozen[v] marks them plus the box.
//
// on_surface: Steiner vertices the insertion put on the input surface itself.
// That happens only where the offset coincides with the surface: on an edge
// whose two ends are pinched (singular), or in a face whose three corners
// are. Each comes with the vertices it may be collapsed onto without moving
// the boundary (the other vertices on the same segment, or in the same flat
// face); the optimizer must remove them all.
struct SurfaceSteiner {
  int vertex;
  std::vector<int> targets;
};
struct ExactTetMesh {
  Vertices v;
  std::vector<std::array<int, 4>> tets;
  std::vector<int> tags;
  std::vector<char> frozen;
  std::vector<SurfaceSteiner> on_surface;
};

} // namespace curvetet::volume::exact
