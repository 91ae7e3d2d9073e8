#pragma once
// Assembly of the output on the middle surface (the default for an interior
// mesh): a boundary-preserving fill of a flat surface S, plus the parts of
// the bottom slabs that lie between S and the curved middle surface, raised
// to order P.
//
// S has one vertex per shell vertex: on the middle surface, or, where the
// vertex is "retracted", on the bottom surface B. With nothing retracted S
// is the flat middle surface and there is no slab at all, so no thin layer
// is built in; with everything retracted S = B and this is the paper's
// assembly (fill inside B + every bottom slab). In between, a face with some
// corners retracted keeps the tets of its slab whose pillar is retracted
// (the others have no volume).
//
// Nodes: every node of a boundary face (edges included) on that face's
// curved middle patch; every other node starts straight and then takes the
// discrete harmonic extension of the boundary's displacement, so a sagging
// face bends the tets beside it over their whole height.
//
// Positivity is not guaranteed: a patch sagging into a tet deeper than the
// tet is tall inverts it: assemble_on_middle() certifies every tet,
// retracts the corners of the tets that fail, and assembles again.
#include "curvetet/mesh/linear_tet_mesh.hpp"
#include "curvetet/mesh/surface_mesh.hpp"
#include "curvetet/mesh/tet_mesh.hpp"
#include "curvetet/volume/assemble.hpp"

#include <nlohmann/json.hpp>

#include <vector>

namespace curvetet::volume {

// The flat surface S: vertex v on the bottom surface where retracted[v],
// else at the corner of the middle patches; the shell's faces.
mesh::SurfaceMesh retracted_surface(const CurvedMiddle& shell, const std::vector<char>& retracted);

// `fill` tetrahedralizes the inside of retracted_surface(shell, retracted):
// its vertices [0, n) are that surface's (same ids, same positions), its
// boundary faces exactly the shell's faces. Boundary triangle i of the
// result is shell face i. stats: fill_tets, slab_tets, boundary_triangles.
// Singular vertices are never retracted (their pillar has no length).
mesh::TetMesh assemble_retracted(const CurvedMiddle& shell, const std::vector<char>& retracted,
                                 const mesh::LinearTetMesh& fill, int order, AssemblyStats* stats = nullptr);

// The interior on the middle surface: assembled with nothing retracted,
// then, while some tet is not certified positive, again with the surface
// corners of those tets retracted. Fills with fill_direct() (with interior
// grid points, else without), else with the layered fill of
// tetrahedralize(). Returns false, and `out` is not to be used, when no fill
// verifies or a round retracts nothing new while tets still fail (the
// caller then takes assemble_curved_mesh()).
// `report`: rounds, retracted vertices, tets, or why it failed.
bool assemble_on_middle(const CurvedMiddle& shell, int order, mesh::TetMesh& out, nlohmann::json& report);

} // namespace curvetet::volume
