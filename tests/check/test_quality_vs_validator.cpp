// The report tells the truth: the quality figures curvetet reports (the
// main job's report.json, `curvetet check --json`) agree with the
// independent yardstick ../shared/tools/validate.py (DESIGN.md §8) within
// 5 %: max AMIPS (amips_curved_max), mean AMIPS (amips_curved_mean) and min
// scaled Jacobian (scaled_jacobian_curved_min), in its convention (regular
// tet: AMIPS 3, scaled Jacobian 1; highorder/quality.hpp, which samples
// validate.py's points; its mean counts the corners twice, so the means are
// close, not equal). Skipped only when /usr/bin/python3 lacks numpy or the
// script is missing.
#include "curvetet/io/msh.hpp"
#include "curvetet/io/write_surface.hpp"

#include "common/curved_box.hpp"
#include "support/run_command.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

using namespace curvetet;

namespace {

const std::string kValidator = CURVETET_SHARED_DATA "/../tools/validate.py";

// The command's stdout and exit code (stderr dropped: logs).
test::CommandResult run(const std::string& cmd) { return test::run_command(cmd + " 2>/dev/null"); }

bool validator_available() {
  return std::filesystem::exists(kValidator) &&
         std::system("/usr/bin/python3 -c 'import numpy' > /dev/null 2>&1") == 0;
}

std::filesystem::path temp_dir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("curvetet_quality_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// validate.py's "quality" object for `msh` (through --out-json: Gmsh may
// write to stdout).
nlohmann::json validator_quality(const std::filesystem::path& msh, const std::string& extra = "") {
  const auto out = msh.parent_path() / (msh.stem().string() + ".validate.json");
  const auto r = run("/usr/bin/python3 " + kValidator + " " + msh.string() + " --out-json " + out.string() + " " + extra);
  EXPECT_EQ(r.exit_code, 0) << r.out;
  std::ifstream in(out);
  return nlohmann::json::parse(in).at("quality");
}

// Ours (max AMIPS, mean AMIPS, min scaled Jacobian) against validate.py's.
void expect_agrees(double max_amips, double mean_amips, double min_sj, const nlohmann::json& v, const char* what) {
  SCOPED_TRACE(what);
  const double vmax = v.at("amips_curved_max").get<double>(), vmean = v.at("amips_curved_mean").get<double>(),
               vsj = v.at("scaled_jacobian_curved_min").get<double>();
  EXPECT_NEAR(max_amips, vmax, 0.05 * vmax);
  EXPECT_NEAR(mean_amips, vmean, 0.05 * vmean);
  EXPECT_NEAR(min_sj, vsj, 0.05 * std::abs(vsj));
  std::printf("%s: max AMIPS %.6g vs %.6g, mean %.6g vs %.6g, min SJ %.6g vs %.6g\n", what, max_amips, vmax,
              mean_amips, vmean, min_sj, vsj);
}

void expect_check_agrees(const std::filesystem::path& msh, const nlohmann::json& v) {
  const auto r = run(std::string(CURVETET_BINARY) + " check " + msh.string() + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto q = nlohmann::json::parse(r.out)["check"]["quality"];
  expect_agrees(q["max_amips"].get<double>(), q["mean_amips"].get<double>(), q["min_scaled_jacobian"].get<double>(),
                v, "curvetet check --json");
}

} // namespace

// A bent order-3 box (curved tets everywhere, worst points on edges and
// corners): `curvetet check --json` against validate.py.
TEST(QualityVsValidator, CheckAgreesOnACurvedBox) {
  if (!validator_available()) GTEST_SKIP() << "no validate.py or numpy";
  const auto dir = temp_dir("box");
  const auto m = curvetet::testing::curved_box(3, 2, 0.3);
  io::write_msh((dir / "box.msh").string(), m, io::MshFormat::v41_binary);
  const auto v = validator_quality(dir / "box.msh");
  expect_check_agrees(dir / "box.msh", v);
}

// The main job on spot (P = 4, eps = 1 %): its report's curved optimization
// and verification figures and `curvetet check --json` against validate.py.
TEST(QualityVsValidator, MainJobReportAgreesOnSpot) {
  if (!validator_available()) GTEST_SKIP() << "no validate.py or numpy";
  const auto dir = temp_dir("spot");
  const std::string input = CURVETET_SOURCE_DIR "/examples/spot.off";
  const auto msh = dir / "spot.msh", report = dir / "spot.json";
  const auto r = run(std::string(CURVETET_BINARY) + " " + input + " -o " + msh.string() + " --report " +
                     report.string());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  std::ifstream in(report);
  const auto j = nlohmann::json::parse(in);
  const auto v = validator_quality(msh, "--input " + input + " --eps 0.01");
  const auto& co = j.at("curved_optimization");
  expect_agrees(co["max_amips_after"].get<double>(), co["mean_amips_after"].get<double>(),
                co["min_scaled_jacobian_after"].get<double>(), v, "report curved_optimization");
  const auto& q = j.at("verification").at("quality");
  expect_agrees(q["max_amips"].get<double>(), q["mean_amips"].get<double>(), q["min_scaled_jacobian"].get<double>(), v,
                "report verification");
  expect_check_agrees(msh, v);
}
