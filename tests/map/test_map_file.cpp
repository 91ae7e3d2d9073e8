// The map file layouts (docs/map_format.md): binary and JSON round trips are
// bit-exact, and malformed files are refused with Error(io).
#include "curvetet/core/error.hpp"
#include "curvetet/io/map_file.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

using namespace curvetet;

namespace {

// A tetrahedron surface mapped to itself with order-2 boundary triangles:
// values chosen to exercise non-trivial doubles (not round numbers).
mesh::BoundaryMap small_map() {
  mesh::BoundaryMap m;
  m.order = 2;
  m.input.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.input.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  // One order-2 triangle over 6 nodes, another sharing an edge.
  for (int j = 0; j < 9; ++j) {
    m.nodes.emplace_back(0.1 * j + 1.0 / 3, -j / 7.0, std::sqrt(2.0) * j);
    m.node_ids.push_back(100 + 3 * j);
  }
  m.triangles = {0, 1, 2, 3, 4, 5, 1, 6, 2, 7, 8, 4};
  for (int i = 0; i < 4; ++i) m.vertex_to_boundary.push_back({i % 2, 0.1 + i / 11.0, 0.2 / (i + 1)});
  for (int j = 0; j < 9; ++j) m.node_to_input.push_back({j % 4, 1.0 / (j + 3), 0.5 - 1.0 / (j + 5)});
  return m;
}

void expect_equal(const mesh::BoundaryMap& a, const mesh::BoundaryMap& b) {
  EXPECT_EQ(a.order, b.order);
  EXPECT_EQ(a.input.vertices, b.input.vertices);
  EXPECT_EQ(a.input.faces, b.input.faces);
  EXPECT_EQ(a.nodes, b.nodes);
  EXPECT_EQ(a.node_ids, b.node_ids);
  EXPECT_EQ(a.triangles, b.triangles);
  ASSERT_EQ(a.vertex_to_boundary.size(), b.vertex_to_boundary.size());
  ASSERT_EQ(a.node_to_input.size(), b.node_to_input.size());
  for (std::size_t i = 0; i < a.vertex_to_boundary.size(); ++i) {
    EXPECT_EQ(a.vertex_to_boundary[i].face, b.vertex_to_boundary[i].face);
    EXPECT_EQ(a.vertex_to_boundary[i].u, b.vertex_to_boundary[i].u); // bit-exact
    EXPECT_EQ(a.vertex_to_boundary[i].v, b.vertex_to_boundary[i].v);
  }
  for (std::size_t j = 0; j < a.node_to_input.size(); ++j) {
    EXPECT_EQ(a.node_to_input[j].face, b.node_to_input[j].face);
    EXPECT_EQ(a.node_to_input[j].u, b.node_to_input[j].u);
    EXPECT_EQ(a.node_to_input[j].v, b.node_to_input[j].v);
  }
}

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("curvetet_map_" + std::to_string(::getpid()) + "_" + name)).string();
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

} // namespace

TEST(MapFile, FormatFollowsTheExtension) {
  EXPECT_EQ(io::map_format_for("a/b.map"), io::MapFormat::binary);
  EXPECT_EQ(io::map_format_for("b.JSON"), io::MapFormat::json);
  EXPECT_EQ(io::map_format_for("json"), io::MapFormat::binary);
}

TEST(MapFile, BinaryRoundTripIsBitExact) {
  const auto m = small_map();
  const auto path = temp_path("rt.map");
  io::write_map(path, m);
  const auto bytes = slurp(path);
  EXPECT_EQ(bytes.substr(0, 7), "CTETMAP");
  // Header 8 + 4 + 4, then each array with its count (docs/map_format.md).
  const std::size_t expected = 16 + 8 + 4 * 24 + 8 + 4 * 12 + 8 + 9 * 28 + 8 + 12 * 4 + 4 * 20 + 9 * 20;
  EXPECT_EQ(bytes.size(), expected);
  expect_equal(m, io::read_map(path));
  std::filesystem::remove(path);
}

TEST(MapFile, JsonRoundTripIsBitExact) {
  const auto m = small_map();
  const auto path = temp_path("rt.map.json");
  io::write_map(path, m);
  EXPECT_EQ(slurp(path).front(), '{');
  expect_equal(m, io::read_map(path));
  std::filesystem::remove(path);
}

TEST(MapFile, RefusesMalformedFiles) {
  const auto m = small_map();
  const auto path = temp_path("bad.map");
  io::write_map(path, m, io::MapFormat::binary);
  const auto bytes = slurp(path);
  std::filesystem::remove(path);
  // Truncated anywhere, or trailing garbage.
  for (std::size_t cut : {std::size_t(10), std::size_t(40), bytes.size() / 2, bytes.size() - 1})
    EXPECT_THROW(io::parse_map(std::string_view(bytes).substr(0, cut), "cut"), Error) << cut;
  EXPECT_THROW(io::parse_map(bytes + "x", "trailing"), Error);
  // An out-of-range index is caught by validation, in either layout.
  auto broken = m;
  broken.triangles[3] = 9;
  EXPECT_THROW(io::write_map(path, broken, io::MapFormat::binary), Error);
  broken = m;
  broken.node_to_input[2].face = 4;
  EXPECT_THROW(io::write_map(path, broken, io::MapFormat::json), Error);
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_THROW(io::parse_map("{\"format\": \"something else\"}", "other"), Error);
  EXPECT_THROW(io::parse_map("not json at all", "garbage"), Error);
  try {
    io::parse_map(std::string_view(bytes).substr(0, 40), "cut.map");
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), static_cast<int>(ExitCode::io));
  }
}
