// The whole pipeline with the curved middle (issues 7-8) on a small sphere: the result is certified (every tet positive by the Bézier
// certificate, conforming, exact boundary checks), within epsilon, its
// boundary is curved (degree P-1 middle), and it is coarser than the same
// pipeline with a flat middle.
#include "../shell/tiny_meshes.hpp"

#include "curvetet/pipeline/pipeline.hpp"

#include <gtest/gtest.h>


using namespace curvetet;

namespace {

pipeline::PipelineResult run(const mesh::SurfaceMesh& input, bool curved, Report& report) {
  pipeline::PipelineOptions o;
  o.order = 4;
  o.epsilon = 0.01;
  o.curved_middle = curved;
  return pipeline::run_pipeline(input, o, report);
}

} // namespace

TEST(PipelineCurved, CertifiedCoarserThanFlat) {
  const auto input = shell::test::sphere(4);
  Report curved_report, flat_report;
  const auto curved = run(input, true, curved_report);
  const auto flat = run(input, false, flat_report);
  for (const auto* r : {&curved, &flat}) {
    const auto& v = r->verification;
    EXPECT_TRUE(v.ok());
    EXPECT_EQ(v.positive, static_cast<std::size_t>(r->mesh.num_tets()));
    EXPECT_TRUE(v.conformity_ok());
    EXPECT_TRUE(v.distance_ok());
  }
  EXPECT_EQ(curved.shell.middle_degree, 3);
  EXPECT_EQ(curved.mesh.order, 4);
  EXPECT_LT(curved.mesh.num_boundary(), flat.mesh.num_boundary());
  EXPECT_LT(curved.verification.input_to_boundary_max, 0.01);
}
