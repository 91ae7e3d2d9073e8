// `curvetet shell` with coarsening, end to end: the same files for 1 and 2
// threads, the report's coarsening section, and every input vertex mapped
// (read back from map.txt and middle.ply) within epsilon of itself.
#include "tiny_meshes.hpp"

#include "curvetet/io/read_surface.hpp"
#include "curvetet/io/write_surface.hpp"
#include "curvetet/io/write_vertex_map.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

using namespace curvetet;

namespace {
std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
} // namespace

TEST(CliCoarsen, IdenticalForOneAndTwoThreadsAndWithinEpsilon) {
  namespace fs = std::filesystem;
  const fs::path base = fs::temp_directory_path() / "curvetet_test_cli_coarsen";
  fs::remove_all(base);
  // A subdivided octahedron on the unit sphere (512 faces): coarsens well.
  fs::create_directories(base);
  const std::string input = (base / "sphere.off").string();
  io::write_surface(input, shell::test::sphere(3));
  for (int threads : {1, 2}) {
    const std::string cmd = std::string(CURVETET_BINARY) + " -q --threads " + std::to_string(threads) + " shell " +
                            input + " -o " + (base / std::to_string(threads)).string() + " --epsilon 0.02 --debug-invariants";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  }
  for (const char* name : {"bottom.ply", "middle.ply", "top.ply", "map.txt"})
    EXPECT_EQ(slurp(base / "1" / name), slurp(base / "2" / name)) << name;

  const auto report = nlohmann::json::parse(slurp(base / "1" / "report.json"));
  ASSERT_TRUE(report.contains("coarsen"));
  const auto& c = report["coarsen"];
  const auto middle = mesh::to_surface_mesh(io::read_surface((base / "1" / "middle.ply").string()));
  EXPECT_EQ(c["faces_after"].get<int>(), middle.num_faces());
  EXPECT_LT(c["faces_after"].get<int>(), c["faces_before"].get<int>());
  ASSERT_FALSE(c["passes"].empty());
  for (const auto& p : c["passes"]) {
    long long sum = 0;
    for (const auto& [reason, n] : p["rejected_by_reason"].items()) sum += n.get<long long>();
    EXPECT_EQ(p["tried"].get<long long>(), p["accepted"].get<long long>() + sum);
  }
  const double epsilon = c["epsilon"].get<double>();
  const auto in = mesh::to_surface_mesh(io::read_surface(input));
  const auto map = io::read_vertex_map((base / "1" / "map.txt").string());
  ASSERT_EQ(static_cast<int>(map.size()), in.num_vertices());
  for (int i = 0; i < in.num_vertices(); ++i) {
    const auto& r = map[i];
    ASSERT_GE(r.face, 0);
    ASSERT_LT(r.face, middle.num_faces());
    const auto& t = middle.faces[r.face];
    const auto p = (1 - r.u - r.v) * middle.vertices[t[0]] + r.u * middle.vertices[t[1]] + r.v * middle.vertices[t[2]];
    // Files hold the doubles at full precision (round trip), so no slack.
    EXPECT_LT((p - in.vertices[i]).norm(), epsilon) << "vertex " << i;
  }
  fs::remove_all(base);
}
