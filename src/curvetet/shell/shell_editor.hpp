#pragma once
// The mutable state of a shell being coarsened: vertex -> faces adjacency,
// dead/alive flags, the points mapped into each prism, vertex versions (for
// stale queue entries) and the cap grid. Read-only during the parallel check
// phase; only commit() and compact() write (sequentially).
//
// Dead faces/vertices keep their slots until compact(), which renumbers
// everything (the Shell is then plain again: no dead entries).
#include "curvetet/geometry/box_pairs.hpp"
#include "curvetet/shell/cap_grid.hpp"
#include "curvetet/shell/star.hpp"

#include <cstdint>
#include <vector>

namespace curvetet::shell {

class ShellEditor {
 public:
  explicit ShellEditor(Shell& s);

  const Shell& shell() const { return s_; }
  bool face_alive(int f) const { return face_alive_[f]; }
  bool vertex_alive(int v) const { return vertex_alive_[v]; }
  const std::vector<int>& faces_of(int v) const { return vf_[v]; }
  std::vector<int> neighbours(int v) const; // sorted
  const std::vector<int>& points_in(int prism) const { return prism_points_[prism]; }
  std::uint32_t version(int v) const { return version_[v]; }
  int batch_of(int f) const { return face_batch_[f]; } // -1: not created by a commit
  int alive_faces() const { return alive_faces_; }
  const CapGrid& grid() const { return grid_; }
  // true when an earlier commit of batch `batch` reshaped (straighten.hpp)
  // one of the input faces c reshapes: c was checked against the old face.
  bool reshapes_batch_face(const StarCandidate& c, int batch) const;

  PrismGeom geom(int f) const { return prism_geom(s_, f); }
  // Positions of vertex v as the candidate has them.
  const Vec3& bottom(const StarCandidate& c, int v) const;
  const Vec3& middle(const StarCandidate& c, int v) const;
  const Vec3& top(const StarCandidate& c, int v) const;
  PrismGeom candidate_geom(const StarCandidate& c, int k) const;
  // Cap boxes: cap = 2 * prism + (0 bottom, 1 top).
  geometry::Box3 cap_box(int cap) const;

  // Applies a checked candidate (its derived part filled). `batch` stamps the
  // new faces. Returns the ids of the new faces, in c.faces order.
  std::vector<int> commit(const StarCandidate& c, int batch);
  // Drops dead faces and vertices, renumbering; rebuilds the grid.
  void compact();

 private:
  void rebuild();
  Shell& s_;
  std::vector<std::vector<int>> vf_;
  std::vector<std::vector<int>> prism_points_;
  std::vector<char> face_alive_, vertex_alive_;
  std::vector<std::uint32_t> version_;
  std::vector<int> face_batch_;
  std::vector<int> reshaped_batch_; // per input face: batch of the last commit reshaping it (empty until one does)
  int alive_faces_ = 0;
  CapGrid grid_;
};

} // namespace curvetet::shell
