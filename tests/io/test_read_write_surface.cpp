// Reading every surface format, including binary STL/PLY written by hand,
// and bit-exact round trips through every writer.
#include "curvetet/core/error.hpp"
#include "curvetet/io/read_surface.hpp"
#include "curvetet/io/write_surface.hpp"
#include "support/shapes.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

using namespace curvetet;
namespace fs = std::filesystem;

namespace {

fs::path temp_dir() {
  auto d = fs::temp_directory_path() / ("curvetet_io_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

bool same_bits(const mesh::Vec3& a, const mesh::Vec3& b) { return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0; }

// A mesh whose coordinates need all 17 digits: random doubles.
mesh::SurfaceMesh awkward_tetrahedron() {
  auto m = test::tetrahedron();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  for (auto& v : m.vertices) v += mesh::Vec3(u(rng), u(rng), u(rng)) * 1e-7;
  m.vertices[1].x() = 5e-324; // a denormal must survive too
  return m;
}

void expect_same(const mesh::SurfaceMesh& m, const mesh::PolygonSoup& s) {
  ASSERT_EQ(s.points.size(), m.vertices.size());
  for (std::size_t i = 0; i < s.points.size(); ++i) EXPECT_TRUE(same_bits(s.points[i], m.vertices[i])) << "vertex " << i;
  ASSERT_EQ(s.polygons.size(), m.faces.size());
  for (std::size_t f = 0; f < m.faces.size(); ++f)
    EXPECT_EQ(s.polygons[f], (std::vector<std::int64_t>{m.faces[f][0], m.faces[f][1], m.faces[f][2]}));
}

} // namespace

TEST(SurfaceRoundTrip, TextFormatsKeepDoublesBitExact) {
  auto m = awkward_tetrahedron();
  for (std::string ext : {".off", ".obj", ".ply"}) {
    auto path = (temp_dir() / ("t" + ext)).string();
    io::write_surface(path, m);
    expect_same(m, io::read_surface(path));
  }
}

TEST(SurfaceRoundTrip, BinaryPly) {
  auto m = awkward_tetrahedron();
  auto path = (temp_dir() / "b.ply").string();
  io::write_surface(path, m, {.binary = true});
  expect_same(m, io::read_surface(path));
}

TEST(SurfaceRoundTrip, StlAsciiAndBinaryForFloatCoordinates) {
  // STL holds floats: coordinates that are floats round-trip exactly, and
  // corners are welded back to the same vertex numbering (first appearance).
  auto m = test::cube(-0.375f, 1.1f);
  for (bool binary : {false, true}) {
    auto path = (temp_dir() / (binary ? "b.stl" : "a.stl")).string();
    io::write_surface(path, m, {.binary = binary});
    auto s = io::read_surface(path);
    ASSERT_EQ(s.polygons.size(), m.faces.size());
    ASSERT_EQ(s.points.size(), m.vertices.size());
    for (std::size_t f = 0; f < m.faces.size(); ++f)
      for (int k = 0; k < 3; ++k)
        EXPECT_TRUE(same_bits(s.points[s.polygons[f][k]], m.vertices[m.faces[f][k]])) << "face " << f;
  }
}

TEST(SurfaceRead, OffWithCommentsColoursAndHeaderCounts) {
  std::string text =
      "OFF # a comment\n"
      "# another\n"
      "4 2 0\n"
      "0 0 0 255 0 0\n1 0 0\n\n0 1 0\n0.1 0.2 3e-1\n"
      "3 0 1 2 9 9 9\n"
      "4 0 1 2 3\n";
  auto s = io::parse_off(text, "mem");
  ASSERT_EQ(s.points.size(), 4u);
  EXPECT_EQ(s.points[3], mesh::Vec3(0.1, 0.2, 0.3));
  EXPECT_EQ(s.polygons[0], (std::vector<std::int64_t>{0, 1, 2}));
  EXPECT_EQ(s.polygons[1].size(), 4u); // kept as a quad: the checker names it
}

TEST(SurfaceRead, ObjCornerSyntaxAndNegativeIndices) {
  std::string text = "# obj\nv 0 0 0\nv 1 0 0\nvn 0 0 1\nv 0 1 0\nf 1/1/1 2//1 3\nf -3 -2 -1\ng x\n";
  auto s = io::parse_obj(text, "mem");
  ASSERT_EQ(s.points.size(), 3u);
  ASSERT_EQ(s.polygons.size(), 2u);
  EXPECT_EQ(s.polygons[0], (std::vector<std::int64_t>{0, 1, 2}));
  EXPECT_EQ(s.polygons[1], (std::vector<std::int64_t>{0, 1, 2}));
}

TEST(SurfaceRead, BigEndianPlyWithExtraPropertiesAndElements) {
  std::string bytes =
      "ply\nformat binary_big_endian 1.0\ncomment hand made\n"
      "element vertex 3\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\n"
      "element face 1\nproperty list uchar int vertex_indices\nproperty short flags\n"
      "element extra 1\nproperty double w\nend_header\n";
  auto put = [&](const void* p, std::size_t n) {
    const char* c = static_cast<const char*>(p);
    for (std::size_t i = 0; i < n; ++i) bytes.push_back(c[n - 1 - i]); // little -> big (x86)
  };
  float coords[3][3] = {{0.f, 0.f, 0.f}, {1.5f, 0.f, 0.f}, {0.f, -2.25f, 0.f}};
  for (auto& v : coords) {
    for (float x : v) put(&x, 4);
    bytes.push_back(char(200));
  }
  bytes.push_back(3);
  for (std::int32_t i : {0, 1, 2}) put(&i, 4);
  std::int16_t flags = 5;
  put(&flags, 2);
  double w = 1;
  put(&w, 8);
  auto s = io::parse_ply(bytes, "mem");
  ASSERT_EQ(s.points.size(), 3u);
  EXPECT_EQ(s.points[2], mesh::Vec3(0, -2.25, 0));
  EXPECT_EQ(s.polygons[0], (std::vector<std::int64_t>{0, 1, 2}));
}

TEST(SurfaceRead, AsciiPlyVertexIndexName) {
  std::string text =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
      "element face 1\nproperty list uchar uint vertex_index\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 2 1 0\n";
  auto s = io::parse_ply(text, "mem");
  EXPECT_EQ(s.polygons[0], (std::vector<std::int64_t>{2, 1, 0}));
}

TEST(SurfaceRead, BadFilesAreUnreadableWithLocation) {
  auto expect_unreadable = [](auto fn, const std::string& text) {
    try {
      fn(text, "bad.file");
      ADD_FAILURE() << "no error for: " << text;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), exit_code(InputDefect::unreadable));
      EXPECT_NE(std::string(e.what()).find("bad.file"), std::string::npos);
    }
  };
  expect_unreadable(io::parse_off, "OFF\n3 1 0\n0 0 0\n1 0\n");
  expect_unreadable(io::parse_off, "PLY\n");
  expect_unreadable(io::parse_obj, "v 0 0 zero\n");
  expect_unreadable(io::parse_ply, "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nend_header\n1\n");
  expect_unreadable(io::parse_stl, "not an stl at all");
  EXPECT_THROW(io::read_surface("/nonexistent/file.off"), Error);
  EXPECT_THROW(io::read_surface("mesh.xyz"), Error);
}

