#include "curvetet/core/error.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/io/vtu.hpp"
#include "curvetet/io/write_surface.hpp"

#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace curvetet::io {

std::string base64(const void* data, std::size_t size) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* b = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < size; i += 3) {
    const std::uint32_t v = (b[i] << 16) | (b[i + 1] << 8) | b[i + 2];
    out += kAlphabet[v >> 18 & 63];
    out += kAlphabet[v >> 12 & 63];
    out += kAlphabet[v >> 6 & 63];
    out += kAlphabet[v & 63];
  }
  if (i < size) {
    std::uint32_t v = b[i] << 16;
    if (i + 1 < size) v |= b[i + 1] << 8;
    out += kAlphabet[v >> 18 & 63];
    out += kAlphabet[v >> 12 & 63];
    out += i + 1 < size ? kAlphabet[v >> 6 & 63] : '=';
    out += '=';
  }
  return out;
}

namespace {

static_assert(std::endian::native == std::endian::little, "VTU writer assumes a little-endian host");

// One binary data array: header (UInt64 payload size) + payload, base64 encoded.
template <class T>
std::string encoded(const std::vector<T>& values) {
  const std::uint64_t bytes = values.size() * sizeof(T);
  std::string raw(sizeof bytes + bytes, '\0');
  std::memcpy(raw.data(), &bytes, sizeof bytes);
  if (bytes) std::memcpy(raw.data() + sizeof bytes, values.data(), bytes);
  return base64(raw.data(), raw.size());
}

template <class T>
void data_array(std::ostream& o, const char* type, const std::string& name, int components, const std::vector<T>& v) {
  o << "        <DataArray type=\"" << type << "\" Name=\"" << name << "\"";
  if (components > 1) o << " NumberOfComponents=\"" << components << "\"";
  o << " format=\"binary\">\n          " << encoded(v) << "\n        </DataArray>\n";
}

} // namespace

void write_vtu(const std::string& path, const mesh::TetMesh& m, const std::vector<CellField>& fields,
               bool include_boundary) {
  if (m.order < 1 || m.order > highorder::kMaxOrder)
    throw Error(ExitCode::internal, fmt::format("write_vtu: order {} not supported", m.order));
  for (const auto& f : fields)
    if (static_cast<int>(f.per_tet.size()) != m.num_tets())
      throw Error(ExitCode::internal, "write_vtu: field '" + f.name + "' needs one value per tet");
  const auto& tet_perm = highorder::vtk_tet_permutation(m.order);
  const auto& tri_perm = highorder::vtk_triangle_permutation(m.order);
  const int num_tris = include_boundary ? m.num_boundary() : 0;
  const int num_cells = m.num_tets() + num_tris;

  std::vector<double> points;
  points.reserve(3 * m.nodes.size());
  for (const auto& p : m.nodes) points.insert(points.end(), {p.x(), p.y(), p.z()});
  std::vector<std::int64_t> connectivity, offsets;
  std::vector<std::uint8_t> types;
  std::vector<std::int32_t> dims;
  for (int t = 0; t < m.num_tets(); ++t) {
    for (int k : tet_perm) connectivity.push_back(m.tet(t)[k]);
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    types.push_back(71);
    dims.push_back(3);
  }
  for (int b = 0; b < num_tris; ++b) {
    for (int k : tri_perm) connectivity.push_back(m.boundary_triangle(b)[k]);
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    types.push_back(69);
    dims.push_back(2);
  }

  AtomicFile file(path);
  auto& o = file.stream();
  o << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
    << "  <UnstructuredGrid>\n"
    << "    <Piece NumberOfPoints=\"" << m.nodes.size() << "\" NumberOfCells=\"" << num_cells << "\">\n"
    << "      <Points>\n";
  data_array(o, "Float64", "Points", 3, points);
  o << "      </Points>\n      <Cells>\n";
  data_array(o, "Int64", "connectivity", 1, connectivity);
  data_array(o, "Int64", "offsets", 1, offsets);
  data_array(o, "UInt8", "types", 1, types);
  o << "      </Cells>\n      <CellData>\n";
  data_array(o, "Int32", "cell_dimension", 1, dims);
  for (const auto& f : fields) {
    std::vector<double> v = f.per_tet;
    v.resize(num_cells, std::numeric_limits<double>::quiet_NaN());
    data_array(o, "Float64", f.name, 1, v);
  }
  o << "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  file.commit();
}

} // namespace curvetet::io
