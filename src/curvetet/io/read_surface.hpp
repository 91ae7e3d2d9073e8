#pragma once
// Surface readers: OFF, OBJ, STL (ASCII and binary), PLY (ASCII and binary,
// either endianness). Coordinates are kept bit-exact (decimal text is parsed
// correctly rounded; binary floats widen exactly to double). Nothing is
// merged, reordered or repaired -- with one necessary exception: STL has no
// shared vertices, so corners with bit-identical coordinates become one
// vertex, numbered in order of first appearance.
//
// Polygons are returned as they are (any corner count, any index); the
// check module reports what is wrong with them. A file that cannot be parsed
// throws Error(InputDefect::unreadable) naming the file and line/offset.
#include "curvetet/mesh/surface_mesh.hpp"

#include <string>
#include <string_view>

namespace curvetet::io {

enum class SurfaceFormat { off, obj, stl, ply };

// By extension (case-insensitive); throws Error(unreadable) if unknown.
SurfaceFormat format_from_path(const std::string& path);

mesh::PolygonSoup read_surface(const std::string& path);
mesh::PolygonSoup parse_surface(std::string_view bytes, SurfaceFormat format, const std::string& name);

mesh::PolygonSoup parse_off(std::string_view bytes, const std::string& name);
mesh::PolygonSoup parse_obj(std::string_view bytes, const std::string& name);
mesh::PolygonSoup parse_stl(std::string_view bytes, const std::string& name);
mesh::PolygonSoup parse_ply(std::string_view bytes, const std::string& name);

} // namespace curvetet::io
