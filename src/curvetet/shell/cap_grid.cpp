#include "curvetet/shell/cap_grid.hpp"

#include <algorithm>
#include <cmath>

namespace curvetet::shell {

namespace {
std::uint64_t key(std::int64_t i, std::int64_t j, std::int64_t k) {
  // 21 bits per axis (wraps far away: only costs extra candidates).
  const std::uint64_t m = (1u << 21) - 1;
  return (std::uint64_t(i) & m) | ((std::uint64_t(j) & m) << 21) | ((std::uint64_t(k) & m) << 42);
}
} // namespace

template <class Fn>
void CapGrid::for_cells(const geometry::Box3& box, Fn&& fn) const {
  std::int64_t lo[3], hi[3];
  for (int d = 0; d < 3; ++d) {
    lo[d] = static_cast<std::int64_t>(std::floor(box.min[d] / cell_));
    hi[d] = static_cast<std::int64_t>(std::floor(box.max[d] / cell_));
  }
  for (auto i = lo[0]; i <= hi[0]; ++i)
    for (auto j = lo[1]; j <= hi[1]; ++j)
      for (auto k = lo[2]; k <= hi[2]; ++k) fn(key(i, j, k));
}

void CapGrid::insert(int cap, const geometry::Box3& box) {
  for_cells(box, [&](std::uint64_t k) { const_cast<CapGrid*>(this)->cells_[k].push_back(cap); });
}

void CapGrid::erase(int cap, const geometry::Box3& box) {
  for_cells(box, [&](std::uint64_t k) {
    auto it = const_cast<CapGrid*>(this)->cells_.find(k);
    if (it == cells_.end()) return;
    auto& v = it->second;
    v.erase(std::remove(v.begin(), v.end(), cap), v.end());
  });
}

std::vector<int> CapGrid::query(const geometry::Box3& box) const {
  std::vector<int> out;
  for_cells(box, [&](std::uint64_t k) {
    auto it = cells_.find(k);
    if (it != cells_.end()) out.insert(out.end(), it->second.begin(), it->second.end());
  });
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

} // namespace curvetet::shell
