#pragma once
// Cached per-tet frames (highorder::AmipsFrames) for the curved optimizer,
// within a memory budget: a slot per cached tet; when a move needs more free
// slots than remain, every slot is released and refilled on demand. A mesh
// that fits is thus computed once, and a larger one costs recomputation, not
// memory.
#include <Eigen/Core>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace curvetet::volume {

class FrameCache {
 public:
  FrameCache(int num_tets, int points_per_tet, std::size_t budget_bytes)
      : points_(points_per_tet), slot_of_(num_tets, -1) {
    const std::size_t per_tet = sizeof(Eigen::Matrix3d) * static_cast<std::size_t>(points_per_tet);
    grow(static_cast<int>(std::min<std::size_t>(budget_bytes / per_tet, num_tets)));
  }

  // Guarantees that the next n lookups find a slot without a release, so
  // their pointers stay valid together (the capacity grows to n if smaller).
  void reserve(int n) {
    if (used_ + n <= capacity_) return;
    for (int s = 0; s < used_; ++s) slot_of_[tet_of_slot_[s]] = -1;
    used_ = 0;
    if (n > capacity_) grow(n);
  }

  bool cached(int t) const { return slot_of_[t] >= 0; }

  // Tet t's slot, assigned if it had none (then its content is stale: the
  // caller computes it). Requires a prior reserve() covering this call.
  Eigen::Matrix3d* slot(int t) {
    if (slot_of_[t] < 0) {
      slot_of_[t] = used_;
      tet_of_slot_[used_++] = t;
    }
    return cached_frames(t);
  }

  // Frames of a cached tet (no bookkeeping: safe from several threads).
  Eigen::Matrix3d* cached_frames(int t) { return &storage_[static_cast<std::size_t>(slot_of_[t]) * points_]; }

  int capacity() const { return capacity_; }

 private:
  void grow(int capacity) {
    capacity_ = capacity;
    storage_.resize(static_cast<std::size_t>(capacity_) * points_);
    tet_of_slot_.resize(capacity_, -1);
  }

  int points_, capacity_ = 0, used_ = 0;
  std::vector<int> slot_of_, tet_of_slot_;
  std::vector<Eigen::Matrix3d> storage_;
};

} // namespace curvetet::volume
