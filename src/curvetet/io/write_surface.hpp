#pragma once
// Surface writers (OFF, OBJ, PLY ASCII/binary, STL ASCII/binary) and the
// atomic-file helper every writer uses: output goes to "<path>.partial" and is
// renamed into place only once complete, so a failed run leaves no partial
// output file.
//
// Text formats print doubles with 17 significant digits: reading them back
// gives the same bits. STL stores 32-bit floats: exact only for coordinates
// that are floats.
#include "curvetet/io/read_surface.hpp"
#include "curvetet/mesh/surface_mesh.hpp"

#include <fstream>
#include <string>

namespace curvetet::io {

class AtomicFile {
 public:
  explicit AtomicFile(std::string path, bool binary = false);
  ~AtomicFile(); // removes the partial file unless commit() ran
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ofstream& stream() { return out_; }
  // Flushes, checks for errors and renames into place; throws Error(io).
  void commit();

 private:
  std::string path_, partial_;
  std::ofstream out_;
  bool committed_ = false;
};

struct SurfaceWriteOptions {
  bool binary = false; // PLY and STL only
};

void write_surface(const std::string& path, const mesh::SurfaceMesh& mesh, SurfaceWriteOptions options = {});
void write_surface(const std::string& path, const mesh::SurfaceMesh& mesh, SurfaceFormat format,
                   SurfaceWriteOptions options);

} // namespace curvetet::io
