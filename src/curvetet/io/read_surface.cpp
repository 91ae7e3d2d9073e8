#include "curvetet/io/read_surface.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/io/text_cursor.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace curvetet::io {

SurfaceFormat format_from_path(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".off") return SurfaceFormat::off;
  if (ext == ".obj") return SurfaceFormat::obj;
  if (ext == ".stl") return SurfaceFormat::stl;
  if (ext == ".ply") return SurfaceFormat::ply;
  throw Error(InputDefect::unreadable,
              "'" + path + "': unknown surface format '" + ext + "' (expected .off, .obj, .stl or .ply)");
}

mesh::PolygonSoup parse_surface(std::string_view bytes, SurfaceFormat format, const std::string& name) {
  switch (format) {
    case SurfaceFormat::off: return parse_off(bytes, name);
    case SurfaceFormat::obj: return parse_obj(bytes, name);
    case SurfaceFormat::stl: return parse_stl(bytes, name);
    case SurfaceFormat::ply: return parse_ply(bytes, name);
  }
  throw Error(InputDefect::unreadable, name + ": unknown format");
}

mesh::PolygonSoup read_surface(const std::string& path) {
  auto format = format_from_path(path);
  std::string bytes = read_file_bytes(path);
  return parse_surface(bytes, format, path);
}

} // namespace curvetet::io
