#include "curvetet/features/feature_input.hpp"

#include "curvetet/core/error.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

namespace curvetet::features {
namespace {

// Collects "what: ids" lines, listing at most a few ids each.
struct Problems {
  std::vector<std::string> lines;
  void add(const std::string& what, const std::vector<long long>& ids) {
    if (ids.empty()) return;
    std::vector<long long> shown(ids.begin(), ids.begin() + std::min<std::size_t>(ids.size(), 10));
    lines.push_back(fmt::format("{} {}: {}{}", ids.size(), what, fmt::join(shown, ", "), ids.size() > 10 ? ", ..." : ""));
  }
};

} // namespace

void validate_and_normalize(FeatureInput& f, const mesh::SurfaceMesh& m, const mesh::EdgeTopology& topo) {
  const int nv = m.num_vertices(), nf = m.num_faces();
  Problems p;

  std::vector<long long> bad_index, not_edge;
  for (std::size_t i = 0; i < f.edges.size(); ++i) {
    auto& e = f.edges[i];
    if (e[0] < 0 || e[0] >= nv || e[1] < 0 || e[1] >= nv) {
      bad_index.push_back(static_cast<long long>(i));
      continue;
    }
    if (e[0] > e[1]) std::swap(e[0], e[1]);
    if (!std::binary_search(topo.edges.begin(), topo.edges.end(), e)) not_edge.push_back(static_cast<long long>(i));
  }
  p.add("feature edges with a vertex index out of range (edge entries)", bad_index);
  p.add("feature edges that are not edges of the mesh (edge entries)", not_edge);

  std::vector<long long> bad_corner;
  for (int c : f.corners)
    if (c < 0 || c >= nv) bad_corner.push_back(c);
  p.add("corners out of range (vertex ids)", bad_corner);

  auto& pts = f.points;
  if (pts.faces.size() != pts.barycentric.size())
    p.lines.push_back(fmt::format("points: {} faces but {} barycentric triples", pts.faces.size(), pts.barycentric.size()));
  std::vector<long long> bad_face, bad_bary;
  for (std::size_t i = 0; i < std::min(pts.faces.size(), pts.barycentric.size()); ++i) {
    if (pts.faces[i] < 0 || pts.faces[i] >= nf) bad_face.push_back(static_cast<long long>(i));
    auto& b = pts.barycentric[i];
    double sum = b[0] + b[1] + b[2];
    bool finite = std::isfinite(b[0]) && std::isfinite(b[1]) && std::isfinite(b[2]);
    if (!finite || b[0] < 0 || b[1] < 0 || b[2] < 0 || std::abs(sum - 1.0) > 1e-9) {
      bad_bary.push_back(static_cast<long long>(i));
      continue;
    }
    for (double& x : b) x /= sum;
  }
  p.add("points on a face id out of range (point entries)", bad_face);
  p.add("points with barycentrics negative or not summing to 1 (point entries)", bad_bary);

  if (!p.lines.empty())
    throw Error(InputDefect::bad_features, fmt::format("invalid feature file:\n  {}", fmt::join(p.lines, "\n  ")));

  std::sort(f.edges.begin(), f.edges.end());
  f.edges.erase(std::unique(f.edges.begin(), f.edges.end()), f.edges.end());
  std::sort(f.corners.begin(), f.corners.end());
  f.corners.erase(std::unique(f.corners.begin(), f.corners.end()), f.corners.end());
}

} // namespace curvetet::features
