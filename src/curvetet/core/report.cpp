#include "curvetet/core/report.hpp"

#include "curvetet/core/atomic_file.hpp"
#include "curvetet/core/error.hpp"
#include "curvetet/core/log.hpp"

namespace curvetet {

void Report::add_timing(const std::string& stage, double seconds) { data_["timings_s"][stage] = seconds; }

void Report::write(const std::string& path) const {
  AtomicFile file(path);
  file.stream() << data_.dump(2) << '\n';
  file.commit();
}

StageTimer::StageTimer(Report* report, std::string stage)
    : report_(report), stage_(std::move(stage)), start_(std::chrono::steady_clock::now()) {
  logger().info("{} ...", stage_);
}

double StageTimer::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

StageTimer::~StageTimer() {
  double s = elapsed();
  if (report_) report_->add_timing(stage_, s);
  logger().info("{} done in {:.3f} s", stage_, s);
}

} // namespace curvetet
