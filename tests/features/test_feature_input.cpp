#include "curvetet/core/error.hpp"
#include "curvetet/features/detect.hpp"
#include "curvetet/features/feature_input.hpp"
#include "curvetet/io/features_json.hpp"
#include "support/shapes.hpp"

#include <gtest/gtest.h>

using namespace curvetet;

namespace {
features::FeatureInput parse_and_validate(const std::string& json, io::FeatureSet set = io::FeatureSet::all) {
  auto m = test::cube();
  auto topo = mesh::build_edge_topology(m.faces);
  auto f = io::parse_features(json, set, "mem.json");
  features::validate_and_normalize(f, m, topo);
  return f;
}

void expect_bad(const std::string& json, const std::string& needle) {
  try {
    parse_and_validate(json);
    ADD_FAILURE() << "accepted: " << json;
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), exit_code(InputDefect::bad_features));
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}
} // namespace

TEST(FeatureFile, ReadsEveryPartAndIgnoresUnknownKeys) {
  auto f = parse_and_validate(
      R"({"edges": [[1,0],[0,2]], "corners": [7, 0, 7], "points": {"faces": [3], "barycentric": [[0.1,0.2,0.7]]},
          "comment": "ignored"})");
  EXPECT_EQ(f.edges, (std::vector<std::array<int, 2>>{{0, 1}, {0, 2}}));
  EXPECT_EQ(f.corners, (std::vector<int>{0, 7}));
  ASSERT_EQ(f.points.faces.size(), 1u);
  EXPECT_NEAR(f.points.barycentric[0][2], 0.7, 1e-15);
}

TEST(FeatureFile, SharpSetReadsSharpKeys) {
  auto f = parse_and_validate(R"({"edges": [[0,1],[0,2]], "sharp_edges": [[0,4]], "sharp_corners": [4]})",
                              io::FeatureSet::sharp);
  EXPECT_EQ(f.edges, (std::vector<std::array<int, 2>>{{0, 4}}));
  EXPECT_EQ(f.corners, (std::vector<int>{4}));
}

TEST(FeatureFile, RejectsWhatDoesNotFitTheMesh) {
  expect_bad(R"({"edges": [[0,7]]})", "not edges of the mesh");          // cube diagonal
  expect_bad(R"({"edges": [[0,8]]})", "out of range");
  expect_bad(R"({"corners": [-1]})", "corners out of range");
  expect_bad(R"({"points": {"faces": [12], "barycentric": [[1,0,0]]}})", "face id out of range");
  expect_bad(R"({"points": {"faces": [0], "barycentric": [[0.5,0.6,-0.1]]}})", "barycentrics");
  expect_bad(R"({"points": {"faces": [0], "barycentric": [[0.5,0.6,0.1]]}})", "barycentrics");
  expect_bad(R"({"points": {"faces": [0, 1], "barycentric": [[1,0,0]]}})", "2 faces but 1");
  expect_bad(R"({"edges": [[0,1]],)", "malformed");
  expect_bad(R"({"edges": "none"})", "malformed");
  // Fuzz findings (issue 27): numbers no int holds are errors, not conversions.
  expect_bad(R"({"corners": [2e62]})", "malformed");
  expect_bad(R"({"edges": [[0, 99999999999999999999]]})", "malformed");
  expect_bad(R"({"points": {"faces": [-9999999999]}})", "malformed");
  expect_bad(R"({"edges": [[0, 1, 2]]})", "malformed");
}

TEST(FeatureDetection, CubeEdgesAreFeaturesDiagonalsAreNot) {
  auto m = test::cube();
  auto topo = mesh::build_edge_topology(m.faces);
  auto edges = features::detect_feature_edges(m, topo, 30.0);
  EXPECT_EQ(edges.size(), 12u); // the 12 cube edges; the 6 face diagonals are flat
  EXPECT_TRUE(features::detect_feature_edges(m, topo, 100.0).empty());
}
