#pragma once
// A uniform hash grid of the shell's cap triangles (bottom and top faces) for
// finding the caps a new cap may intersect (paper App. B: dynamic hash grid).
// Cap id: 2 * prism + (0 bottom, 1 top). Only the commit step writes to it;
// queries are read-only and thread-safe between writes.
#include "curvetet/geometry/box_pairs.hpp"

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace curvetet::shell {

class CapGrid {
 public:
  explicit CapGrid(double cell = 1.0) : cell_(cell) {}
  double cell() const { return cell_; }
  void insert(int cap, const geometry::Box3& box);
  void erase(int cap, const geometry::Box3& box); // box must be the inserted one
  // Caps whose cells overlap `box` (sorted, unique; a superset of the caps
  // whose boxes overlap it).
  std::vector<int> query(const geometry::Box3& box) const;
  void clear() { cells_.clear(); }

 private:
  template <class Fn> void for_cells(const geometry::Box3& box, Fn&& fn) const;
  double cell_;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
};

} // namespace curvetet::shell
