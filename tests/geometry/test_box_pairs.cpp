#include "curvetet/geometry/box_pairs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace curvetet::geometry;

namespace {
bool overlap(const Box3& a, const Box3& b) {
  return (a.min.array() <= b.max.array()).all() && (b.min.array() <= a.max.array()).all();
}
std::vector<Box3> random_boxes(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1), s(0, 0.15);
  std::vector<Box3> boxes;
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d lo(u(rng), u(rng), u(rng));
    boxes.push_back({lo, lo + Eigen::Vector3d(s(rng), s(rng), s(rng))});
  }
  boxes.push_back(boxes[3]); // identical boxes overlap
  boxes.push_back({boxes[5].max, boxes[5].max + Eigen::Vector3d::Constant(0.1)}); // touching at a corner
  return boxes;
}
} // namespace

TEST(BoxPairs, SelfMatchesBruteForceEachPairOnce) {
  auto boxes = random_boxes(600, 1);
  std::vector<std::pair<int, int>> brute;
  for (int i = 0; i < (int)boxes.size(); ++i)
    for (int j = i + 1; j < (int)boxes.size(); ++j)
      if (overlap(boxes[i], boxes[j])) brute.emplace_back(i, j);
  auto fast = overlapping_pairs(boxes);
  std::sort(fast.begin(), fast.end());
  EXPECT_EQ(fast, brute);
}

TEST(BoxPairs, BipartiteMatchesBruteForce) {
  auto a = random_boxes(300, 2), b = random_boxes(250, 3);
  std::vector<std::pair<int, int>> brute;
  for (int i = 0; i < (int)a.size(); ++i)
    for (int j = 0; j < (int)b.size(); ++j)
      if (overlap(a[i], b[j])) brute.emplace_back(i, j);
  EXPECT_EQ(overlapping_pairs(a, b), brute);
}
