#include "curvetet/shell/build.hpp"

#include "curvetet/core/log.hpp"
#include "curvetet/mesh/edge_topology.hpp"
#include "curvetet/shell/invariants.hpp"
#include "curvetet/shell/layer_growth.hpp"
#include "curvetet/shell/projection.hpp"

#include "curvetet/core/error.hpp"

#include <algorithm>
#include <chrono>
#include <limits>

namespace curvetet::shell {

namespace {

using clock_type = std::chrono::steady_clock;
double since(clock_type::time_point t) { return std::chrono::duration<double>(clock_type::now() - t).count(); }

// Input vertex i -> the first middle face around it, at its corner.
void map_input_vertices(Shell& s) {
  const int n = s.input.num_vertices();
  const auto vf = mesh::build_vertex_faces(s.num_vertices(), s.faces);
  s.points.resize(n);
  for (int i = 0; i < n; ++i) {
    auto& p = s.points[i];
    p.position = s.input.vertices[i];
    const int f = vf.faces[vf.offsets[i]];
    p.image.prism = f;
    const auto& t = s.faces[f];
    p.image.u = t[1] == i ? 1.0 : 0.0;
    p.image.v = t[2] == i ? 1.0 : 0.0;
    // The input face: the one this middle face lies in.
    p.input_face = s.tracked[f].front();
  }
}

void fill_stats(const Shell& s, const std::vector<double>& length, ShellBuildStats& st) {
  st.min_pillar = st.min_thickness = std::numeric_limits<double>::infinity();
  double sum_p = 0, sum_t = 0;
  int count = 0;
  for (int v = 0; v < s.num_vertices(); ++v) {
    if (s.singular[v]) continue;
    const double thick = (s.top[v] - s.bottom[v]).norm();
    st.min_pillar = std::min(st.min_pillar, length[v]);
    st.max_pillar = std::max(st.max_pillar, length[v]);
    st.min_thickness = std::min(st.min_thickness, thick);
    st.max_thickness = std::max(st.max_thickness, thick);
    sum_p += length[v];
    sum_t += thick;
    st.vertices_at_target += length[v] >= st.target_pillar;
    ++count;
  }
  if (count == 0) st.min_pillar = st.min_thickness = 0;
  st.mean_pillar = count ? sum_p / count : 0;
  st.mean_thickness = count ? sum_t / count : 0;
}

// Barycentric coordinates of x projected on the plane of (a, b, c).
std::array<double, 3> barycentric_of(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const double area = n.squaredNorm();
  if (!(area > 0)) return {-1, -1, -1};
  const double lb = n.dot((x - a).cross(c - a)) / area, lc = n.dot((b - a).cross(x - a)) / area;
  return {1 - lb - lc, lb, lc};
}

} // namespace

void add_constraint_points(Shell& s, const std::vector<Vec3>& positions, const std::vector<Tri>& near) {
  const auto vf = mesh::build_vertex_faces(s.input.num_vertices(), s.input.faces);
  const Projector projector(s);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    TrackedPoint p;
    p.position = positions[i];
    double best = -std::numeric_limits<double>::infinity();
    for (int v : near[i])
      for (int k = vf.offsets[v]; k < vf.offsets[v + 1]; ++k) {
        const int t = vf.faces[k];
        const auto tri = straight_triangle(s, t);
        const auto l = barycentric_of(p.position, tri[0], tri[1], tri[2]);
        const double depth = std::min({l[0], l[1], l[2]});
        if (depth > best) {
          best = depth;
          p.input_face = t;
          // Clamped into the face: the point lies on it up to rounding.
          const std::array<double, 3> c{std::max(l[0], 0.0), std::max(l[1], 0.0), std::max(l[2], 0.0)};
          const double sum = c[0] + c[1] + c[2];
          p.barycentric = {c[0] / sum, c[1] / sum, c[2] / sum};
        }
      }
    if (p.input_face < 0) throw Error(ExitCode::internal, "constraint point beside no input face");
    s.points.push_back(p);
    s.points.back().image = projector.project(straight_point(s, static_cast<int>(s.points.size()) - 1), p.input_face);
  }
}

ShellBuild build_shell(const mesh::SurfaceMesh& input, const ShellOptions& options) {
  const auto start = clock_type::now();
  ShellBuild out;
  auto& st = out.stats;
  auto& s = out.shell;
  st.input_vertices = input.num_vertices();
  st.input_faces = input.num_faces();
  const auto& eo = options.extrusion;

  auto t = clock_type::now();
  auto iso = isolate_singularities(input, eo.singular_dot);
  st.seconds_isolation = since(t);
  st.split_edges = iso.split_edges;
  if (iso.split_edges) logger().info("shell: split {} edges between adjacent singular vertices", iso.split_edges);

  s.input = input;
  s.middle = iso.mesh.vertices;
  s.faces = iso.mesh.faces;
  s.tracked.resize(s.faces.size());
  for (int f = 0; f < s.num_prisms(); ++f) s.tracked[f] = {iso.origin_face[f]};
  s.singular.resize(s.num_vertices());
  LayerGrowthSpec spec;
  spec.direction.resize(s.num_vertices());
  for (int v = 0; v < s.num_vertices(); ++v) {
    s.singular[v] = iso.directions[v].singular;
    spec.direction[v] = iso.directions[v].direction;
    st.singular_vertices += s.singular[v];
  }
  const double diag = mesh::bbox_diagonal(input.vertices);
  spec.target = absolute_length(eo.target_thickness, eo.target_thickness_abs, diag);
  spec.initial = std::min(spec.target, eo.initial_thickness * diag);
  spec.max_rounds = eo.max_rounds;
  st.target_pillar = spec.target;
  if (options.debug_invariants) spec.after_stage = [](const Shell& sh, std::string_view stage) { require_valid_shell(sh, stage); };

  std::vector<double> length;
  const auto g = grow_layer(s, spec, length);
  st.initial_halvings = g.initial_halvings;
  st.rounds = g.rounds;
  st.reverts = g.reverts;
  st.seconds_initial = g.seconds_initial;
  st.seconds_thickening = g.seconds_rounds;

  t = clock_type::now();
  map_input_vertices(s);
  st.seconds_map = since(t);
  fill_stats(s, length, st);
  st.seconds_total = since(start);
  return out;
}

} // namespace curvetet::shell
