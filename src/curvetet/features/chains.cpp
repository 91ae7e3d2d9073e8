#include "curvetet/features/chains.hpp"

#include <algorithm>
#include <map>

namespace curvetet::features {

FeatureGraph group_features(int num_vertices, const std::vector<std::array<int, 2>>& edges,
                            const std::vector<int>& user_corners) {
  // Sorted adjacency of the feature graph.
  std::vector<std::vector<int>> adj(num_vertices);
  for (const auto& e : edges) {
    adj[e[0]].push_back(e[1]);
    adj[e[1]].push_back(e[0]);
  }
  for (auto& a : adj) std::sort(a.begin(), a.end());

  FeatureGraph g;
  std::vector<char> is_corner(num_vertices, 0);
  for (int c : user_corners) is_corner[c] = 1;
  for (int v = 0; v < num_vertices; ++v)
    if (!adj[v].empty() && adj[v].size() != 2) is_corner[v] = 1;
  for (int v = 0; v < num_vertices; ++v)
    if (is_corner[v]) g.corners.push_back(v);

  std::map<std::array<int, 2>, char> used;
  auto key = [](int a, int b) { return std::array<int, 2>{std::min(a, b), std::max(a, b)}; };
  // Walks from `from` through `next` until a corner or a used edge.
  auto walk = [&](int from, int next) {
    FeatureChain c;
    c.vertices = {from};
    int prev = from, cur = next;
    used[key(prev, cur)] = 1;
    while (true) {
      if (cur == c.vertices.front() && !is_corner[cur]) { // back at the start of a loop
        c.closed = true;
        break;
      }
      c.vertices.push_back(cur);
      if (is_corner[cur]) break;
      // Not a corner: exactly two feature edges, continue on the other one.
      int nxt = adj[cur][0] == prev ? adj[cur][1] : adj[cur][0];
      if (used[key(cur, nxt)]) break;
      used[key(cur, nxt)] = 1;
      prev = cur;
      cur = nxt;
    }
    return c;
  };

  for (int c : g.corners)
    for (int n : adj[c])
      if (!used[key(c, n)]) g.chains.push_back(walk(c, n));
  for (int v = 0; v < num_vertices; ++v) // what is left are loops without corners
    for (int n : adj[v])
      if (!used[key(v, n)]) g.chains.push_back(walk(v, n));
  return g;
}

} // namespace curvetet::features
