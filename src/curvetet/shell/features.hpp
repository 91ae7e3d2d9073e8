#pragma once
// Feature chains and corners carried by the shell (paper §5, App. B).
//
// The input side is fixed: the chains of the input surface (input vertex
// ids, features::group_features) with their cumulative arc lengths. A
// *position* along chain k is a real number p: integer p is input vertex
// chains[k].vertices[p] (mod n for a loop of n edges), a fractional p is the
// point at that arc-length fraction of the input edge (isolation splits put
// shell vertices at p + 0.5).
//
// The shell side changes with every committed operation: each shell vertex
// is a corner, an interior vertex of one chain (with its position and its
// two chain neighbours), or neither; each coarse feature edge covers the
// input chain between two positions [start, start + length] and is a shell
// edge. The feature correspondence is arc-length: the input chain point at
// arc-length fraction t of that range maps to the point at parameter t of
// the coarse edge (from `first` to the other end). For a loop positions are
// taken mod n; start is in [0, n).
//
// Invariants kept by coarsening (feature_invariant.cpp): corners never move
// nor disappear; an interior chain vertex sits exactly (bitwise middle) on
// the input vertex at its position, or at its fractional isolation point;
// the coarse edges of a chain cover it contiguously, end to end; an open
// chain keeps >= 1 edge, a loop or a chain closed at one corner keeps >= 3.
#include "curvetet/features/chains.hpp"
#include "curvetet/mesh/edge_topology.hpp"

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace curvetet::shell {

struct CoarseFeatureEdge {
  int chain = -1;
  int first = -1;     // shell vertex at position `start`
  double start = 0;   // position along the chain of `first`
  double length = 0;  // in positions (number of input edges covered)
};

// Where straightening (straighten.hpp) put an input chain vertex: on coarse
// feature edge (a, b) at parameter t from a; a = -1: not on an edge's inside.
struct StraightOnEdge {
  int a = -1, b = -1;
  double t = 0;
};

struct ShellFeatures {
  // ---- input side (fixed) ----
  std::vector<features::FeatureChain> chains; // input vertex ids
  std::vector<std::vector<double>> arc;       // per chain: arc length at positions 0..num_edges
  std::vector<int> input_corners;             // sorted input vertex ids
  mesh::VertexFaces input_faces_around;       // input faces around each input vertex (straightening)
  // ---- shell side (per shell vertex; empty when there are no features) ----
  std::vector<int> corner_input;  // input vertex of a corner, -1 otherwise
  std::vector<int> chain;         // chain of an interior chain vertex, -1 otherwise
  std::vector<double> position;   // its position (loops: in [0, n))
  std::vector<int> prev, next;    // its chain neighbours (lower / higher position)
  std::unordered_map<std::uint64_t, CoarseFeatureEdge> edges; // key: edge_key(a, b)
  std::vector<int> chain_edges;   // current number of coarse edges per chain
  std::vector<StraightOnEdge> on_edge; // per input vertex (empty until a chain is straightened)

  bool empty() const { return chains.empty() && corner_input.empty(); }
  bool is_corner(int v) const { return v >= 0 && v < static_cast<int>(corner_input.size()) && corner_input[v] >= 0; }
  int chain_of(int v) const { return v >= 0 && v < static_cast<int>(chain.size()) ? chain[v] : -1; }
  const CoarseFeatureEdge* edge(int a, int b) const {
    auto it = edges.find(edge_key(a, b));
    return it == edges.end() ? nullptr : &it->second;
  }
  bool closed(int k) const; // a loop, or a chain starting and ending at one corner
  int num_positions(int k) const { return chains[k].num_edges(); }
  // Arc length at position p (fractional: linear on the input edge; loops
  // wrap, adding the loop length per turn).
  double arc_at(int k, double p) const;
  // Input vertex at integer position p (mod n for loops).
  int input_vertex(int k, long long p) const;
  // p in [0, n) for loops, unchanged for open chains.
  double wrap(int k, double p) const;

  static std::uint64_t edge_key(int a, int b) {
    const auto lo = static_cast<std::uint32_t>(a < b ? a : b), hi = static_cast<std::uint32_t>(a < b ? b : a);
    return (std::uint64_t(lo) << 32) | hi;
  }
};

} // namespace curvetet::shell
