#pragma once
// The vertex map file written by `curvetet shell` (and later by the full
// pipeline): where each input vertex lands on a triangle mesh.
//
// Layout (text, one record per line, ids 0-based, doubles with 17 digits):
//   # curvetet vertex map v1
//   # <free comment lines starting with '#'>
//   vertices N
//   <face> <u> <v>          (N lines: line i is input vertex i)
// The point is (1-u-v)*P[F[face][0]] + u*P[F[face][1]] + v*P[F[face][2]]
// on the target mesh (P, F) named in the comments.
#include <string>
#include <vector>

namespace curvetet::io {

struct VertexMapRecord {
  int face = -1;
  double u = 0, v = 0;
};

// Written atomically (AtomicFile); throws Error(ExitCode::io) on failure.
void write_vertex_map(const std::string& path, const std::vector<VertexMapRecord>& records,
                      const std::vector<std::string>& comments = {});

// Reads the file back (for tests and tools); throws Error(ExitCode::io).
std::vector<VertexMapRecord> read_vertex_map(const std::string& path);

} // namespace curvetet::io
