#pragma once
// Gmsh-generated cube / ball tet meshes for the fem tests, written once per
// test process into a temporary folder by make_gmsh_mesh.py (Debian's
// /usr/bin/python3 with python3-gmsh).
#include "curvetet/io/msh.hpp"
#include "curvetet/mesh/tet_mesh.hpp"

#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <map>
#include <string>
#include <unistd.h>

namespace curvetet::test {

inline bool python_gmsh_available() {
  static const bool available = std::system("/usr/bin/python3 -c 'import gmsh' > /dev/null 2>&1") == 0;
  return available;
}

// The per-process folder of generated meshes, removed at exit.
struct GeneratedMeshFolder {
  std::filesystem::path path =
      std::filesystem::temp_directory_path() / fmt::format("curvetet_fem_tests_{}", ::getpid());
  GeneratedMeshFolder() { std::filesystem::create_directories(path); }
  ~GeneratedMeshFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

// Path of the mesh of `shape` ("cube" = [0,1]^3, "ball" = unit ball) with
// size h and element order; empty when generation failed.
inline std::string gmsh_mesh_path(const std::string& shape, double h, int order) {
  static std::map<std::string, std::string> cache;
  std::string key = fmt::format("{}_h{}_p{}", shape, h, order);
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  static const GeneratedMeshFolder folder;
  std::string path = (folder.path / (key + ".msh")).string();
  std::string cmd = fmt::format("/usr/bin/python3 '{}/tests/fem/make_gmsh_mesh.py' {} {} {} '{}' > /dev/null 2>&1",
                                CURVETET_SOURCE_DIR, shape, h, order, path);
  if (std::system(cmd.c_str()) != 0) path.clear();
  cache[key] = path;
  return path;
}

inline mesh::TetMesh gmsh_mesh(const std::string& shape, double h, int order) {
  return io::read_msh(gmsh_mesh_path(shape, h, order));
}

} // namespace curvetet::test
