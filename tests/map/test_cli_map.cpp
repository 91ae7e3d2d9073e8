// The CLI side of the map: `curvetet MESH --map` (binary and JSON layouts of
// the same map), `curvetet transfer` both ways (CSV and PLY), `curvetet
// deform` (the twisted dense surface follows the exact twist within the map
// distance).
#include "shell/tiny_meshes.hpp"
#include "support/run_command.hpp"

#include "curvetet/io/map_file.hpp"
#include "curvetet/io/read_surface.hpp"
#include "curvetet/io/vertex_table.hpp"
#include "curvetet/io/write_surface.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

using namespace curvetet;

namespace {

std::string dir() {
  static const std::string d = [] {
    auto p = std::filesystem::temp_directory_path() / ("curvetet_cli_map_" + std::to_string(::getpid()));
    std::filesystem::create_directories(p);
    return p.string();
  }();
  return d;
}

std::string cli() { return std::string(CURVETET_BINARY) + " -q "; }

// A 512-face ellipsoid meshed at epsilon 2% with --map (binary), once.
const std::string& meshed() {
  static const std::string map_path = [] {
    auto m = shell::test::sphere(3);
    for (auto& p : m.vertices) p = mesh::Vec3(p.x(), 0.7 * p.y(), 0.5 * p.z());
    io::write_surface(dir() + "/ell.off", m);
    const auto r = test::run_command(cli() + dir() + "/ell.off -o " + dir() + "/ell.msh --epsilon 0.02 --map " + dir() +
                                     "/ell.map");
    EXPECT_EQ(r.exit_code, 0);
    return dir() + "/ell.map";
  }();
  return map_path;
}

} // namespace

TEST(CliMap, JsonAndBinaryHoldTheSameMap) {
  const auto binary = io::read_map(meshed());
  const auto r = test::run_command(cli() + dir() + "/ell.off -o " + dir() + "/ell2.msh --epsilon 0.02 --map " + dir() +
                                   "/ell.map.json");
  ASSERT_EQ(r.exit_code, 0);
  const auto json = io::read_map(dir() + "/ell.map.json");
  EXPECT_EQ(binary.nodes, json.nodes);
  EXPECT_EQ(binary.triangles, json.triangles);
  ASSERT_EQ(binary.node_to_input.size(), json.node_to_input.size());
  for (std::size_t j = 0; j < json.node_to_input.size(); ++j) {
    EXPECT_EQ(binary.node_to_input[j].face, json.node_to_input[j].face);
    EXPECT_EQ(binary.node_to_input[j].u, json.node_to_input[j].u);
  }
  // The input inside the map is the input file.
  const auto input = mesh::to_surface_mesh(io::read_surface(dir() + "/ell.off"));
  EXPECT_EQ(binary.input.vertices, input.vertices);
  EXPECT_EQ(binary.input.faces, input.faces);
}

TEST(CliMap, TransferBothWaysThroughFiles) {
  const auto m = io::read_map(meshed());
  {
    std::ofstream csv(dir() + "/attr.csv");
    csv << "x,y,z,temperature,label\n";
    for (const auto& p : m.input.vertices) csv << p.x() << ',' << p.y() << ',' << p.z() << ',' << 2 * p.x() - p.z() << ',' << (p.y() > 0 ? 5 : 9) << '\n';
  }
  auto r = test::run_command(cli() + "transfer " + meshed() + " " + dir() + "/attr.csv -o " + dir() + "/nodes.ply --to boundary");
  ASSERT_EQ(r.exit_code, 0);
  const auto nodes = io::read_vertex_table(dir() + "/nodes.ply", {"label"});
  ASSERT_EQ(nodes.values.rows(), static_cast<Eigen::Index>(m.nodes.size()));
  EXPECT_EQ(nodes.positions, m.nodes);
  r = test::run_command(cli() + "transfer " + meshed() + " " + dir() + "/nodes.ply -o " + dir() + "/back.csv --to input");
  ASSERT_EQ(r.exit_code, 0);
  const auto back = io::read_vertex_table(dir() + "/back.csv", {"label"});
  ASSERT_EQ(back.values.rows(), static_cast<Eigen::Index>(m.input.vertices.size()));
  const double eps = 0.02 * mesh::bbox_diagonal(m.input.vertices);
  int flipped = 0;
  for (std::size_t i = 0; i < m.input.vertices.size(); ++i) {
    const auto& p = m.input.vertices[i];
    // Linear field, |grad| = sqrt(5): round trip within 3 |grad| epsilon.
    EXPECT_LT(std::abs(back.values(i, 0) - (2 * p.x() - p.z())), 3 * std::sqrt(5.0) * eps);
    EXPECT_TRUE(back.values(i, 1) == 5 || back.values(i, 1) == 9);
    flipped += back.values(i, 1) != (p.y() > 0 ? 5 : 9);
  }
  EXPECT_LT(flipped, static_cast<int>(m.input.vertices.size()) / 10);
  // Wrong direction for the table's size: refused.
  r = test::run_command(cli() + "transfer " + meshed() + " " + dir() + "/attr.csv -o " + dir() + "/x.csv --to input 2>/dev/null");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_FALSE(std::filesystem::exists(dir() + "/x.csv"));
}

TEST(CliMap, DeformCarriesATwistToTheDenseInput) {
  const auto r = test::run_command(cli() + "deform " + meshed() + " -o " + dir() + "/twisted.off --twist 45 --report " +
                                   dir() + "/deform.json");
  ASSERT_EQ(r.exit_code, 0);
  const auto m = io::read_map(meshed());
  const auto twisted = mesh::to_surface_mesh(io::read_surface(dir() + "/twisted.off"));
  ASSERT_EQ(twisted.vertices.size(), m.input.vertices.size());
  EXPECT_EQ(twisted.faces, m.input.faces);
  // Twist about x (the longest axis) by up to ±22.5°: points move a lot...
  double moved = 0;
  for (std::size_t i = 0; i < m.input.vertices.size(); ++i) moved = std::max(moved, (twisted.vertices[i] - m.input.vertices[i]).norm());
  EXPECT_GT(moved, 0.1);
  // ...yet the carried surface stays within the map distance (< epsilon)
  // times the twist's Lipschitz factor of the exact twist of the input.
  std::ifstream in(dir() + "/deform.json");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto pos = text.find("max_deviation_from_exact_twist_relative");
  ASSERT_NE(pos, std::string::npos);
  const double deviation = std::stod(text.substr(text.find(':', pos) + 1));
  EXPECT_LT(deviation, 3 * 0.02);
  EXPECT_GT(deviation, 0.0);
}
