// Gmsh reads curvetet's curved meshes (orders 2, 3, 4; MSH 4.1 ASCII and
// binary, MSH 2.2) with the same element maps and agrees with the
// certificate on validity; meshio reads the MSH and VTU files
// (tests/io/gmsh_crosscheck.py). Skipped only if python3-gmsh is missing.
//
// A wrong node-ordering table makes this fail: checked by hand once by
// swapping two edge nodes of the order-3 tet in gmsh_node_tables.inc.
#include "curvetet/highorder/element_map.hpp"
#include "curvetet/highorder/jacobian_certificate.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/io/msh.hpp"
#include "curvetet/io/vtu.hpp"

#include "common/curved_box.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>

using namespace curvetet;

namespace {

bool python_gmsh_available() {
  return std::system("/usr/bin/python3 -c 'import gmsh, meshio, numpy' > /dev/null 2>&1") == 0;
}

// Appends a disjoint single tet (order p) at offset, returns its first tet index.
void add_single_tet(mesh::TetMesh& m, const Eigen::Vector3d& offset, bool invalid) {
  const int p = m.order;
  const int first = static_cast<int>(m.nodes.size());
  for (int i = 0; i < highorder::tet_node_count(p); ++i) {
    auto q = highorder::tet_node(p, i);
    Eigen::Vector3d x(q[0], q[1], q[2]);
    x /= p;
    x += 0.05 * Eigen::Vector3d(std::sin(3 * x.y()), std::sin(3 * x.z()), std::sin(3 * x.x()));
    m.nodes.push_back(offset + x);
    m.tets.push_back(first + i);
  }
  if (invalid) m.nodes[first + 4] = offset + Eigen::Vector3d(0.7, 0.9, 0.9); // edge 0-1 node across face 123
  for (int f = 0; f < 4; ++f)
    for (int n : highorder::tet_face_nodes(p, f)) m.boundary.push_back(first + n);
  m.tet_tags.push_back(mesh::kDomainTag);
  for (int f = 0; f < 4; ++f) m.boundary_tags.push_back(mesh::kBoundaryTag);
}

} // namespace

class GmshCrossCheck : public ::testing::TestWithParam<int> {};

TEST_P(GmshCrossCheck, GmshAndMeshioReadOurFiles) {
  if (!python_gmsh_available()) GTEST_SKIP() << "python3-gmsh / meshio not installed";
  const int order = GetParam();
  auto m = curvetet::testing::curved_box(order, 2, 0.3);
  add_single_tet(m, Eigen::Vector3d(3, 0, 0), false);
  add_single_tet(m, Eigen::Vector3d(5, 0, 0), true);

  // Reference points: random interior points plus the corners.
  std::mt19937 rng(order);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Eigen::Vector3d> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  while (points.size() < 24) {
    Eigen::Vector3d x(u(rng), u(rng), u(rng));
    if (x.sum() < 1) points.push_back(x);
  }
  nlohmann::json s;
  s["order"] = order;
  s["num_nodes"] = m.nodes.size();
  for (const auto& p : points) s["points"].push_back({p.x(), p.y(), p.z()});
  int invalid = 0;
  for (int t = 0; t < m.num_tets(); ++t) {
    std::vector<Eigen::Vector3d> nodes;
    for (int i = 0; i < m.tet_nodes(); ++i) nodes.push_back(m.nodes[m.tet(t)[i]]);
    nlohmann::json e;
    for (const auto& p : points) {
      auto x = highorder::tet_point(order, nodes.data(), p);
      e["coords"].push_back({x.x(), x.y(), x.z()});
    }
    const bool valid = highorder::certify_tet(order, nodes.data()).validity == highorder::Validity::positive;
    invalid += !valid;
    e["valid"] = valid;
    // MSH element tags: boundary triangles first, then tets.
    s["tets"][std::to_string(m.num_boundary() + t + 1)] = e;
  }
  ASSERT_EQ(invalid, 1) << "the fixture should have exactly one invalid tet";

  auto dir = std::filesystem::temp_directory_path() / ("curvetet_gmsh_" + std::to_string(order));
  std::filesystem::create_directories(dir);
  const std::pair<io::MshFormat, const char*> formats[] = {
      {io::MshFormat::v41_ascii, "v41.msh"}, {io::MshFormat::v41_binary, "v41b.msh"}, {io::MshFormat::v22_ascii, "v22.msh"}};
  for (const auto& [format, name] : formats) {
    auto path = (dir / name).string();
    io::write_msh(path, m, format);
    s["msh"].push_back(path);
  }
  auto vtu = (dir / "mesh.vtu").string();
  io::write_vtu(vtu, m, {{"order", std::vector<double>(m.num_tets(), order)}});
  s["vtu"].push_back(vtu);
  auto json_path = (dir / "samples.json").string();
  std::ofstream(json_path) << s.dump();

  const std::string cmd = "/usr/bin/python3 " CURVETET_SOURCE_DIR "/tests/io/gmsh_crosscheck.py " + json_path;
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
}

INSTANTIATE_TEST_SUITE_P(Orders, GmshCrossCheck, ::testing::Values(2, 3, 4));

// The checked-in node table is what Gmsh says (tools/gen_gmsh_node_tables.py).
TEST(GmshNodeTable, MatchesGmshGetElementProperties) {
  if (!python_gmsh_available()) GTEST_SKIP() << "python3-gmsh not installed";
  const std::string cmd =
      "/usr/bin/python3 " CURVETET_SOURCE_DIR "/tools/gen_gmsh_node_tables.py --check > /dev/null";
  EXPECT_EQ(std::system(cmd.c_str()), 0);
}
