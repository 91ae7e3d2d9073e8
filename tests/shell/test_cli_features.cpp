// Features end to end (issue 9): `curvetet shell --feature-angle` keeps
// every corner and chain, and the main command writes the coarse feature
// curves as order-P lines in the physical group "features", read back by
// Gmsh itself.
#include "tiny_meshes.hpp"

#include "curvetet/io/write_surface.hpp"
#include "support/run_command.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <map>

using namespace curvetet;

namespace {

std::filesystem::path temp_dir() {
  auto dir = std::filesystem::temp_directory_path() / "curvetet_cli_features";
  std::filesystem::create_directories(dir);
  return dir;
}

// Flat-subdivided octahedron (12 feature chains, 6 corners at 30 degrees).
std::string write_octahedron(int levels) {
  mesh::SurfaceMesh m = shell::test::octahedron();
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      auto key = std::minmax(a, b);
      auto [it, inserted] = mid.try_emplace({key.first, key.second}, m.num_vertices());
      if (inserted) m.vertices.push_back(0.5 * (m.vertices[a] + m.vertices[b]));
      return it->second;
    };
    std::vector<mesh::Tri> faces;
    for (auto [a, b, c] : m.faces) {
      const int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      faces.insert(faces.end(), {{a, ab, ca}, {ab, b, bc}, {ca, bc, c}, {ab, bc, ca}});
    }
    m.faces = faces;
  }
  const auto path = (temp_dir() / "octahedron.off").string();
  io::write_surface(path, m);
  return path;
}

} // namespace

TEST(CliFeatures, ShellKeepsCornersAndChains) {
  const auto in = write_octahedron(3);
  const auto out = (temp_dir() / "shell").string();
  const auto r = test::run_command(std::string(CURVETET_BINARY) + " -q shell " + in +
                                   " --feature-angle 30 --epsilon 0.01 -o " + out + " 2>&1");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto j = nlohmann::json::parse(std::ifstream(out + "/report.json"));
  const auto& c = j["features"]["check"];
  EXPECT_TRUE(c["ok"].get<bool>());
  EXPECT_EQ(c["corners"].get<int>(), 6);
  EXPECT_EQ(c["chains"].get<int>(), 12);
  EXPECT_EQ(c["corners_missing"].get<int>(), 0);
  EXPECT_EQ(c["corners_moved"].get<int>(), 0);
  EXPECT_EQ(c["broken_chains"].get<int>(), 0);
  EXPECT_LT(c["coarse_edges"].get<int>(), 96); // the chains coarsened
}

TEST(CliFeatures, MeshWritesFeatureLinesThatGmshReads) {
  const auto in = write_octahedron(2);
  const auto msh = (temp_dir() / "octahedron.msh").string();
  const auto report = (temp_dir() / "octahedron.json").string();
  const auto r = test::run_command(std::string(CURVETET_BINARY) + " -q " + in + " --feature-angle 30 --order 3 -o " +
                                   msh + " --report " + report + " 2>&1");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto j = nlohmann::json::parse(std::ifstream(report));
  const int lines = j["features"]["lines"].get<int>();
  EXPECT_EQ(lines, j["features"]["coarse_edges"].get<int>());
  EXPECT_GE(lines, 12);
  // Gmsh: the "features" group holds `lines` order-3 lines (type 26) whose
  // end nodes are corner nodes of boundary triangles.
  const std::string py = R"(
import gmsh, sys
gmsh.initialize(); gmsh.option.setNumber("General.Terminal", 0); gmsh.open(sys.argv[1])
n = 0
for dim, tag in gmsh.model.getPhysicalGroups(1):
    if gmsh.model.getPhysicalName(dim, tag) != "features": continue
    for e in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
        types, tags, nodes = gmsh.model.mesh.getElements(1, e)
        for t, ts in zip(types, tags):
            assert t == 26, t
            n += len(ts)
print(n)
)";
  const auto g = test::run_command("/usr/bin/python3 -c '" + py + "' " + msh + " 2>&1");
  ASSERT_EQ(g.exit_code, 0) << g.out;
  EXPECT_EQ(std::stoi(g.out), lines);
}

// Constraint points (issue 26): the features file's points join the input
// vertices where input -> boundary is enforced, also on faces the feature
// refinement splits (every corner face of the octahedron has two feature
// edges).
TEST(CliFeatures, ConstraintPointsAreMappedWithinEpsilon) {
  const auto in = write_octahedron(2);
  const auto features = (temp_dir() / "points.json").string();
  nlohmann::json points;
  for (int f = 0; f < 128; f += 3) {
    points["faces"].push_back(f);
    points["barycentric"].push_back({0.2, 0.3, 0.5});
  }
  std::ofstream(features) << nlohmann::json{{"points", points}}.dump();
  const auto msh = (temp_dir() / "points.msh").string();
  const auto report = (temp_dir() / "points.json.report").string();
  const auto r = test::run_command(std::string(CURVETET_BINARY) + " -q " + in + " --feature-angle 30 --features " +
                                   features + " --order 3 --debug-invariants -o " + msh + " --report " + report + " 2>&1");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto j = nlohmann::json::parse(std::ifstream(report));
  EXPECT_EQ(j["shell"]["constraint_points"].get<int>(), 43);
  // The shell's map check covers every tracked point, constraint points too.
  EXPECT_LT(j["coarsen"]["max_distance_relative"].get<double>(), 0.01);
  EXPECT_LE(j["coarsen"]["max_surface_distance_relative"].get<double>(), 0.01);
}
