// `--threads N` (core/threads.hpp) must cap oneTBB while it lives, and lift
// the cap afterwards.
#include "curvetet/core/threads.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

namespace {

std::size_t allowed() { return tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism); }

TEST(ThreadLimit, CapsTbbWhileAliveAndLiftsTheCapAfter) {
  const std::size_t before = allowed();
  {
    curvetet::ThreadLimit one(1);
    EXPECT_EQ(allowed(), 1u);
  }
  EXPECT_EQ(allowed(), before);
  if (before >= 2) {
    curvetet::ThreadLimit two(2);
    EXPECT_EQ(allowed(), 2u);
  }
}

} // namespace
