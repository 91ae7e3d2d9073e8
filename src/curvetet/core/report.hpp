#pragma once
// Report: the JSON record every stage adds its counts and timings to
// (`--report FILE`). Stages write under their own key; timings go to
// report["timings_s"][stage].
#include <nlohmann/json.hpp>

#include <chrono>
#include <string>

namespace curvetet {

class Report {
 public:
  nlohmann::json& operator[](const std::string& key) { return data_[key]; }
  const nlohmann::json& json() const { return data_; }
  void add_timing(const std::string& stage, double seconds);
  // Writes the report; throws Error(ExitCode::io) on failure.
  void write(const std::string& path) const;

 private:
  nlohmann::json data_ = nlohmann::json::object();
};

// Times a scope, logs "stage ... done in X s" and records it in the report.
class StageTimer {
 public:
  StageTimer(Report* report, std::string stage);
  ~StageTimer();
  double elapsed() const;

 private:
  Report* report_;
  std::string stage_;
  std::chrono::steady_clock::time_point start_;
};

} // namespace curvetet
