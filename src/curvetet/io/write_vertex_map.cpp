#include "curvetet/io/write_vertex_map.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/io/write_surface.hpp"

#include <fmt/format.h>

#include <fstream>
#include <sstream>

namespace curvetet::io {

void write_vertex_map(const std::string& path, const std::vector<VertexMapRecord>& records,
                      const std::vector<std::string>& comments) {
  AtomicFile file(path);
  auto& out = file.stream();
  out << "# curvetet vertex map v1\n";
  for (const auto& c : comments) out << "# " << c << '\n';
  out << "vertices " << records.size() << '\n';
  for (const auto& r : records) out << fmt::format("{} {:.17g} {:.17g}\n", r.face, r.u, r.v);
  file.commit();
}

std::vector<VertexMapRecord> read_vertex_map(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(ExitCode::io, "cannot read vertex map " + path);
  std::string line;
  std::vector<VertexMapRecord> out;
  long long expected = -1;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ls(line);
    if (expected < 0) {
      std::string word;
      if (!(ls >> word >> expected) || word != "vertices" || expected < 0)
        throw Error(ExitCode::io, path + ": expected 'vertices N'");
      continue;
    }
    VertexMapRecord r;
    if (!(ls >> r.face >> r.u >> r.v)) throw Error(ExitCode::io, path + ": bad record: " + line);
    out.push_back(r);
  }
  if (expected < 0 || static_cast<long long>(out.size()) != expected)
    throw Error(ExitCode::io, fmt::format("{}: {} records, header says {}", path, out.size(), expected));
  return out;
}

} // namespace curvetet::io
