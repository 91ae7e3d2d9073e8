#include "curvetet/volume/verify.hpp"

#include "curvetet/geometry/predicates.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <unordered_map>

namespace curvetet::volume {
namespace {
// Rotates a triangle so its smallest id comes first (keeps the cyclic order).
mesh::Tri canonical(mesh::Tri t) {
  while (t[0] > t[1] || t[0] > t[2]) t = {t[1], t[2], t[0]};
  return t;
}
mesh::Tri flipped(const mesh::Tri& t) { return canonical({t[0], t[2], t[1]}); }
struct TriHash {
  std::size_t operator()(const mesh::Tri& t) const {
    return (static_cast<std::size_t>(t[0]) * 73856093u) ^ (static_cast<std::size_t>(t[1]) * 19349663u) ^
           (static_cast<std::size_t>(t[2]) * 83492791u);
  }
};
} // namespace

std::string TetMeshCheck::text() const {
  return fmt::format("{} non-positive tets, {} over-used faces, {} missing and {} extra boundary faces, volume {}",
                     non_positive, overused_faces, missing_boundary, extra_boundary, volume);
}

TetMeshCheck verify_tet_mesh(const mesh::LinearTetMesh& m, const std::vector<mesh::Tri>& expected_boundary,
                             std::optional<Box> box) {
  TetMeshCheck r;
  const auto& p = m.vertices;
  // outward faces of each tet, counted by oriented canonical form
  std::unordered_map<mesh::Tri, int, TriHash> count;
  count.reserve(4 * m.tets.size());
  for (const auto& t : m.tets) {
    if (geometry::orient3d(p[t[0]], p[t[1]], p[t[2]], p[t[3]]) <= 0) ++r.non_positive;
    r.volume += (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).dot(p[t[3]] - p[t[0]]) / 6.0;
    for (const mesh::Tri& f : {mesh::Tri{t[0], t[2], t[1]}, mesh::Tri{t[0], t[1], t[3]}, mesh::Tri{t[0], t[3], t[2]},
                               mesh::Tri{t[1], t[2], t[3]}})
      ++count[canonical(f)];
  }
  std::unordered_map<mesh::Tri, int, TriHash> expected;
  for (const auto& f : expected_boundary) ++expected[canonical(f)];
  for (const auto& [f, c] : count) {
    if (c > 1) {
      ++r.overused_faces;
      continue;
    }
    const auto it = count.find(flipped(f));
    const bool paired = it != count.end();
    if (paired) continue; // interior face, seen from both sides
    if (expected.count(f)) continue;
    bool on_box = false;
    if (box)
      for (int k = 0; k < 3 && !on_box; ++k)
        for (double side : {box->lo[k], box->hi[k]})
          if (p[f[0]][k] == side && p[f[1]][k] == side && p[f[2]][k] == side) on_box = true;
    if (!on_box) ++r.extra_boundary;
  }
  for (const auto& [f, c] : expected) {
    const auto it = count.find(f);
    if (c != 1 || it == count.end() || count.count(flipped(f))) ++r.missing_boundary;
  }
  return r;
}

} // namespace curvetet::volume
