// MSH 4.1 (ASCII, binary) and 2.2 round trips are bit-exact and keep
// connectivity and physical groups; VTU files are well-formed and hold the
// VTK-ordered connectivity; every writer leaves no partial file on failure.
#include "curvetet/core/error.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/io/msh.hpp"
#include "curvetet/io/text_cursor.hpp"
#include "curvetet/io/vtu.hpp"

#include "common/curved_box.hpp"

#include <gtest/gtest.h>

#include <filesystem>

using namespace curvetet;

namespace {

std::string temp_path(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / "curvetet_test_io";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

void expect_same(const mesh::TetMesh& a, const mesh::TetMesh& b) {
  ASSERT_EQ(a.order, b.order);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  // Node ids may be renumbered by the block layout; compare through coordinates.
  ASSERT_EQ(a.tets.size(), b.tets.size());
  for (std::size_t i = 0; i < a.tets.size(); ++i) ASSERT_EQ(a.nodes[a.tets[i]], b.nodes[b.tets[i]]) << i;
  ASSERT_EQ(a.boundary.size(), b.boundary.size());
  for (std::size_t i = 0; i < a.boundary.size(); ++i) ASSERT_EQ(a.nodes[a.boundary[i]], b.nodes[b.boundary[i]]);
  EXPECT_EQ(a.tet_tags, b.tet_tags);
  EXPECT_EQ(a.boundary_tags, b.boundary_tags);
  ASSERT_EQ(a.groups.size(), b.groups.size());
  for (std::size_t i = 0; i < a.groups.size(); ++i) {
    EXPECT_EQ(a.groups[i].name, b.groups[i].name);
    EXPECT_EQ(a.groups[i].tag, b.groups[i].tag);
    EXPECT_EQ(a.groups[i].dim, b.groups[i].dim);
  }
}

} // namespace

class MshRoundTrip : public ::testing::TestWithParam<std::tuple<int, io::MshFormat>> {};

TEST_P(MshRoundTrip, BitExact) {
  auto [order, format] = GetParam();
  auto m = curvetet::testing::curved_box(order, 2, 0.2);
  // Awkward coordinates: not short decimals.
  for (auto& p : m.nodes) p *= 1.0 / 3.0;
  // One file per case: ctest runs the cases in parallel processes.
  const std::string path =
      temp_path("round_trip_" + std::to_string(order) + "_" + std::to_string(static_cast<int>(format)) + ".msh");
  io::write_msh(path, m, format);
  auto back = io::read_msh(path);
  expect_same(m, back);
  EXPECT_FALSE(std::filesystem::exists(path + ".partial"));
}

INSTANTIATE_TEST_SUITE_P(OrdersAndFormats, MshRoundTrip,
                         ::testing::Combine(::testing::Values(1, 2, 3, 4, 6, 8),
                                            ::testing::Values(io::MshFormat::v41_ascii, io::MshFormat::v41_binary,
                                                              io::MshFormat::v22_ascii)));

TEST(Msh, RejectsGarbageAndMixedOrders) {
  EXPECT_THROW(io::parse_msh("hello", "x.msh"), Error);
  EXPECT_THROW(io::parse_msh("$MeshFormat\n3.0 0 8\n$EndMeshFormat\n", "x.msh"), Error);
  const char* mixed =
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n"
      "$Elements\n2\n1 4 2 0 1 1 2 3 4\n2 9 2 0 1 1 2 3 1 2 3\n$EndElements\n";
  EXPECT_THROW(io::parse_msh(mixed, "x.msh"), Error);
  const char* missing =
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n$EndNodes\n$Elements\n1\n1 4 2 0 1 1 2 3 4\n$EndElements\n";
  EXPECT_THROW(io::parse_msh(missing, "x.msh"), Error);
}

TEST(Msh, UnwritableDirectoryThrowsAndLeavesNothing) {
  auto m = curvetet::testing::curved_box(2, 1, 0.1);
  EXPECT_THROW(io::write_msh("/nonexistent-dir/x.msh", m), Error);
}

TEST(Vtu, Base64) {
  EXPECT_EQ(io::base64("", 0), "");
  EXPECT_EQ(io::base64("f", 1), "Zg==");
  EXPECT_EQ(io::base64("fo", 2), "Zm8=");
  EXPECT_EQ(io::base64("foo", 3), "Zm9v");
  EXPECT_EQ(io::base64("foobar", 6), "Zm9vYmFy");
}

TEST(Vtu, WritesLagrangeCellsAndFields) {
  auto m = curvetet::testing::curved_box(3, 1, 0.2);
  const std::string path = temp_path("mesh.vtu");
  std::vector<double> q(m.num_tets(), 0.5);
  io::write_vtu(path, m, {{"min_scaled_jacobian", q}});
  auto text = io::read_file_bytes(path);
  EXPECT_NE(text.find("NumberOfCells=\"" + std::to_string(m.num_tets() + m.num_boundary()) + "\""), std::string::npos);
  EXPECT_NE(text.find("Name=\"min_scaled_jacobian\""), std::string::npos);
  EXPECT_NE(text.find("header_type=\"UInt64\""), std::string::npos);
  // The types array: num_tets x 71 then num_boundary x 69, base64 of UInt64 size + bytes.
  std::vector<std::uint8_t> types(m.num_tets(), 71);
  types.resize(m.num_tets() + m.num_boundary(), 69);
  std::string raw(8 + types.size(), '\0');
  const std::uint64_t n = types.size();
  std::memcpy(raw.data(), &n, 8);
  std::memcpy(raw.data() + 8, types.data(), types.size());
  EXPECT_NE(text.find(io::base64(raw.data(), raw.size())), std::string::npos);
  EXPECT_THROW(io::write_vtu(path, m, {{"bad", {1.0}}}), Error);
}

// Several physical tags per dimension (e.g. `tetrahedralize --exterior`:
// interior and exterior regions) become one entity each and survive a round
// trip in every format, elements in their original order.
TEST(Msh, SeveralPhysicalTagsPerDimension) {
  auto m = curvetet::testing::curved_box(2, 2, 0.1);
  for (int t = 0; t < m.num_tets(); ++t) m.tet_tags[t] = t % 2 ? 7 : mesh::kDomainTag;
  for (int b = 0; b < m.num_boundary(); ++b) m.boundary_tags[b] = b % 3 ? mesh::kBoundaryTag : 9;
  m.groups.push_back({3, 7, "exterior"});
  m.groups.push_back({2, 9, "other"});
  for (auto format : {io::MshFormat::v41_ascii, io::MshFormat::v41_binary, io::MshFormat::v22_ascii}) {
    const std::string path = temp_path("tags.msh");
    io::write_msh(path, m, format);
    expect_same(m, io::read_msh(path));
  }
}

// A fuzz finding (issue 27): a node count near 2^64 sized a reservation
// (std::length_error). Now the file runs out first: a curvetet::Error.
TEST(Msh, HugeNodeCountIsAParseError) {
  const std::string msh = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n0 0 0 0\n$EndEntities\n$Nodes\n"
                          "1 18446744073709551000 1 18446744073709551000\n3 1 0 1\n";
  EXPECT_THROW(io::parse_msh(msh, "x.msh"), Error);
}

// A fuzz finding (issue 27): a block of an unsupported element type whose
// count exceeds the file skipped "lines" past its end for ~2^64 rounds.
TEST(Msh, UnsupportedBlockLongerThanTheFileIsAParseError) {
  const std::string msh = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Elements\n1 18446744073709551000 1 1\n"
                          "2 1 99 18446744073709551000\n1 1 2 3\n";
  EXPECT_THROW(io::parse_msh(msh, "x.msh"), Error);
}
