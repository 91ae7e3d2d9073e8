#include "curvetet/io/map_file.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/io/write_surface.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>

namespace curvetet::io {
namespace {

constexpr char kMagic[8] = {'C', 'T', 'E', 'T', 'M', 'A', 'P', '\0'};
constexpr std::uint32_t kVersion = 1;

[[noreturn]] void fail(const std::string& name, const std::string& what) {
  throw Error(ExitCode::io, fmt::format("{}: map file: {}", name, what));
}

// Little-endian scalars whatever the host.
template <class T>
void put(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) std::reverse(bytes, bytes + sizeof(T));
  out.append(bytes, sizeof(T));
}

class Reader {
 public:
  Reader(std::string_view bytes, const std::string& name) : bytes_(bytes), name_(name) {}
  template <class T>
  T get() {
    if (bytes_.size() - pos_ < sizeof(T)) fail(name_, "truncated");
    char b[sizeof(T)];
    std::memcpy(b, bytes_.data() + pos_, sizeof(T));
    if constexpr (std::endian::native == std::endian::big) std::reverse(b, b + sizeof(T));
    pos_ += sizeof(T);
    T value;
    std::memcpy(&value, b, sizeof(T));
    return value;
  }
  // A count followed by that many records of `record_bytes`: refuse counts
  // the remaining bytes cannot hold before allocating.
  std::size_t count(std::size_t record_bytes) {
    const auto n = get<std::uint64_t>();
    if (record_bytes > 0 && n > (bytes_.size() - pos_) / record_bytes) fail(name_, "count exceeds the file size");
    return static_cast<std::size_t>(n);
  }
  bool at_end() const { return pos_ == bytes_.size(); }

 private:
  std::string_view bytes_;
  std::string name_;
  std::size_t pos_ = 0;
};

std::string to_binary(const mesh::BoundaryMap& m) {
  std::string out(kMagic, sizeof(kMagic));
  put<std::uint32_t>(out, kVersion);
  put<std::int32_t>(out, m.order);
  put<std::uint64_t>(out, m.input.vertices.size());
  for (const auto& p : m.input.vertices)
    for (int d = 0; d < 3; ++d) put<double>(out, p[d]);
  put<std::uint64_t>(out, m.input.faces.size());
  for (const auto& f : m.input.faces)
    for (int k = 0; k < 3; ++k) put<std::int32_t>(out, f[k]);
  put<std::uint64_t>(out, m.nodes.size());
  for (std::size_t j = 0; j < m.nodes.size(); ++j) {
    for (int d = 0; d < 3; ++d) put<double>(out, m.nodes[j][d]);
    put<std::int32_t>(out, m.node_ids[j]);
  }
  put<std::uint64_t>(out, m.num_triangles());
  for (int id : m.triangles) put<std::int32_t>(out, id);
  auto points = [&](const std::vector<mesh::SurfacePoint>& ps) {
    for (const auto& p : ps) {
      put<std::int32_t>(out, p.face);
      put<double>(out, p.u);
      put<double>(out, p.v);
    }
  };
  points(m.vertex_to_boundary); // one per input vertex
  points(m.node_to_input);      // one per boundary node
  return out;
}

mesh::BoundaryMap from_binary(std::string_view bytes, const std::string& name) {
  Reader r(bytes.substr(sizeof(kMagic)), name);
  if (const auto v = r.get<std::uint32_t>(); v != kVersion) fail(name, fmt::format("unsupported version {}", v));
  mesh::BoundaryMap m;
  m.order = r.get<std::int32_t>();
  if (m.order < 1 || m.order > 8) fail(name, fmt::format("order {} outside 1..8", m.order));
  m.input.vertices.resize(r.count(24));
  for (auto& p : m.input.vertices)
    for (int d = 0; d < 3; ++d) p[d] = r.get<double>();
  m.input.faces.resize(r.count(12));
  for (auto& f : m.input.faces)
    for (int k = 0; k < 3; ++k) f[k] = r.get<std::int32_t>();
  const std::size_t nodes = r.count(28);
  m.nodes.resize(nodes);
  m.node_ids.resize(nodes);
  for (std::size_t j = 0; j < nodes; ++j) {
    for (int d = 0; d < 3; ++d) m.nodes[j][d] = r.get<double>();
    m.node_ids[j] = r.get<std::int32_t>();
  }
  m.triangles.resize(r.count(4 * static_cast<std::size_t>(m.triangle_nodes())) * m.triangle_nodes());
  for (int& id : m.triangles) id = r.get<std::int32_t>();
  auto points = [&](std::vector<mesh::SurfacePoint>& ps, std::size_t n) {
    ps.resize(n);
    for (auto& p : ps) {
      p.face = r.get<std::int32_t>();
      p.u = r.get<double>();
      p.v = r.get<double>();
    }
  };
  points(m.vertex_to_boundary, m.input.vertices.size());
  points(m.node_to_input, nodes);
  if (!r.at_end()) fail(name, "trailing bytes after the node records");
  return m;
}

nlohmann::json points_json(const std::vector<mesh::SurfacePoint>& ps) {
  auto a = nlohmann::json::array();
  for (const auto& p : ps) a.push_back({p.face, p.u, p.v});
  return a;
}

std::string to_json(const mesh::BoundaryMap& m) {
  nlohmann::json j;
  j["format"] = "curvetet map";
  j["version"] = kVersion;
  j["order"] = m.order;
  auto vertices = nlohmann::json::array(), nodes = nlohmann::json::array();
  for (const auto& p : m.input.vertices) vertices.push_back({p.x(), p.y(), p.z()});
  for (const auto& p : m.nodes) nodes.push_back({p.x(), p.y(), p.z()});
  j["input"] = {{"vertices", vertices}, {"faces", m.input.faces}};
  auto triangles = nlohmann::json::array();
  for (int b = 0; b < m.num_triangles(); ++b)
    triangles.push_back(std::vector<int>(m.triangle(b), m.triangle(b) + m.triangle_nodes()));
  j["boundary"] = {{"nodes", nodes}, {"node_ids", m.node_ids}, {"triangles", triangles}};
  j["vertex_to_boundary"] = points_json(m.vertex_to_boundary);
  j["node_to_input"] = points_json(m.node_to_input);
  return j.dump() + "\n";
}

mesh::BoundaryMap from_json(std::string_view text, const std::string& name) {
  mesh::BoundaryMap m;
  try {
    const auto j = nlohmann::json::parse(text);
    if (j.at("format") != "curvetet map") fail(name, "not a curvetet map");
    if (j.at("version") != kVersion) fail(name, "unsupported version");
    m.order = j.at("order").get<int>();
    if (m.order < 1 || m.order > 8) fail(name, fmt::format("order {} outside 1..8", m.order));
    for (const auto& p : j.at("input").at("vertices")) m.input.vertices.emplace_back(p.at(0), p.at(1), p.at(2));
    m.input.faces = j.at("input").at("faces").get<std::vector<mesh::Tri>>();
    const auto& b = j.at("boundary");
    for (const auto& p : b.at("nodes")) m.nodes.emplace_back(p.at(0), p.at(1), p.at(2));
    m.node_ids = b.at("node_ids").get<std::vector<int>>();
    for (const auto& t : b.at("triangles")) {
      const auto ids = t.get<std::vector<int>>();
      if (static_cast<int>(ids.size()) != m.triangle_nodes()) fail(name, "a triangle has the wrong node count");
      m.triangles.insert(m.triangles.end(), ids.begin(), ids.end());
    }
    auto points = [&](const nlohmann::json& a, std::vector<mesh::SurfacePoint>& ps) {
      for (const auto& p : a) ps.push_back({p.at(0).get<int>(), p.at(1).get<double>(), p.at(2).get<double>()});
    };
    points(j.at("vertex_to_boundary"), m.vertex_to_boundary);
    points(j.at("node_to_input"), m.node_to_input);
  } catch (const nlohmann::json::exception& e) {
    fail(name, e.what());
  }
  return m;
}

bool ends_with_json(const std::string& path) {
  if (path.size() < 5) return false;
  std::string tail = path.substr(path.size() - 5);
  std::transform(tail.begin(), tail.end(), tail.begin(), [](unsigned char c) { return std::tolower(c); });
  return tail == ".json";
}

} // namespace

