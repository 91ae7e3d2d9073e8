#pragma once
// Per-vertex attribute tables for `curvetet transfer`: CSV or PLY vertex
// properties (chosen by the extension, .csv or .ply, any case).
//
// CSV: a header line of comma-separated column names, then one line per
// vertex of comma-separated numbers (row i = vertex i). PLY (ASCII or
// binary, either endianness): every scalar property of element "vertex"
// (list properties and other elements are skipped). In both, columns named
// x, y, z are the position (kept apart in `positions`, not attributes).
// Written PLY is ASCII: x y z as double, attributes as double, labels as int,
// plus element "face" when faces are given. Written through AtomicFile.
#include "curvetet/mesh/surface_mesh.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace curvetet::io {

struct VertexTable {
  std::vector<std::string> names;  // attribute columns
  std::vector<char> is_label;      // per column: a label (integer id), else a quantity
  Eigen::MatrixXd values;          // rows = vertices, cols = names.size()
  std::vector<mesh::Vec3> positions; // empty when the file has no x, y, z
};

// Labels are the columns named in `labels` (absent names are an error);
// throws Error(ExitCode::io) on unreadable or malformed files.
VertexTable read_vertex_table(const std::string& path, const std::vector<std::string>& labels = {});

// `positions` (if not empty) and `faces` (PLY only) must match the rows.
void write_vertex_table(const std::string& path, const VertexTable& table, const std::vector<mesh::Tri>& faces = {});

} // namespace curvetet::io
