#pragma once
// Grouping feature edges into chains and loops (paper §5, Fig. 14).
//
// A corner is a vertex given as a corner by the user, or where the number of
// feature edges meeting is not 2 (1: a chain ends; 3 or more: chains meet).
// A chain is a maximal path of feature edges whose interior vertices are not
// corners; it runs from a corner to a corner (possibly the same one). A loop
// is a closed cycle of feature edges with no corner on it. Every feature edge
// belongs to exactly one chain or loop.
#include "curvetet/features/feature_input.hpp"

#include <array>
#include <vector>

namespace curvetet::features {

struct FeatureChain {
  // Ordered vertices. For a chain: corner, interior..., corner (size >= 2).
  // For a loop: each vertex once, the closing edge is back()->front().
  std::vector<int> vertices;
  bool closed = false; // a loop
  int num_edges() const { return static_cast<int>(vertices.size()) - (closed ? 0 : 1); }
};

struct FeatureGraph {
  std::vector<int> corners; // sorted
  std::vector<FeatureChain> chains; // chains and loops, deterministic order
};

// Deterministic: chains are started from corners in increasing id order and
// each corner's edges in increasing neighbour order; loops from their
// smallest vertex, heading to its smaller neighbour.
// edges: [a, b] pairs with a < b, sorted and unique (validate_and_normalize).
FeatureGraph group_features(int num_vertices, const std::vector<std::array<int, 2>>& edges,
                            const std::vector<int>& user_corners);

} // namespace curvetet::features
