#include "curvetet/core/threads.hpp"

#include <tbb/global_control.h>
#include <tbb/info.h>

namespace curvetet {

struct ThreadLimit::Impl {
  tbb::global_control control;
};

ThreadLimit::ThreadLimit(int threads) {
  std::size_t n = threads > 0 ? static_cast<std::size_t>(threads) : static_cast<std::size_t>(tbb::info::default_concurrency());
  impl_ = std::make_unique<Impl>(Impl{tbb::global_control(tbb::global_control::max_allowed_parallelism, n)});
}

ThreadLimit::~ThreadLimit() = default;

} // namespace curvetet
