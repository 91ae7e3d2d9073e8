#include "curvetet/shell/cap_view.hpp"
#include "curvetet/shell/invariants.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace curvetet::shell {

namespace {

std::uint64_t cell_key(long long x, long long y, long long z) {
  // 21 bits per axis (cells are offset to be non-negative near the shell).
  const auto m = [](long long v) { return static_cast<std::uint64_t>(v) & 0x1FFFFF; };
  return m(x) | (m(y) << 21) | (m(z) << 42);
}

// A cap whose box spans more cells than this along an axis is "huge": kept
// out of the grid in a list that every query scans (and a huge query cap
// scans all caps), so candidate finding never misses a pair.
constexpr long long kMaxSpan = 16;

} // namespace

CapIndex::CapIndex(const Shell& s, double cell_size) {
  const CapView view{s, s.num_prisms(), s.num_vertices()};
  const int caps = 2 * view.F;
  std::vector<geometry::Box3> boxes(caps);
  tbb::parallel_for(0, caps, [&](int c) { boxes[c] = view.box(c); });
  double extent = 0;
  origin_ = Vec3::Constant(std::numeric_limits<double>::infinity());
  for (const auto& b : boxes) {
    extent += (b.max - b.min).maxCoeff();
    origin_ = origin_.cwiseMin(b.min);
  }
  cell_ = cell_size > 0 ? cell_size : extent / std::max(caps, 1);
  if (!(cell_ > 0)) cell_ = 1;
  // Margin so that caps growing a little below the origin keep small keys.
  origin_ -= Vec3::Constant(1024 * cell_);
  ranges_.resize(caps);
  boxes_ = boxes;
  for (int c = 0; c < caps; ++c) {
    ranges_[c] = cells_of(boxes[c].min, boxes[c].max);
    insert(c, ranges_[c]);
  }
}

CapIndex::CellRange CapIndex::cells_of(const Vec3& lo, const Vec3& hi) const {
  CellRange r;
  for (int i = 0; i < 3; ++i) {
    r.lo[i] = static_cast<long long>(std::floor((lo[i] - origin_[i]) / cell_));
    r.hi[i] = static_cast<long long>(std::floor((hi[i] - origin_[i]) / cell_));
    if (r.hi[i] - r.lo[i] > kMaxSpan) r.huge = true;
  }
  return r;
}

void CapIndex::insert(int cap, const CellRange& r) {
  if (r.huge) {
    huge_.insert(std::lower_bound(huge_.begin(), huge_.end(), cap), cap);
    return;
  }
  for (long long x = r.lo[0]; x <= r.hi[0]; ++x)
    for (long long y = r.lo[1]; y <= r.hi[1]; ++y)
      for (long long z = r.lo[2]; z <= r.hi[2]; ++z) grid_[cell_key(x, y, z)].push_back(cap);
}

void CapIndex::erase(int cap, const CellRange& r) {
  if (r.huge) {
    huge_.erase(std::lower_bound(huge_.begin(), huge_.end(), cap));
    return;
  }
  for (long long x = r.lo[0]; x <= r.hi[0]; ++x)
    for (long long y = r.lo[1]; y <= r.hi[1]; ++y)
      for (long long z = r.lo[2]; z <= r.hi[2]; ++z) {
        auto it = grid_.find(cell_key(x, y, z));
        if (it == grid_.end()) continue;
        auto& v = it->second;
        v.erase(std::remove(v.begin(), v.end(), cap), v.end());
        if (v.empty()) grid_.erase(it);
      }
}

void CapIndex::update(const Shell& s, std::span<const int> prisms) {
  const CapView view{s, s.num_prisms(), s.num_vertices()};
  for (int f : prisms)
    for (int cap : {f, f + view.F}) {
      const auto b = view.box(cap);
      boxes_[cap] = b;
      const auto r = cells_of(b.min, b.max);
      if (r.lo == ranges_[cap].lo && r.hi == ranges_[cap].hi && r.huge == ranges_[cap].huge) continue;
      erase(cap, ranges_[cap]);
      ranges_[cap] = r;
      insert(cap, r);
    }
}

std::vector<std::pair<int, int>> CapIndex::intersections(const Shell& s, std::span<const int> prisms) const {
  // Every batch size goes through the grid: its queries run in parallel,
  // where CGAL's box sweep is serial (the thickening rounds' whole-shell
  // checks took 2.2-3.4x longer with it; docs/performance.md).
  const CapView view{s, s.num_prisms(), s.num_vertices()};
  std::vector<int> mine;
  for (int f : prisms) {
    mine.push_back(f);
    mine.push_back(f + view.F);
  }
  std::sort(mine.begin(), mine.end());
  mine.erase(std::unique(mine.begin(), mine.end()), mine.end());
  // Each pair is emitted once: from its smaller cap when both are queried,
  // and (inside the grid) only from the first cell the two ranges share.
  auto wanted = [&](int a, int b) {
    return b != a && (a < b || !std::binary_search(mine.begin(), mine.end(), b)) &&
           geometry::boxes_overlap(boxes_[a], boxes_[b]);
  };
  std::vector<std::vector<std::pair<int, int>>> found(mine.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mine.size(), 32), [&](const auto& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const int a = mine[i];
      const auto& r = ranges_[a];
      auto& out = found[i];
      auto emit = [&](int b) { out.emplace_back(std::min(a, b), std::max(a, b)); };
      if (r.huge) {
        for (int b = 0; b < 2 * view.F; ++b)
          if (wanted(a, b)) emit(b);
        continue;
      }
      for (int b : huge_)
        if (wanted(a, b)) emit(b);
      for (long long x = r.lo[0]; x <= r.hi[0]; ++x)
        for (long long y = r.lo[1]; y <= r.hi[1]; ++y)
          for (long long z = r.lo[2]; z <= r.hi[2]; ++z) {
            auto it = grid_.find(cell_key(x, y, z));
            if (it == grid_.end()) continue;
            for (int b : it->second) {
              const auto& rb = ranges_[b];
              if (std::max(r.lo[0], rb.lo[0]) != x || std::max(r.lo[1], rb.lo[1]) != y ||
                  std::max(r.lo[2], rb.lo[2]) != z)
                continue;
              if (wanted(a, b)) emit(b);
            }
          }
    }
  });
  std::vector<std::pair<int, int>> candidates;
  for (auto& f : found) candidates.insert(candidates.end(), f.begin(), f.end());
  return decide_cap_pairs(view, std::move(candidates), poll);
}

} // namespace curvetet::shell
