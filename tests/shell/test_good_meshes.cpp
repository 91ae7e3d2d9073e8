// Real meshes from ../shared/data/good: the shell builds, the global checker
// passes, Π is the identity at input vertices and Π⁻¹(Π(p)) = p. A small
// subset keeps CI fast; CURVETET_SHELL_ALL_MESHES=1 runs every good mesh
// (and the default 20 rounds), as bench/shell_sweep.sh does for the CLI.
#include "curvetet/io/read_surface.hpp"
#include "curvetet/shell/build.hpp"
#include "curvetet/shell/invariants.hpp"
#include "curvetet/shell/projection.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>

using namespace curvetet;
using namespace curvetet::shell;

namespace {

bool all_meshes() { return std::getenv("CURVETET_SHELL_ALL_MESHES") != nullptr; }

std::vector<std::string> meshes() {
  if (!all_meshes())
    return {"thingi10k_288351.off", "couplingdown.off", "abc_00000001_forgescan.off", "spot.off", "bunny_libigl.off"};
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(std::string(CURVETET_SHARED_DATA) + "/good"))
    if (e.path().extension() == ".off") out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

class GoodMesh : public ::testing::TestWithParam<std::string> {};

TEST_P(GoodMesh, ShellIsValidAndTheMapRoundTrips) {
  const std::string path = std::string(CURVETET_SHARED_DATA) + "/good/" + GetParam();
  const auto input = mesh::to_surface_mesh(io::read_surface(path));
  ShellOptions o;
  if (!all_meshes()) o.extrusion.max_rounds = 10; // CI time
  o.debug_invariants = true;   // global check after each stage (throws)
  const auto b = build_shell(input, o);
  const Shell& s = b.shell;
  const auto violations = check_shell(s);
  EXPECT_TRUE(violations.empty()) << violations.size() << " violations, first: "
                                  << to_string(violations.front().kind) << " prism " << violations.front().prism;
  EXPECT_GT(b.stats.min_thickness, 0);
  EXPECT_EQ(static_cast<int>(s.points.size()), input.num_vertices());

  const Projector pi(s);
  for (int i = 0; i < input.num_vertices(); ++i) {
    const auto& p = s.points[i];
    ASSERT_LT((pi.middle_point(p.image) - input.vertices[i]).norm(), 1e-12) << "vertex " << i;
    const MapPoint m = pi.project(input.vertices[i], p.input_face);
    ASSERT_LT((pi.middle_point(m) - input.vertices[i]).norm(), 1e-12) << "vertex " << i;
    const auto back = pi.unproject(m);
    ASSERT_TRUE(back.has_value()) << "vertex " << i;
    ASSERT_LT((*back - input.vertices[i]).norm(), 1e-12) << "vertex " << i;
  }
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(0, 1);
  std::uniform_int_distribution<int> F(0, input.num_faces() - 1);
  for (int k = 0; k < 2000; ++k) {
    const int f = F(rng);
    double a = U(rng), c = U(rng);
    if (a + c > 1) a = 1 - a, c = 1 - c;
    const auto& t = input.faces[f];
    const Vec3 p = (1 - a - c) * input.vertices[t[0]] + a * input.vertices[t[1]] + c * input.vertices[t[2]];
    const auto back = pi.unproject(pi.project(p, f));
    ASSERT_TRUE(back.has_value()) << "face " << f;
    ASSERT_LT((*back - p).norm(), 1e-12) << "face " << f;
  }
}

INSTANTIATE_TEST_SUITE_P(Data, GoodMesh,
                         ::testing::ValuesIn(meshes()),
                         [](const auto& info) {
                           std::string n = info.param.substr(0, info.param.find('.'));
                           for (auto& ch : n)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n;
                         });

} // namespace
