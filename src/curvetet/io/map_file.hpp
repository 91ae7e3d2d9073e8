#pragma once
// Reading and writing the map file (mesh/boundary_map.hpp) in its two
// layouts, binary and JSON, both described in docs/map_format.md. Writers go
// through AtomicFile; readers validate every count and index and throw
// Error(ExitCode::io) naming the file and the defect.
#include "curvetet/mesh/boundary_map.hpp"

#include <string>
#include <string_view>

namespace curvetet::io {

enum class MapFormat { binary, json };

// JSON when the path ends in ".json" (any case), binary otherwise.
MapFormat map_format_for(const std::string& path);

void write_map(const std::string& path, const mesh::BoundaryMap& map, MapFormat format);
inline void write_map(const std::string& path, const mesh::BoundaryMap& map) {
  write_map(path, map, map_format_for(path));
}

// Either layout (told apart by the binary magic); `name` is for messages.
mesh::BoundaryMap read_map(const std::string& path);
mesh::BoundaryMap parse_map(std::string_view bytes, const std::string& name);

// Throws Error(io) unless every count and index of `map` is consistent.
void validate_map(const mesh::BoundaryMap& map, const std::string& name);

} // namespace curvetet::io
