#pragma once
// Surface writers (OFF, OBJ, PLY ASCII/binary, STL ASCII/binary), written
// through AtomicFile (core/atomic_file.hpp).
//
// Text formats print doubles with 17 significant digits: reading them back
// gives the same bits. STL stores 32-bit floats: exact only for coordinates
// that are floats.
#include "curvetet/core/atomic_file.hpp"
#include "curvetet/io/read_surface.hpp"
#include "curvetet/mesh/surface_mesh.hpp"

#include <fstream>
#include <string>

namespace curvetet::io {

using curvetet::AtomicFile;

struct SurfaceWriteOptions {
  bool binary = false; // PLY and STL only
};

void write_surface(const std::string& path, const mesh::SurfaceMesh& mesh, SurfaceWriteOptions options = {});
void write_surface(const std::string& path, const mesh::SurfaceMesh& mesh, SurfaceFormat format,
                   SurfaceWriteOptions options);

} // namespace curvetet::io
