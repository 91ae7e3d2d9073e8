// The editor's open-addressing key table (volume/edit/node_key_table.hpp)
// against std::map under random inserts and erases, many of them in a few
// crowded probe runs (keys differing in one entry), so that deletions shift
// entries across the table's wrap-around.
#include "curvetet/volume/edit/node_key_table.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>

namespace curvetet::volume::edit {
namespace {

NodeKey key(int a, int b) { return {a, 4 - b, b, 0, -1, -1, -1, -1}; }

TEST(NodeKeyTable, MatchesAMapUnderRandomInsertsAndErases) {
  NodeKeyTable table;
  std::map<NodeKey, int> reference;
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> vertex(0, 300), weight(0, 4), op(0, 2);
  for (int step = 0; step < 200000; ++step) {
    const NodeKey k = key(vertex(rng), weight(rng));
    switch (op(rng)) {
      case 0: {
        const bool inserted = table.insert(k, step);
        EXPECT_EQ(inserted, reference.emplace(k, step).second);
        break;
      }
      case 1:
        table.erase(k);
        reference.erase(k);
        break;
      default: {
        const auto it = reference.find(k);
        ASSERT_EQ(table.find(k), it == reference.end() ? -1 : it->second) << "step " << step;
      }
    }
    ASSERT_EQ(table.size(), reference.size());
  }
  for (const auto& [k, node] : reference) EXPECT_EQ(table.find(k), node);
}

TEST(NodeKeyTable, EraseOfAnAbsentKeyChangesNothing) {
  NodeKeyTable table;
  EXPECT_TRUE(table.insert(key(1, 2), 5));
  EXPECT_FALSE(table.insert(key(1, 2), 6));
  table.erase(key(2, 2));
  EXPECT_EQ(table.size(), 1u);
  EXPECT_EQ(table.find(key(1, 2)), 5);
  table.erase(key(1, 2));
  EXPECT_EQ(table.find(key(1, 2)), -1);
  EXPECT_EQ(table.size(), 0u);
}

} // namespace
} // namespace curvetet::volume::edit
