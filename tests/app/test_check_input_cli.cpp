// `curvetet check-input` on every mesh of ../shared/data: the good ones pass,
// each bad one fails naming the defects the MANIFEST lists for it.
#include "curvetet/core/error.hpp"
#include "support/run_command.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <set>

using namespace curvetet;
using test::quoted;
using test::run_command;
namespace fs = std::filesystem;

namespace {

nlohmann::json check_input_json(const fs::path& mesh, int* exit_code) {
  auto r = run_command(std::string(CURVETET_BINARY) + " -q check-input --json " + quoted(mesh.string()) + " 2>/dev/null");
  *exit_code = r.exit_code;
  return nlohmann::json::parse(r.out);
}

std::set<std::string> defect_classes(const nlohmann::json& j) {
  std::set<std::string> out;
  for (const auto& d : j["input"]["defects"]) out.insert(d["class"].get<std::string>());
  return out;
}

} // namespace

TEST(CheckInputCli, EveryGoodMeshPasses) {
  const fs::path dir = fs::path(CURVETET_SHARED_DATA) / "good";
  if (!fs::exists(dir)) GTEST_SKIP() << "no " << dir;
  int tested = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".off") continue;
    int code = -1;
    auto j = check_input_json(entry.path(), &code);
    EXPECT_EQ(code, 0) << entry.path() << "\n" << j.dump(1);
    EXPECT_TRUE(j["input"]["valid"].get<bool>()) << entry.path();
    ++tested;
  }
  EXPECT_GE(tested, 20);
}

TEST(CheckInputCli, EveryBadMeshFailsNamingItsDefects) {
  const fs::path dir = fs::path(CURVETET_SHARED_DATA) / "bad";
  if (!fs::exists(dir)) GTEST_SKIP() << "no " << dir;
  // From ../shared/data/MANIFEST.md: the defects each file has (that our
  // checks can see; later classes are not checked once earlier ones fail).
  const std::map<std::string, std::set<std::string>> expected = {
      {"degenerate_exact_coincident_vertices_spot.off", {"degenerate_triangle", "self_intersection"}},
      {"inconsistent_orientation_blobby_shuffled_cgal.off", {"inconsistent_orientation"}},
      {"inverted_ellipsoid_cgal.off", {"wrong_orientation"}},
      {"many_defects_thingi10k_73335.off",
       {"degenerate_triangle", "nonmanifold_edge", "nonmanifold_vertex", "open_boundary", "inconsistent_orientation"}},
      {"non_triangle_quads_suzanne.off", {"non_triangle_face"}},
      {"nonmanifold_edges_compsolid_gmsh_coherence.off", {"nonmanifold_edge", "nonmanifold_vertex"}},
      {"nonmanifold_vertices_selfint_thingi10k_40922.off", {"nonmanifold_vertex", "self_intersection"}},
      {"open_holes_stanford_bunny.off", {"open_boundary"}},
      {"open_surface_patch_gmsh_spherical_surf.off", {"open_boundary"}},
      {"selfintersecting_bull_cgal.off", {"self_intersection"}},
      {"selfintersecting_touching_assembly_as1.off", {"self_intersection"}},
  };
  for (const auto& [name, classes] : expected) {
    const fs::path path = dir / name;
    ASSERT_TRUE(fs::exists(path)) << path;
    int code = -1;
    auto j = check_input_json(path, &code);
    auto found = defect_classes(j);
    for (const auto& c : classes) EXPECT_TRUE(found.count(c)) << name << " should report " << c << "\n" << j.dump(1);
    EXPECT_GE(code, static_cast<int>(ExitCode::input_defect_base)) << name;
    EXPECT_EQ(code, j["input"]["exit_code"].get<int>()) << name;
    EXPECT_FALSE(j["error"]["message"].get<std::string>().empty());
  }
}

TEST(CheckInputCli, DistinctExitCodesPerClass) {
  std::set<int> codes;
  for (int d = 0; d < static_cast<int>(InputDefect::count); ++d) codes.insert(exit_code(static_cast<InputDefect>(d)));
  EXPECT_EQ(codes.size(), static_cast<std::size_t>(InputDefect::count));
  EXPECT_EQ(codes.count(0), 0u);
}

TEST(CheckInputCli, MainCommandStopsOnBadInputWithoutWritingReport) {
  const fs::path bad = fs::path(CURVETET_SHARED_DATA) / "bad" / "inverted_ellipsoid_cgal.off";
  if (!fs::exists(bad)) GTEST_SKIP();
  const fs::path report = fs::temp_directory_path() / "curvetet_should_not_exist.json";
  fs::remove(report);
  auto r = run_command(std::string(CURVETET_BINARY) + " -q " + quoted(bad.string()) + " --report " +
                       quoted(report.string()) + " 2>&1");
  EXPECT_EQ(r.exit_code, exit_code(InputDefect::wrong_orientation));
  EXPECT_NE(r.out.find("wrong_orientation"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(report));
}
