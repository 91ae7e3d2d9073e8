#include "curvetet/core/error.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/io/msh.hpp"
#include "curvetet/io/text_cursor.hpp"

#include <fmt/format.h>

#include <algorithm>

#include <cctype>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <map>
#include <unordered_map>

namespace curvetet::io {

namespace {

// Cursor over a whole MSH file: text tokens and, in binary files, raw values.
class MshCursor {
 public:
  MshCursor(std::string_view bytes, const std::string& name) : s_(bytes), name_(name) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw Error(ExitCode::io, fmt::format("{}: MSH parse error near byte {}: {}", name_, pos_, what));
  }
  std::size_t size() const { return s_.size(); }
  bool at_end() {
    skip_space();
    return pos_ >= s_.size();
  }
  std::string_view token() {
    skip_space();
    std::size_t start = pos_;
    while (pos_ < s_.size() && !std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
    return s_.substr(start, pos_ - start);
  }
  std::string_view rest_of_line() {
    std::size_t start = pos_;
    while (pos_ < s_.size() && s_[pos_] != '\n') ++pos_;
    auto line = s_.substr(start, pos_ - start);
    if (pos_ < s_.size()) ++pos_;
    return line;
  }
  void skip_line_end() { // after text headers, before binary data
    while (pos_ < s_.size() && s_[pos_] != '\n') ++pos_;
    if (pos_ < s_.size()) ++pos_;
  }
  template <class T>
  T text() {
    auto t = token();
    T v{};
    if constexpr (std::is_floating_point_v<T>) {
      auto r = parse_real(t);
      if (!r) fail(fmt::format("expected a number, got '{}'", t));
      v = static_cast<T>(*r);
    } else {
      auto r = parse_integer(t);
      if (!r) fail(fmt::format("expected an integer, got '{}'", t));
      v = static_cast<T>(*r);
    }
    return v;
  }
  template <class T>
  T raw() {
    if (pos_ + sizeof(T) > s_.size()) fail("truncated binary data");
    T v;
    std::memcpy(&v, s_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  // Binary files: size_t/int/double raw; ASCII: text.
  template <class T, class Raw = T>
  T value(bool binary) {
    return binary ? static_cast<T>(raw<Raw>()) : text<T>();
  }
  void expect(std::string_view word) {
    auto t = token();
    if (t != word) fail(fmt::format("expected '{}', got '{}'", word, t));
  }
  void skip_section(std::string_view section) {
    const std::string end = "$End" + std::string(section.substr(1));
    auto at = s_.find(end, pos_);
    if (at == std::string_view::npos) fail("missing " + end);
    pos_ = at + end.size();
  }

 private:
  void skip_space() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  std::string_view s_;
  std::string name_;
  std::size_t pos_ = 0;
};

// Nodes per element for the types we may meet (complete Lagrange points,
// lines, triangles, tets); 0 if unknown.
int nodes_of_type(int type) {
  if (int p = highorder::gmsh_triangle_order(type)) return highorder::triangle_node_count(p);
  if (int p = highorder::gmsh_tet_order(type)) return highorder::tet_node_count(p);
  switch (type) {
    case 15: return 1;
    case 1: return 2;
    case 8: return 3;
    case 26: return 4;
    case 27: return 5;
    case 28: return 6;
    case 62: return 7;
    case 63: return 8;
    case 64: return 9;
    default: return 0;
  }
}

struct Raw {
  std::vector<std::int64_t> node_tags;
  std::vector<Eigen::Vector3d> coords;
  struct Element {
    int type, physical;
    std::vector<std::int64_t> nodes;
    std::int64_t tag = 0; // element tag: elements are kept in tag order
  };
  std::vector<Element> elements;
  std::vector<mesh::PhysicalGroup> groups;
};

void read_physical_names(MshCursor& c, Raw& raw) {
  const int n = c.text<int>();
  c.skip_line_end();
  for (int i = 0; i < n; ++i) {
    auto line = c.rest_of_line();
    MshCursor lc(line, "PhysicalNames");
    mesh::PhysicalGroup g;
    g.dim = lc.text<int>();
    g.tag = lc.text<int>();
    auto q0 = line.find('"'), q1 = line.rfind('"');
    if (q0 != std::string_view::npos && q1 > q0) g.name = std::string(line.substr(q0 + 1, q1 - q0 - 1));
    raw.groups.push_back(g);
  }
}

using EntityPhysical = std::map<std::pair<int, int>, int>; // (dim, tag) -> first physical tag

void read_entities(MshCursor& c, bool binary, EntityPhysical& phys) {
  std::uint64_t counts[4];
  for (auto& n : counts) n = c.value<std::uint64_t>(binary);
  for (int dim = 0; dim < 4; ++dim)
    for (std::uint64_t e = 0; e < counts[dim]; ++e) {
      const int tag = c.value<int>(binary);
      for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) c.value<double>(binary);
      const auto np = c.value<std::uint64_t>(binary);
      for (std::uint64_t k = 0; k < np; ++k) {
        const int p = c.value<int>(binary);
        if (k == 0) phys[{dim, tag}] = p;
      }
      if (dim > 0) {
        const auto nb = c.value<std::uint64_t>(binary);
        for (std::uint64_t k = 0; k < nb; ++k) c.value<int>(binary);
      }
    }
}

void read_nodes_v41(MshCursor& c, bool binary, Raw& raw) {
  const auto blocks = c.value<std::uint64_t>(binary);
  const auto total = c.value<std::uint64_t>(binary);
  c.value<std::uint64_t>(binary);
  c.value<std::uint64_t>(binary);
  // A count from the file sizes no allocation beyond what the file can hold.
  raw.node_tags.reserve(std::min<std::uint64_t>(total, c.size()));
  raw.coords.reserve(std::min<std::uint64_t>(total, c.size()));
  for (std::uint64_t b = 0; b < blocks; ++b) {
    const int dim = c.value<int>(binary);
    c.value<int>(binary);
    const int parametric = c.value<int>(binary);
    const auto n = c.value<std::uint64_t>(binary);
    for (std::uint64_t i = 0; i < n; ++i) raw.node_tags.push_back(c.value<std::int64_t, std::uint64_t>(binary));
    const int extra = parametric ? (dim == 3 ? 0 : dim) : 0;
    for (std::uint64_t i = 0; i < n; ++i) {
      Eigen::Vector3d p;
      for (int k = 0; k < 3; ++k) p[k] = c.value<double>(binary);
      for (int k = 0; k < extra; ++k) c.value<double>(binary);
      raw.coords.push_back(p);
    }
  }
}

void read_elements_v41(MshCursor& c, bool binary, const EntityPhysical& phys, Raw& raw) {
  const auto blocks = c.value<std::uint64_t>(binary);
  c.value<std::uint64_t>(binary);
  c.value<std::uint64_t>(binary);
  c.value<std::uint64_t>(binary);
  for (std::uint64_t b = 0; b < blocks; ++b) {
    const int dim = c.value<int>(binary);
    const int tag = c.value<int>(binary);
    const int type = c.value<int>(binary);
    const auto n = c.value<std::uint64_t>(binary);
    const int per = nodes_of_type(type);
    if (per == 0) {
      if (binary) c.fail(fmt::format("unsupported element type {} in a binary file", type));
      c.skip_line_end();
      for (std::uint64_t i = 0; i < n; ++i) {
        // A count from the file: stop at its end, not after n empty lines.
        if (c.at_end()) c.fail("the file ends inside an element block");
        c.rest_of_line();
      }
      continue;
    }
    auto it = phys.find({dim, tag});
    const int physical = it == phys.end() ? 0 : it->second;
    for (std::uint64_t i = 0; i < n; ++i) {
      const auto element_tag = c.value<std::int64_t, std::uint64_t>(binary);
      Raw::Element e{type, physical, {}, element_tag};
      e.nodes.resize(per);
      for (int k = 0; k < per; ++k) e.nodes[k] = c.value<std::int64_t, std::uint64_t>(binary);
      raw.elements.push_back(std::move(e));
    }
  }
}

void read_nodes_v22(MshCursor& c, Raw& raw) {
  const auto n = c.text<std::int64_t>();
  for (std::int64_t i = 0; i < n; ++i) {
    raw.node_tags.push_back(c.text<std::int64_t>());
    Eigen::Vector3d p;
    for (int k = 0; k < 3; ++k) p[k] = c.text<double>();
    raw.coords.push_back(p);
  }
}

void read_elements_v22(MshCursor& c, Raw& raw) {
  const auto n = c.text<std::int64_t>();
  for (std::int64_t i = 0; i < n; ++i) {
    const auto element_tag = c.text<std::int64_t>();
    const int type = c.text<int>();
    const int ntags = c.text<int>();
    int physical = 0;
    for (int k = 0; k < ntags; ++k) {
      const int t = c.text<int>();
      if (k == 0) physical = t;
    }
    const int per = nodes_of_type(type);
    if (per == 0) {
      c.rest_of_line();
      continue;
    }
    Raw::Element e{type, physical, {}, element_tag};
    e.nodes.resize(per);
    for (int k = 0; k < per; ++k) e.nodes[k] = c.text<std::int64_t>();
    raw.elements.push_back(std::move(e));
  }
}

mesh::TetMesh assemble(Raw& raw, const std::string& name) {
  mesh::TetMesh m;
  m.groups = raw.groups;
  std::unordered_map<std::int64_t, int> index;
  index.reserve(raw.node_tags.size());
  for (std::size_t i = 0; i < raw.node_tags.size(); ++i)
    if (!index.emplace(raw.node_tags[i], static_cast<int>(i)).second)
      throw Error(ExitCode::io, fmt::format("{}: node tag {} appears twice", name, raw.node_tags[i]));
  m.nodes = std::move(raw.coords);
  int order = 0;
  auto set_order = [&](int p) {
    if (order != 0 && order != p)
      throw Error(ExitCode::io, fmt::format("{}: mixed element orders {} and {}", name, order, p));
    order = p;
  };
  for (const auto& e : raw.elements) {
    if (int p = highorder::gmsh_tet_order(e.type)) set_order(p);
    if (int p = highorder::gmsh_triangle_order(e.type)) set_order(p);
  }
  if (order == 0) throw Error(ExitCode::io, name + ": no triangles or tetrahedra");
  m.order = order;
  auto id = [&](std::int64_t tag) {
    auto it = index.find(tag);
    if (it == index.end()) throw Error(ExitCode::io, fmt::format("{}: element refers to missing node {}", name, tag));
    return it->second;
  };
  // Blocks group elements by entity; the tags give back the writer's order.
  std::stable_sort(raw.elements.begin(), raw.elements.end(),
                   [](const Raw::Element& a, const Raw::Element& b) { return a.tag < b.tag; });
  for (const auto& e : raw.elements) {
    if (highorder::gmsh_tet_order(e.type)) {
      for (auto t : e.nodes) m.tets.push_back(id(t));
      m.tet_tags.push_back(e.physical);
    } else if (highorder::gmsh_triangle_order(e.type)) {
      for (auto t : e.nodes) m.boundary.push_back(id(t));
      m.boundary_tags.push_back(e.physical);
    }
  }
  return m;
}

} // namespace

mesh::TetMesh parse_msh(std::string_view bytes, const std::string& name) {
  MshCursor c(bytes, name);
  Raw raw;
  EntityPhysical phys;
  bool binary = false, v41 = false, seen_format = false;
  while (!c.at_end()) {
    auto section = c.token();
    if (section.empty() || section[0] != '$') c.fail(fmt::format("expected a section, got '{}'", section));
    if (section == "$MeshFormat") {
      auto version = c.token();
      const int file_type = c.text<int>();
      const int data_size = c.text<int>();
      if (version.substr(0, 1) == "4") {
        if (version != "4.1") c.fail(fmt::format("MSH version {} not supported (4.1 or 2.2)", version));
        v41 = true;
      } else if (version.substr(0, 1) != "2") {
        c.fail(fmt::format("MSH version {} not supported (4.1 or 2.2)", version));
      }
      binary = file_type == 1;
      if (binary && !v41) c.fail("binary MSH 2 is not supported");
      if (binary && data_size != 8) c.fail("binary MSH needs 8-byte size_t");
      if (binary) {
        c.skip_line_end();
        if (c.raw<int>() != 1) c.fail("binary MSH written with another endianness");
      }
      c.expect("$EndMeshFormat");
      seen_format = true;
      continue;
    }
    if (!seen_format) c.fail("missing $MeshFormat");
    if (section == "$PhysicalNames") {
      read_physical_names(c, raw);
    } else if (section == "$Entities" && v41) {
      if (binary) c.skip_line_end();
      read_entities(c, binary, phys);
    } else if (section == "$Nodes") {
      if (binary) c.skip_line_end();
      v41 ? read_nodes_v41(c, binary, raw) : read_nodes_v22(c, raw);
    } else if (section == "$Elements") {
      if (binary) c.skip_line_end();
      v41 ? read_elements_v41(c, binary, phys, raw) : read_elements_v22(c, raw);
    } else {
      c.skip_section(section);
      continue;
    }
    c.expect("$End" + std::string(section.substr(1)));
  }
  return assemble(raw, name);
}

mesh::TetMesh read_msh(const std::string& path) {
  std::string bytes;
  try {
    bytes = read_file_bytes(path);
  } catch (const Error& e) {
    throw Error(ExitCode::io, e.what());
  }
  return parse_msh(bytes, path);
}

} // namespace curvetet::io
