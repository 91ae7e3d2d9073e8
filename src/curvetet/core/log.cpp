#include "curvetet/core/log.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>

namespace curvetet {

spdlog::logger& logger() {
  // stderr, so that stdout stays free for machine-readable output (--json).
  static std::shared_ptr<spdlog::logger> instance = [] {
    auto l = spdlog::stderr_color_mt("curvetet");
    l->set_pattern("[%T.%e] %^%l%$ %v");
    l->set_level(spdlog::level::info);
    return l;
  }();
  return *instance;
}

void set_verbosity(int level) {
  auto lvl = level <= 0 ? spdlog::level::warn : level == 1 ? spdlog::level::info : spdlog::level::debug;
  logger().set_level(lvl);
}

Progress::Progress(std::string label, std::size_t total, std::chrono::milliseconds period)
    : label_(std::move(label)), total_(total), period_(period), last_(std::chrono::steady_clock::now()) {}

void Progress::update(std::size_t done) {
  auto now = std::chrono::steady_clock::now();
  if (now - last_ < period_) return;
  last_ = now;
  double pct = total_ ? 100.0 * static_cast<double>(done) / static_cast<double>(total_) : 100.0;
  logger().info("{}: {}/{} ({:.0f}%)", label_, done, total_, pct);
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  logger().debug("{}: {}/{} done", label_, total_, total_);
}

} // namespace curvetet
