// The main command end to end, judged by tools that share no code with it:
// `curvetet spot.off -o OUT.msh --order 4 --epsilon 0.01` must succeed, and
// Gmsh (python3-gmsh, tests/pipeline/gmsh_pipeline_check.py) must find every
// tet positive (its AnalyseMeshQuality plugin, det J sampled densely, minSJ)
// and every input vertex within epsilon of the curved boundary, sampled
// through Gmsh's own element map. Skipped only when /usr/bin/python3 lacks
// gmsh or numpy.
#include "support/run_command.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace {

bool python_gmsh_available() {
  return std::system("/usr/bin/python3 -c 'import gmsh, numpy' > /dev/null 2>&1") == 0;
}

struct Run {
  std::filesystem::path dir, msh, report;
};

// Runs the main command on `input` with `extra` arguments into a fresh dir.
Run run_main(const std::string& input, const std::string& name, const std::string& extra) {
  Run r;
  r.dir = std::filesystem::temp_directory_path() / ("curvetet_pipeline_" + name);
  std::filesystem::remove_all(r.dir);
  std::filesystem::create_directories(r.dir);
  r.msh = r.dir / "out.msh";
  r.report = r.dir / "report.json";
  const std::string cmd = curvetet::test::quoted(CURVETET_BINARY) + " -q " + curvetet::test::quoted(input) + " -o " +
                          curvetet::test::quoted(r.msh.string()) + " --report " +
                          curvetet::test::quoted(r.report.string()) + " " + extra + " 2>&1";
  auto out = curvetet::test::run_command(cmd);
  EXPECT_EQ(out.exit_code, 0) << cmd << "\n" << out.out;
  return r;
}

std::string gmsh_check(const Run& r, const std::string& input, double epsilon) {
  return "/usr/bin/python3 " CURVETET_SOURCE_DIR "/tests/pipeline/gmsh_pipeline_check.py " +
         curvetet::test::quoted(r.msh.string()) + " " + curvetet::test::quoted(input) + " " + std::to_string(epsilon) +
         " 2>&1";
}

} // namespace

TEST(PipelineGmsh, SpotOrder4IsPositiveAndWithinEpsilonForGmsh) {
  if (!python_gmsh_available()) GTEST_SKIP() << "/usr/bin/python3 lacks gmsh or numpy";
  const std::string input = CURVETET_SOURCE_DIR "/examples/spot.off";
  const double epsilon = 0.01;
  auto run = run_main(input, "spot", "--order 4 --epsilon 0.01");
  ASSERT_TRUE(std::filesystem::exists(run.msh));

  // curvetet's own verdict, for the record (the report must say valid too).
  nlohmann::json report = nlohmann::json::parse(std::ifstream(run.report));
  EXPECT_TRUE(report["verification"]["valid"].get<bool>());
  EXPECT_GT(report["verification"]["tets"].get<int>(), 0);

  const auto cmd = gmsh_check(run, input, epsilon);
  auto out = curvetet::test::run_command(cmd);
  EXPECT_EQ(out.exit_code, 0) << cmd << "\n" << out.out;
  // The checker really looked: it printed its figures.
  EXPECT_NE(out.out.find("AnalyseMeshQuality:"), std::string::npos) << out.out;
  EXPECT_NE(out.out.find("distance:"), std::string::npos) << out.out;

  // The same checker fails on a distance bound the mesh cannot meet (its
  // input->boundary max is near 1e-2, the mean near 3e-3).
  auto strict = curvetet::test::run_command(gmsh_check(run, input, 1e-3));
  EXPECT_NE(strict.exit_code, 0) << strict.out;
  EXPECT_NE(strict.out.find("FAIL: input vertex"), std::string::npos) << strict.out;
}

// `--fill all`: the exterior region out to a box is meshed too. Gmsh finds
// every tet of both regions positive and the "boundary" group (now the
// interface) within epsilon; `curvetet check` re-verifies the written file
// with its two regions.
TEST(PipelineGmsh, FillAllMeshesTheExteriorForGmshAndCheck) {
  if (!python_gmsh_available()) GTEST_SKIP() << "/usr/bin/python3 lacks gmsh or numpy";
  const std::string input = CURVETET_SOURCE_DIR "/examples/spot.off";
  auto run = run_main(input, "spot_all", "--order 4 --epsilon 0.01 --fill all");
  ASSERT_TRUE(std::filesystem::exists(run.msh));
  nlohmann::json report = nlohmann::json::parse(std::ifstream(run.report));
  const auto& v = report["verification"];
  EXPECT_TRUE(v["valid"].get<bool>());
  ASSERT_TRUE(v.contains("exterior")) << v.dump(1);
  EXPECT_GT(v["exterior"]["tets"].get<int>(), 0);
  EXPECT_EQ(v["exterior"]["interface_triangles"].get<int>(), report["assembly"]["boundary_triangles"].get<int>());
  EXPECT_GT(v["exterior"]["outer_triangles"].get<int>(), 0);

  auto out = curvetet::test::run_command(gmsh_check(run, input, 0.01));
  EXPECT_EQ(out.exit_code, 0) << out.out;
  EXPECT_NE(out.out.find("AnalyseMeshQuality:"), std::string::npos) << out.out;

  auto check = curvetet::test::run_command(curvetet::test::quoted(CURVETET_BINARY) + " -q check " +
                                           curvetet::test::quoted(run.msh.string()) + " --input " +
                                           curvetet::test::quoted(input) + " 2>&1");
  EXPECT_EQ(check.exit_code, 0) << check.out;
  EXPECT_NE(check.out.find("exterior region:"), std::string::npos) << check.out;
}
