// The cap spatial hash finds exactly the pairs the global check finds.
#include "tiny_meshes.hpp"

#include "curvetet/shell/build.hpp"
#include "curvetet/shell/invariants.hpp"

#include <gtest/gtest.h>

#include <numeric>
#include <random>

using namespace curvetet;
using namespace curvetet::shell;

TEST(CapIndex, AgreesWithTheGlobalCheckAfterRandomMoves) {
  auto b = build_shell(test::sphere(2));
  Shell& s = b.shell;
  CapIndex index(s);
  std::vector<int> all(s.num_prisms());
  std::iota(all.begin(), all.end(), 0);
  EXPECT_TRUE(index.intersections(s, all).empty());
  // Push random top vertices inward through the shell: caps cross.
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> V(0, s.num_vertices() - 1);
  std::vector<int> moved;
  for (int k = 0; k < 20; ++k) {
    const int v = V(rng);
    s.top[v] = s.middle[v] * 0.9;
    moved.push_back(v);
  }
  std::vector<int> touched;
  for (int f = 0; f < s.num_prisms(); ++f)
    for (int v : s.faces[f])
      if (std::find(moved.begin(), moved.end(), v) != moved.end()) touched.push_back(f);
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  index.update(s, touched);
  const auto global = cap_intersections(s);
  ASSERT_FALSE(global.empty());
  EXPECT_EQ(index.intersections(s, all), global);
  // Local queries: exactly the global pairs with a cap of the queried prisms.
  const int F = s.num_prisms();
  std::vector<std::pair<int, int>> expected;
  for (auto p : global)
    if (std::find(touched.begin(), touched.end(), p.first % F) != touched.end() ||
        std::find(touched.begin(), touched.end(), p.second % F) != touched.end())
      expected.push_back(p);
  EXPECT_EQ(index.intersections(s, touched), expected);
  EXPECT_EQ(cap_intersections(s, touched), expected);
  // A huge cap (spanning many cells) is still found.
  s.top[0] = Vec3(50, 0, 0);
  std::vector<int> around;
  for (int f = 0; f < F; ++f)
    if (s.faces[f][0] == 0 || s.faces[f][1] == 0 || s.faces[f][2] == 0) around.push_back(f);
  index.update(s, around);
  EXPECT_EQ(index.intersections(s, all), cap_intersections(s));
}
