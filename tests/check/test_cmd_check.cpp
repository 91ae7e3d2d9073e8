// `curvetet check` end to end: a valid mesh file exits 0 and its JSON says
// valid; an inverted one exits with ExitCode::verification and names the tet.
#include "curvetet/core/error.hpp"
#include "curvetet/io/msh.hpp"
#include "curvetet/io/write_surface.hpp"

#include "common/curved_box.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <sys/wait.h>

using namespace curvetet;

namespace {

struct Run {
  int code;
  std::string out;
};

Run run(const std::string& args) {
  const std::string cmd = std::string(CURVETET_BINARY) + " " + args + " 2>/dev/null";
  FILE* p = popen(cmd.c_str(), "r");
  Run r{-1, ""};
  std::array<char, 4096> buf;
  while (std::size_t n = fread(buf.data(), 1, buf.size(), p)) r.out.append(buf.data(), n);
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::string temp(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / "curvetet_cmd_check";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

} // namespace

TEST(CmdCheck, ValidMeshExitsZero) {
  auto m = curvetet::testing::curved_box(3, 2, 0.3);
  const auto path = temp("valid.msh");
  io::write_msh(path, m, io::MshFormat::v41_binary);
  // The input surface: the box's boundary corners (a coarse stand-in).
  mesh::SurfaceMesh input;
  input.vertices = m.nodes;
  for (int b = 0; b < m.num_boundary(); ++b)
    input.faces.push_back({m.boundary_triangle(b)[0], m.boundary_triangle(b)[1], m.boundary_triangle(b)[2]});
  const auto in_path = temp("input.off");
  io::write_surface(in_path, input);
  auto r = run("check " + path + " --json --input " + in_path + " --epsilon 0.05 --vtu " + temp("valid.vtu"));
  ASSERT_EQ(r.code, 0) << r.out;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["check"]["valid"].get<bool>());
  EXPECT_EQ(j["check"]["positivity"]["positive"].get<int>(), m.num_tets());
  EXPECT_TRUE(j["check"]["distance"]["ok"].get<bool>());
  EXPECT_TRUE(std::filesystem::exists(temp("valid.vtu")));
}

TEST(CmdCheck, InvertedMeshFailsWithVerificationCode) {
  auto m = curvetet::testing::curved_box(2, 1, 0.2);
  m.nodes[m.tet(3)[4]] += Eigen::Vector3d(2, -2, 2); // an edge node far out
  const auto path = temp("inverted.msh");
  io::write_msh(path, m, io::MshFormat::v22_ascii);
  auto r = run("check " + path);
  EXPECT_EQ(r.code, static_cast<int>(ExitCode::verification)) << r.out;
  EXPECT_NE(r.out.find("INVALID"), std::string::npos) << r.out;
}

TEST(CmdCheck, UnreadableFileIsAnIoError) {
  const auto path = temp("garbage.msh");
  { std::ofstream(path) << "not a mesh"; }
  EXPECT_EQ(run("check " + path).code, static_cast<int>(ExitCode::io));
}
