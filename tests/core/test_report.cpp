// report.json is written like every other output (issue 27): complete or not
// at all, never half-written.
#include "curvetet/core/error.hpp"
#include "curvetet/core/report.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

using namespace curvetet;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
  const auto dir = fs::temp_directory_path() / ("curvetet_test_report_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

} // namespace

TEST(Report, WritesTheWholeDocumentAndNoPartialFile) {
  const auto dir = fresh_dir("whole");
  Report r;
  r["model"] = "spot";
  r.add_timing("coarsen", 1.5);
  const auto path = (dir / "report.json").string();
  r.write(path);
  EXPECT_FALSE(fs::exists(path + ".partial"));
  std::ifstream in(path);
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["model"], "spot");
  EXPECT_EQ(j["timings_s"]["coarsen"], 1.5);
}

TEST(Report, AFailedWriteLeavesNothingAndKeepsThePreviousReport) {
  const auto dir = fresh_dir("failed");
  const auto path = (dir / "report.json").string();
  Report old;
  old["run"] = 1;
  old.write(path);
  // The rename onto a directory fails: the earlier report stays whole and
  // the partial file is gone.
  const auto blocked = (dir / "blocked").string();
  fs::create_directories(blocked);
  Report r;
  r["run"] = 2;
  try {
    r.write(blocked);
    FAIL() << "writing onto a directory must fail";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), static_cast<int>(ExitCode::io));
  }
  EXPECT_FALSE(fs::exists(blocked + ".partial"));
  std::ifstream in(path);
  EXPECT_EQ(nlohmann::json::parse(in)["run"], 1);
}