TEST(AtomicFile, NoPartialOutputOnFailure) {
  auto path = (temp_dir() / "never.off").string();
  {
    io::AtomicFile f(path);
    f.stream() << "OFF\n";
    // destroyed without commit(): as if an exception unwound
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_FALSE(fs::exists(path + ".partial"));
}

// Findings of scripts/fuzz.sh (issue 27): counts from the file must not size
// allocations beyond what the file holds, nor turn NaN into a size.
TEST(SurfaceRead, CountsLargerThanTheFileAreRejectedNotAllocated) {
  using io::SurfaceFormat;
  EXPECT_THROW(io::parse_surface("OFF\n333333332 6333313331336738 34\n", SurfaceFormat::off, "x.off"), Error);
  EXPECT_THROW(io::parse_surface("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n900000000000 0 1 2\n", SurfaceFormat::off, "x.off"),
               Error);
  const std::string ply_header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                 "property float z\nelement face ";
  EXPECT_THROW(io::parse_surface(ply_header + "99999999999999\nproperty list uchar int vertex_indices\nend_header\n",
                                 SurfaceFormat::ply, "x.ply"),
               Error);
  EXPECT_THROW(io::parse_surface(ply_header + "1\nproperty list float int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
                                              "1e300 0 1 2\n",
                                 SurfaceFormat::ply, "x.ply"),
               Error);
  // An index beyond int64 (3e42) or fractional is an error, not a conversion.
  for (const char* face : {"3 0 1 3e42\n", "3 0 1 1.5\n", "3 0 1 nan\n"})
    EXPECT_THROW(io::parse_surface(ply_header + "1\nproperty list uchar float vertex_indices\nend_header\n0 0 0\n1 0 0\n"
                                                "0 1 0\n" + face,
                                   SurfaceFormat::ply, "x.ply"),
                 Error)
        << face;
}
