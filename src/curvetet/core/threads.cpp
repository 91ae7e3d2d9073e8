#include "curvetet/core/threads.hpp"

#include <tbb/global_control.h>
#include <tbb/info.h>

namespace curvetet {

// Built in place: a global_control copied out of a temporary is not the one
// registered (the temporary's destructor lifts the limit again).
struct ThreadLimit::Impl {
  explicit Impl(std::size_t n) : control(tbb::global_control::max_allowed_parallelism, n) {}
  tbb::global_control control;
};

ThreadLimit::ThreadLimit(int threads) {
  std::size_t n = threads > 0 ? static_cast<std::size_t>(threads) : static_cast<std::size_t>(tbb::info::default_concurrency());
  impl_ = std::make_unique<Impl>(n);
}

ThreadLimit::~ThreadLimit() = default;

} // namespace curvetet
