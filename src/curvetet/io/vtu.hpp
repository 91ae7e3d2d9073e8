#pragma once
// VTK XML UnstructuredGrid (.vtu) output of a curved tet mesh, for ParaView.
//
// Cells: every tet as VTK_LAGRANGE_TETRAHEDRON (71) and, if requested, every
// boundary triangle as VTK_LAGRANGE_TRIANGLE (69), nodes permuted from the
// internal (Gmsh) order to VTK's (highorder/node_ordering.hpp). Data arrays
// are "binary": base64 of (UInt64 byte count + little-endian raw values),
// inline. Per-cell fields (one value per tet) are written as Float64 arrays;
// boundary triangles get NaN in them, plus an Int32 "cell_dimension" field.
// Written through AtomicFile.
#include "curvetet/mesh/tet_mesh.hpp"

#include <string>
#include <vector>

namespace curvetet::io {

struct CellField {
  std::string name;
  std::vector<double> per_tet;
};

void write_vtu(const std::string& path, const mesh::TetMesh& mesh, const std::vector<CellField>& fields = {},
               bool include_boundary = true);

// Base64 (RFC 4648, with padding) of raw bytes; exposed for tests.
std::string base64(const void* data, std::size_t size);

} // namespace curvetet::io
