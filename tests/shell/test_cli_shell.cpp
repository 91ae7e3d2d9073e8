// `curvetet shell` end to end: files written, the map read back points at
// the input vertices on the written middle surface.
#include "curvetet/highorder/element_map.hpp"
#include "curvetet/io/msh.hpp"
#include "curvetet/io/read_surface.hpp"
#include "curvetet/io/write_vertex_map.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

using namespace curvetet;

TEST(CliShell, WritesSurfacesMapAndReport) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "curvetet_test_cli_shell";
  fs::remove_all(dir);
  const std::string input = std::string(CURVETET_SHARED_DATA) + "/good/thingi10k_288351.off";
  const std::string cmd = std::string(CURVETET_BINARY) + " -q shell " + input + " -o " + dir.string() +
                          " --debug-invariants --no-coarsen --rounds 6";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  for (const char* name : {"bottom.ply", "middle.ply", "top.ply", "map.txt", "report.json"})
    EXPECT_TRUE(fs::exists(dir / name)) << name;
  const auto in = mesh::to_surface_mesh(io::read_surface(input));
  const auto middle = mesh::to_surface_mesh(io::read_surface((dir / "middle.ply").string()));
  const auto map = io::read_vertex_map((dir / "map.txt").string());
  ASSERT_EQ(static_cast<int>(map.size()), in.num_vertices());
  for (int i = 0; i < in.num_vertices(); ++i) {
    const auto& r = map[i];
    ASSERT_GE(r.face, 0);
    ASSERT_LT(r.face, middle.num_faces());
    const auto& t = middle.faces[r.face];
    const auto p = (1 - r.u - r.v) * middle.vertices[t[0]] + r.u * middle.vertices[t[1]] + r.v * middle.vertices[t[2]];
    EXPECT_LT((p - in.vertices[i]).norm(), 1e-12) << "vertex " << i;
  }
  std::ifstream report(dir / "report.json");
  const std::string text((std::istreambuf_iterator<char>(report)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"global_check\": \"passed\""), std::string::npos);
  EXPECT_NE(text.find("\"singular_vertices\""), std::string::npos);
  fs::remove_all(dir);
}

// --order 4: the middle surface is written as a conforming mesh of cubic
// triangles whose map points (read back from middle.msh) are within epsilon
// of every input vertex.
TEST(CliShell, OrderFourWritesTheCurvedMiddle) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "curvetet_test_cli_shell_curved";
  fs::remove_all(dir);
  const std::string input = std::string(CURVETET_SHARED_DATA) + "/good/thingi10k_288351.off";
  const std::string cmd = std::string(CURVETET_BINARY) + " -q shell " + input + " -o " + dir.string() +
                          " --order 4 --epsilon 0.01 --rounds 6";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  const auto middle = io::read_msh((dir / "middle.msh").string());
  EXPECT_EQ(middle.order, 3);
  EXPECT_EQ(middle.num_tets(), 0);
  const auto in = mesh::to_surface_mesh(io::read_surface(input));
  const auto map = io::read_vertex_map((dir / "map.txt").string());
  ASSERT_EQ(static_cast<int>(map.size()), in.num_vertices());
  ASSERT_GT(middle.num_boundary(), 0);
  const double epsilon = 0.01 * mesh::bbox_diagonal(in.vertices);
  std::vector<Eigen::Vector3d> nodes(middle.triangle_nodes());
  for (int i = 0; i < in.num_vertices(); ++i) {
    ASSERT_LT(map[i].face, middle.num_boundary());
    const int* t = middle.boundary_triangle(map[i].face);
    for (int k = 0; k < middle.triangle_nodes(); ++k) nodes[k] = middle.nodes[t[k]];
    const auto p = highorder::triangle_point(3, nodes.data(), Eigen::Vector2d(map[i].u, map[i].v));
    EXPECT_LT((p - in.vertices[i]).norm(), epsilon) << "vertex " << i;
  }
  EXPECT_TRUE(fs::exists(dir / "middle.vtu"));
  fs::remove_all(dir);
}
