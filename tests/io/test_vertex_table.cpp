// Attribute tables for `curvetet transfer` (io/vertex_table.hpp): CSV and
// PLY round trips keep every value bit-exact, x/y/z become the position,
// labels are the named columns, binary PLY (both endiannesses) reads the
// same as ASCII, malformed tables are refused.
#include "curvetet/core/error.hpp"
#include "curvetet/io/vertex_table.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>

using namespace curvetet;

namespace {

std::string temp(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("curvetet_vt_" + std::to_string(::getpid()) + "_" + name)).string();
}

io::VertexTable sample() {
  io::VertexTable t;
  t.names = {"temperature", "label", "ux"};
  t.is_label = {0, 1, 0};
  t.values.resize(3, 3);
  t.values << 0.1, 4, -1.0 / 3, 1e-300, 7, 2.5, -7.25, 0, 1.0 / 7;
  t.positions = {{0, 1, 2}, {1.0 / 3, 0.5, -2}, {3, 4, 5}};
  return t;
}

void expect_same(const io::VertexTable& a, const io::VertexTable& b) {
  EXPECT_EQ(a.names, b.names);
  EXPECT_EQ(a.is_label, b.is_label);
  EXPECT_EQ(a.values, b.values);
  EXPECT_EQ(a.positions, b.positions);
}

template <class T>
void put(std::string& out, T v, bool big) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big != (std::endian::native == std::endian::big)) std::reverse(b, b + sizeof(T));
  out.append(b, sizeof(T));
}

} // namespace

TEST(VertexTable, CsvAndPlyRoundTrips) {
  const auto t = sample();
  for (const char* ext : {"a.csv", "a.ply"}) {
    const auto path = temp(ext);
    io::write_vertex_table(path, t, {{0, 1, 2}});
    expect_same(t, io::read_vertex_table(path, {"label"}));
    std::filesystem::remove(path);
  }
}

TEST(VertexTable, BinaryPlyReadsLikeAscii) {
  for (bool big : {false, true}) {
    std::string bytes = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                        " 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
                        "property uchar label\nproperty double f\nelement face 1\n"
                        "property list uchar int vertex_indices\nend_header\n";
    for (int v = 0; v < 2; ++v) {
      put<float>(bytes, 1.5f * v, big);
      put<float>(bytes, 2.0f, big);
      put<float>(bytes, -0.25f, big);
      put<std::uint8_t>(bytes, static_cast<std::uint8_t>(200 + v), big);
      put<double>(bytes, 1.0 / 3 + v, big);
    }
    put<std::uint8_t>(bytes, 3, big);
    for (int k = 0; k < 3; ++k) put<std::int32_t>(bytes, k % 2, big);
    const auto path = temp(big ? "be.ply" : "le.ply");
    std::ofstream(path, std::ios::binary) << bytes;
    const auto t = io::read_vertex_table(path, {"label"});
    std::filesystem::remove(path);
    ASSERT_EQ(t.names, (std::vector<std::string>{"label", "f"}));
    EXPECT_EQ(t.is_label, (std::vector<char>{1, 0}));
    EXPECT_EQ(t.values(1, 0), 201);
    EXPECT_EQ(t.values(1, 1), 1.0 / 3 + 1);
    EXPECT_EQ(t.positions[1], mesh::Vec3(1.5, 2.0, -0.25));
  }
}

TEST(VertexTable, RefusesMalformedTables) {
  const auto path = temp("bad.csv");
  std::ofstream(path) << "a,b\n1,2\n3\n";
  EXPECT_THROW(io::read_vertex_table(path), Error);
  std::ofstream(path) << "a,b\n1,x\n";
  EXPECT_THROW(io::read_vertex_table(path), Error);
  std::ofstream(path) << "a,b\n1,2\n";
  EXPECT_THROW(io::read_vertex_table(path, {"missing"}), Error);
  EXPECT_NO_THROW(io::read_vertex_table(path, {"b"}));
  std::filesystem::remove(path);
  EXPECT_THROW(io::read_vertex_table(temp("x.txt")), Error);
  const auto ply = temp("cut.ply");
  std::ofstream(ply) << "ply\nformat ascii 1.0\nelement vertex 3\nproperty double a\nend_header\n1 2\n";
  EXPECT_THROW(io::read_vertex_table(ply), Error);
  std::filesystem::remove(ply);
}
