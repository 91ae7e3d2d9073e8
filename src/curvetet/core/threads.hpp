#pragma once
// `--threads N`: caps oneTBB's worker count for the whole process while the
// returned object lives. N = 0 means "all cores".
#include <memory>

namespace curvetet {

class ThreadLimit {
 public:
  explicit ThreadLimit(int threads);
  ~ThreadLimit();
  ThreadLimit(const ThreadLimit&) = delete;
  ThreadLimit& operator=(const ThreadLimit&) = delete;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace curvetet
