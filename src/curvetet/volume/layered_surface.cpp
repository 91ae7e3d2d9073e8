#include "curvetet/volume/layered_surface.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/geometry/predicates.hpp"

#include <algorithm>
#include <fmt/format.h>

namespace curvetet::volume {

std::vector<LayerTet> layer_tets(const LayeredSurface& s, std::vector<int>* face_of) {
  if (face_of) face_of->clear();
  const int n = s.surface.num_vertices();
  if (static_cast<int>(s.offset.size()) != n)
    throw Error(ExitCode::internal, "layer_tets: offset has the wrong size");
  auto pos = [&](int id) -> const mesh::Vec3& { return id < n ? s.surface.vertices[id] : s.offset[id - n]; };
  const int side = s.side == OffsetSide::inward ? 1 : -1;

  std::vector<LayerTet> out;
  out.reserve(3 * s.surface.faces.size());
  for (int f = 0; f < s.surface.num_faces(); ++f) {
    auto t = s.surface.faces[f];
    std::array<int, 3> v = t;
    std::sort(v.begin(), v.end());
    // sigma = +1 when (a, b, c) has the face's cyclic order.
    const bool cyclic = (v[0] == t[0] && v[1] == t[1]) || (v[0] == t[1] && v[1] == t[2]) || (v[0] == t[2] && v[1] == t[0]);
    const int sigma = cyclic ? 1 : -1;
    const int a = v[0], b = v[1], c = v[2];
    const int a2 = offset_id(s, a), b2 = offset_id(s, b), c2 = offset_id(s, c);
    // Signs of the three tets in the limit of a short inward pillar are
    // -sigma, +sigma, -sigma (outward: the opposite).
    const std::array<LayerTet, 3> tets = {LayerTet{a, b, c, c2}, LayerTet{a, b, b2, c2}, LayerTet{a, a2, b2, c2}};
    const std::array<int, 3> expected = {-sigma * side, sigma * side, -sigma * side};
    for (int k = 0; k < 3; ++k) {
      LayerTet tet = tets[k];
      if (tet[0] == tet[1] || tet[0] == tet[2] || tet[0] == tet[3] || tet[1] == tet[2] || tet[1] == tet[3] ||
          tet[2] == tet[3])
        continue; // contains a pinched pillar
      if (expected[k] < 0) std::swap(tet[0], tet[1]);
      if (geometry::orient3d(pos(tet[0]), pos(tet[1]), pos(tet[2]), pos(tet[3])) <= 0)
        throw Error(ExitCode::internal,
                    fmt::format("volume: layer prism of face {} has a non-positive tet (invalid offset)", f));
      out.push_back(tet);
      if (face_of) face_of->push_back(f);
    }
  }
  return out;
}

} // namespace curvetet::volume
