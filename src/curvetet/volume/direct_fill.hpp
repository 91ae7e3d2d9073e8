#pragma once
// The fast path of the fill, tried before the offset layer and the BSP
// insertion of fill_layered(): when the Delaunay tetrahedralization of the
// surface's own vertices (plus, outward, the box points) already has every
// surface triangle as one of its faces, its tets on the wanted side of the
// surface (winding number) tetrahedralize that side exactly, with no Steiner
// point at all; only the AMIPS optimization (flips, interior splits) is left.
// On most CAD surfaces this holds: their vertices are spread evenly over
// flat or gently curved faces (docs/dt_conformity.md). Output contract: the
// one of fill_layered() (fill.hpp).
#include "curvetet/mesh/linear_tet_mesh.hpp"
#include "curvetet/mesh/surface_mesh.hpp"
#include "curvetet/volume/fill.hpp"
#include "curvetet/volume/layered_surface.hpp"

#include <optional>

namespace curvetet::volume {

// nullopt when some surface triangle is not a Delaunay face (the caller then
// takes the layered path); `stats` is only written on success.
std::optional<mesh::LinearTetMesh> fill_direct(const mesh::SurfaceMesh& surface, OffsetSide side,
                                               const FillOptions& options = {}, FillStats* stats = nullptr);

} // namespace curvetet::volume
