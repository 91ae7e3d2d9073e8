#pragma once
// INTERNAL to volume/*.cpp. Small combinatorial helpers shared by the BSP
// insertion, the optimizer and the Delaunay fill: hash keys of unordered
// edges and triangles, a mixer, and the vertex cycle around an edge.
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace curvetet::volume {

inline std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
}

// Ids must be below 2^21 (kMaxFaceKeyId).
constexpr int kMaxFaceKeyId = 1 << 21;
inline std::uint64_t face_key(int a, int b, int c) {
  int s[3] = {a, b, c};
  std::sort(s, s + 3);
  return (static_cast<std::uint64_t>(s[0]) << 42) | (static_cast<std::uint64_t>(s[1]) << 21) |
         static_cast<std::uint64_t>(s[2]);
}

// A 64-bit mixer (splitmix64's finalizer): keys summed after it name a set
// whatever its order; also a pseudo-random number seeded by a key.
inline std::uint64_t mix64(std::uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ull;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// The links (x, y) of the tets around an edge (their two other vertices)
// chained into the cycle of the edge's ring; empty unless they close one
// simple cycle of at least 3 vertices (an edge on the boundary has an open
// fan).
inline std::vector<int> ring_cycle(const std::vector<std::array<int, 2>>& links) {
  if (links.size() < 3) return {};
  std::vector<int> c{links[0][0], links[0][1]};
  std::vector<char> used(links.size(), 0);
  used[0] = 1;
  while (c.size() < links.size()) {
    bool found = false;
    for (std::size_t i = 0; i < links.size() && !found; ++i)
      if (!used[i] && (links[i][0] == c.back() || links[i][1] == c.back())) {
        c.push_back(links[i][0] == c.back() ? links[i][1] : links[i][0]);
        used[i] = found = true;
      }
    if (!found) return {};
  }
  const auto& last = links[std::find(used.begin(), used.end(), 0) - used.begin()];
  const bool closes = (last[0] == c.back() && last[1] == c[0]) || (last[0] == c[0] && last[1] == c.back());
  std::vector<int> sorted = c;
  std::sort(sorted.begin(), sorted.end());
  if (!closes || std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return {};
  return c;
}

} // namespace curvetet::volume
