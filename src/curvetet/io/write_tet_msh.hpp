#pragma once
// Linear tet mesh writer: Gmsh MSH 4.1 ASCII. One volume entity per tag
// (tags > 0; physical group = tag), element type 4 (4-node tet, Gmsh's node
// order = ours: positive tets are positive for Gmsh). Doubles are printed
// with 17 significant digits, so reading back gives the same bits. Written
// through AtomicFile (no partial output on failure).
#include "curvetet/mesh/tet_mesh.hpp"

#include <string>

namespace curvetet::io {

void write_tet_msh(const std::string& path, const mesh::TetMesh& mesh);

} // namespace curvetet::io