MapFormat map_format_for(const std::string& path) { return ends_with_json(path) ? MapFormat::json : MapFormat::binary; }

void validate_map(const mesh::BoundaryMap& m, const std::string& name) {
  const auto nv = static_cast<long long>(m.input.vertices.size()), nf = static_cast<long long>(m.input.faces.size());
  const auto nn = static_cast<long long>(m.nodes.size());
  const int nb = m.num_triangles();
  if (m.order < 1 || m.order > 8) fail(name, fmt::format("order {} outside 1..8", m.order));
  if (m.triangles.size() % m.triangle_nodes() != 0) fail(name, "triangle array not a multiple of the node count");
  if (static_cast<long long>(m.node_ids.size()) != nn) fail(name, "node_ids and nodes differ in length");
  if (static_cast<long long>(m.vertex_to_boundary.size()) != nv) fail(name, "vertex_to_boundary needs one entry per input vertex");
  if (static_cast<long long>(m.node_to_input.size()) != nn) fail(name, "node_to_input needs one entry per boundary node");
  for (const auto& f : m.input.faces)
    for (int k : f)
      if (k < 0 || k >= nv) fail(name, fmt::format("input face refers to vertex {} of {}", k, nv));
  for (int id : m.triangles)
    if (id < 0 || id >= nn) fail(name, fmt::format("boundary triangle refers to node {} of {}", id, nn));
  auto check = [&](const std::vector<mesh::SurfacePoint>& ps, long long faces, const char* what) {
    for (const auto& p : ps)
      if (p.face < 0 || p.face >= faces || !std::isfinite(p.u) || !std::isfinite(p.v))
        fail(name, fmt::format("{} entry with face {} of {} or non-finite (u, v)", what, p.face, faces));
  };
  check(m.vertex_to_boundary, nb, "vertex_to_boundary");
  check(m.node_to_input, nf, "node_to_input");
}

void write_map(const std::string& path, const mesh::BoundaryMap& map, MapFormat format) {
  validate_map(map, path);
  AtomicFile file(path, format == MapFormat::binary);
  const std::string bytes = format == MapFormat::binary ? to_binary(map) : to_json(map);
  file.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  file.commit();
}

mesh::BoundaryMap parse_map(std::string_view bytes, const std::string& name) {
  const bool binary = bytes.size() >= sizeof(kMagic) && std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) == 0;
  auto m = binary ? from_binary(bytes, name) : from_json(bytes, name);
  validate_map(m, name);
  return m;
}

mesh::BoundaryMap read_map(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(ExitCode::io, "cannot read map file " + path);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return parse_map(bytes, path);
}

} // namespace curvetet::io
