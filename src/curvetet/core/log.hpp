#pragma once
// The library's one logger (spdlog), and a throttled progress line for long
// loops. Verbosity: 0 = warnings only (-q), 1 = info (default), 2 = debug (-v).
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstddef>
#include <string>

namespace curvetet {

spdlog::logger& logger();
void set_verbosity(int level);

// Logs "label: done/total (pct%)" at most every `period`, and once at the end.
class Progress {
 public:
  Progress(std::string label, std::size_t total, std::chrono::milliseconds period = std::chrono::milliseconds(1000));
  void update(std::size_t done);
  void finish();

 private:
  std::string label_;
  std::size_t total_;
  std::chrono::milliseconds period_;
  std::chrono::steady_clock::time_point last_;
  bool finished_ = false;
};

} // namespace curvetet
