#pragma once
// Gmsh MSH files for curved tet meshes (mesh/tet_mesh.hpp).
//
// Writing: MSH 4.1 (ASCII or binary, little-endian as the host) and MSH 2.2
// ASCII. Tets of order 1..8 become Gmsh types 4/11/29/30/31/71/72/73, boundary
// triangles of the same order types 2/9/21/23/25/42/43/44, lines (feature
// curves) types 1/8/26/27/28/62/63/64 on one curve entity per line tag (no
// bounding points; their nodes stay on the surfaces). Node order is a
// plain copy (curvetet's internal order is Gmsh's). Entities: one surface
// per distinct boundary tag and one volume per distinct tet tag (physical
// group = the tag; names from mesh.groups, set_default_groups: "boundary" =
// 2D tag 1, "domain" = 3D tag 2); a node belongs to the first entity using it,
// surfaces first. Node tags are 1-based and contiguous; element tags are the
// element's position (boundary triangles first, then tets, then lines), and the reader
// restores that order. Coordinates are
// written with 17 significant digits (bit-exact round trip). Every file goes
// through AtomicFile.
//
// Reading: MSH 4.1 (ASCII/binary) and 2.2 (ASCII). Keeps tetrahedra and
// triangles of the supported complete Lagrange types (all of one order,
// else Error(io)); other elements (points, lines) are skipped. Triangles
// become `boundary` with their physical tag; tets keep theirs. Node tags are
// renumbered 0..n-1 in file order; nodes not used by a kept element are kept.
#include "curvetet/mesh/tet_mesh.hpp"

#include <string>
#include <string_view>

namespace curvetet::io {

enum class MshFormat { v41_ascii, v41_binary, v22_ascii };

void write_msh(const std::string& path, const mesh::TetMesh& mesh, MshFormat format = MshFormat::v41_ascii);

// Throws Error(ExitCode::io) naming the file and what is wrong.
mesh::TetMesh read_msh(const std::string& path);
mesh::TetMesh parse_msh(std::string_view bytes, const std::string& name);

} // namespace curvetet::io
