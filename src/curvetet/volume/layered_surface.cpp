#include "curvetet/volume/layered_surface.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/geometry/predicates.hpp"
#include "curvetet/shell/prism_tets.hpp"

#include <fmt/format.h>

namespace curvetet::volume {

std::vector<LayerTet> layer_tets(const LayeredSurface& s, std::vector<int>* face_of) {
  if (face_of) face_of->clear();
  const int n = s.surface.num_vertices();
  if (static_cast<int>(s.offset.size()) != n)
    throw Error(ExitCode::internal, "layer_tets: offset has the wrong size");
  auto pos = [&](int id) -> const mesh::Vec3& { return id < n ? s.surface.vertices[id] : s.offset[id - n]; };
  const bool inward = s.side == OffsetSide::inward;

  std::vector<LayerTet> out;
  out.reserve(3 * s.surface.faces.size());
  for (int f = 0; f < s.surface.num_faces(); ++f) {
    const auto& t = s.surface.faces[f];
    // The slab's lower corners are the ones the face's normal points away
    // from: the offset inward, the surface outward (shell/prism_tets.hpp).
    std::array<int, 6> corner;
    for (int k = 0; k < 3; ++k) {
      corner[inward ? k : k + 3] = offset_id(s, t[k]);
      corner[inward ? k + 3 : k] = t[k];
    }
    for (const auto& st : shell::canonical_split(t)) {
      LayerTet tet;
      for (int i = 0; i < 4; ++i) tet[i] = corner[st.corners[i]];
      if (tet[0] == tet[1] || tet[0] == tet[2] || tet[0] == tet[3] || tet[1] == tet[2] || tet[1] == tet[3] ||
          tet[2] == tet[3])
        continue; // contains a pinched pillar
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
