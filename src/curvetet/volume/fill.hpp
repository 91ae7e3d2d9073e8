#pragma once
// Boundary-preserving tetrahedralization (paper §4.3; DESIGN.md §5).
//
// fill_layered() fills the region behind (side inward: the solid) or in front
// of (side outward: between the surface and a box) a closed surface whose
// offset is given, without any Steiner point on the surface:
//   2. Delaunay of the offset vertices + 8 box corners, exact BSP insertion of
//      the offset triangles (rational coordinates), keep the cells on the
//      wanted side of the offset surface (winding number);
//   3-4. fill every layer prism surface→offset with its 3 tets, refining the
//      tets that touch a refined offset face or edge so everything conforms;
//   5. round vertices to doubles where every incident tet stays positive, and
//      optimize AMIPS energy (smooth, collapse, flip) with the surface and box
//      frozen; unrounded vertices are removed or moved until none is left.
// Output contract (verified exactly by verify_fill, volume/verify.hpp):
// vertices [0, n) are the surface vertices, bit for bit; every tet is positive
// by exact orient3d on the output doubles; the boundary faces are exactly the
// surface faces (inward: same orientation; outward: reversed) plus, outward,
// the box; every other face has exactly two tets.
// Throws Error(internal) if the offset breaks LayeredSurface's contract or a
// vertex cannot be rounded (never seen; it would be a bug).
#include "curvetet/mesh/linear_tet_mesh.hpp"
#include "curvetet/volume/layered_surface.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <cstddef>
#include <string>

namespace curvetet::volume {

struct FillOptions {
  double box_margin = 0.1; // outward: the box grows the bbox by this × diagonal on each side
  int optimize_rounds = 4; // AMIPS rounds (0: rounding only)
  // 0: a collapse or 3-2 flip must not raise its star's largest AMIPS energy
  // (best quality). > 0: it may, up to this energy, so the fill ends with
  // fewer tets (the pipeline's fill, whose tets the curved optimization
  // improves afterwards).
  double coarsen_energy = 0;
  // > 0: collapses and edge removals create no edge longer than this
  // (absolute), so the interior is as fine as the surface asks for.
  double max_edge_length = 0;
  // > 0 (fill_direct, inward): the points of a grid of this spacing
  // (absolute) that are at least half of it from the surface join the
  // surface's vertices, so the interior is no coarser than the grid.
  double interior_spacing = 0;
};

// Why the fill's optimizer turned a collapse, flip or edge removal down,
// each a named check (volume/exact_optimizer.hpp), in the order they run:
//   frozen             the vertex to remove is on the surface or the box
//   topology           not an edge, or not a closed ring of the right size
//   duplicate_entity   the new tets would repeat an existing edge or face
//   link_condition     lk(u) ∩ lk(v) != lk(uv) (the boundary closed at infinity)
//   energy             a new tet above the coarsening bound
//   frozen_tet_energy  a new tet on frozen vertices only above its limit
//   sizing             a new edge longer than FillOptions::max_edge_length
//   no_gain            the new worst tet not below the old one (where asked)
//   positivity         a new tet not positive by exact orient3d
enum class FillReject { frozen, topology, duplicate_entity, link_condition, energy, frozen_tet_energy, sizing, no_gain, positivity };
constexpr int kFillRejectReasons = 9;
const char* to_string(FillReject r);

struct FillStats {
  std::size_t background_tets = 0, bsp_cuts = 0, bsp_cells = 0;
  std::size_t exact_tets = 0, exact_vertices = 0, rational_vertices = 0;
  std::size_t unrounded_after_first_pass = 0;
  std::size_t collapses = 0, smooths = 0, flips = 0, splits = 0, relocations = 0;
  std::array<std::size_t, kFillRejectReasons> rejected{}; // by FillReject
  nlohmann::json rejected_json() const; // reason -> count
  double seconds_insert = 0, seconds_layer = 0, seconds_optimize = 0;
  // Of the output's tets, in highorder/quality.hpp's convention (AMIPS of
  // the regular tet: 3, kReportedAmipsPerEnergy x the fill's own energy,
  // tet_amips.hpp; scaled Jacobian of the regular tet: 1).
  double max_amips = 0, mean_amips = 0, min_scaled_jacobian = 0;
  bool direct = false; // filled by fill_direct() (no layer, no BSP)
  // fill_direct(): the offset points added to the surface's vertices (0 on
  // most CAD surfaces), the surface triangles that were then not Delaunay
  // faces, how many of those flips recovered, and the cones (interior
  // Steiner points) that stand in for the rest.
  std::size_t offset_points = 0, missing_triangles = 0, recovered_by_flips = 0, cones = 0;
};

mesh::LinearTetMesh fill_layered(const LayeredSurface& s, const FillOptions& options = {}, FillStats* stats = nullptr);

} // namespace curvetet::volume
