// Meshes made by Gmsh itself (a curved sphere, orders 2-4, a few tets folded
// on purpose; tests/io/gmsh_generate.py) are read from MSH 4.1 ASCII, 4.1
// binary and 2.2, and the certificate agrees tet by tet with Gmsh's own
// AnalyseMeshQuality (minJ/maxJ > 0). Skipped only if python3-gmsh is absent.
#include "curvetet/check/verify_tet_mesh.hpp"
#include "curvetet/highorder/jacobian_certificate.hpp"
#include "curvetet/io/msh.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>

using namespace curvetet;

class GmshGenerated : public ::testing::TestWithParam<int> {};

TEST_P(GmshGenerated, ReaderAndCertificateAgreeWithGmsh) {
  if (std::system("/usr/bin/python3 -c 'import gmsh' > /dev/null 2>&1") != 0) GTEST_SKIP() << "python3-gmsh missing";
  const int order = GetParam();
  auto dir = std::filesystem::temp_directory_path() / ("curvetet_gmsh_generated_" + std::to_string(order));
  std::filesystem::create_directories(dir);
  const std::string cmd = "/usr/bin/python3 " CURVETET_SOURCE_DIR "/tests/io/gmsh_generate.py " + dir.string() + " " +
                          std::to_string(order) + " 4";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  nlohmann::json g = nlohmann::json::parse(std::ifstream(dir / "gmsh.json"));
  const auto ratio = g["ratio"].get<std::vector<double>>();
  int gmsh_invalid = 0;
  for (double r : ratio) gmsh_invalid += r <= 0;
  ASSERT_GE(gmsh_invalid, 4);

  for (const char* name : {"gmsh_v41.msh", "gmsh_v41b.msh", "gmsh_v22.msh"}) {
    SCOPED_TRACE(name);
    auto m = io::read_msh((dir / name).string());
    ASSERT_EQ(m.order, order);
    ASSERT_EQ(m.num_tets(), g["tets"].get<int>());
    ASSERT_EQ(m.nodes.size(), g["nodes"].get<std::size_t>());
    auto v = check::verify_tet_mesh(m);
    for (int t = 0; t < m.num_tets(); ++t)
      EXPECT_EQ(v.validity[t] == highorder::Validity::positive, ratio[t] > 0)
          << "tet " << t << ": Gmsh minJ/maxJ " << ratio[t] << ", curvetet " << highorder::to_string(v.validity[t]);
    EXPECT_EQ(v.invalid, std::size_t(gmsh_invalid));
    EXPECT_TRUE(v.conformity_ok()) << v.text();
    EXPECT_EQ(m.groups.size(), 2u);
  }
}

INSTANTIATE_TEST_SUITE_P(Orders, GmshGenerated, ::testing::Values(2, 3, 4));
