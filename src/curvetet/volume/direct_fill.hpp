#pragma once
// The fast path of the fill, tried before the offset layer and the BSP
// insertion of fill_layered(): the Delaunay tetrahedralization of the
// surface's own vertices (plus, outward, the box points). Where it has every
// surface triangle as a face, its tets on the wanted side of the surface
// (winding number) tetrahedralize that side exactly, with no Steiner point;
// on most CAD surfaces it has (docs/dt_conformity.md). Elsewhere, flips
// recover most missing triangles (face_recovery.hpp) and cones from interior
// Steiner points fill the cavities around the rest (cavity_fill.hpp). Then
// the AMIPS optimization (flips, interior insertions) runs as usual.
// Output contract: the one of fill_layered() (fill.hpp); the caller verifies
// it (tetrahedralize() falls back to the layered fill if it does not hold).
#include "curvetet/mesh/linear_tet_mesh.hpp"
#include "curvetet/mesh/surface_mesh.hpp"
#include "curvetet/volume/fill.hpp"
#include "curvetet/volume/layered_surface.hpp"

#include <functional>
#include <optional>

namespace curvetet::volume {

// nullopt when some cavity cannot be filled by cones (the caller then takes
// the layered path); `stats` is only written on success. `on_scan_like` is
// called when the surface's own Delaunay tetrahedralization lacks many of
// its triangles (over 1 %, as on scans: where the layered path, when it is
// needed, is), before the longer part of the work.
std::optional<mesh::LinearTetMesh> fill_direct(const mesh::SurfaceMesh& surface, OffsetSide side,
                                               const FillOptions& options = {}, FillStats* stats = nullptr,
                                               const std::function<void()>& on_scan_like = {});

} // namespace curvetet::volume
