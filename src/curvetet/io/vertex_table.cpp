#include "curvetet/io/vertex_table.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/io/write_surface.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

namespace curvetet::io {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw Error(ExitCode::io, fmt::format("{}: {}", path, what));
}

std::string lower_extension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

std::string trim(std::string s) {
  const auto b = s.find_first_not_of(" \t\r\"");
  const auto e = s.find_last_not_of(" \t\r\"");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

// Splits the raw columns into position and attributes.
VertexTable make_table(const std::string& path, const std::vector<std::string>& names,
                       const std::vector<std::vector<double>>& rows, const std::vector<std::string>& labels) {
  VertexTable t;
  int xyz[3] = {-1, -1, -1};
  std::vector<int> keep;
  for (int c = 0; c < static_cast<int>(names.size()); ++c) {
    if (names[c] == "x" || names[c] == "y" || names[c] == "z") xyz[names[c][0] - 'x'] = c;
    else keep.push_back(c);
  }
  const bool has_position = xyz[0] >= 0 && xyz[1] >= 0 && xyz[2] >= 0;
  if (!has_position)
    for (int d = 0; d < 3; ++d)
      if (xyz[d] >= 0) keep.push_back(xyz[d]);
  std::sort(keep.begin(), keep.end());
  for (int c : keep) {
    t.names.push_back(names[c]);
    t.is_label.push_back(std::find(labels.begin(), labels.end(), names[c]) != labels.end());
  }
  for (const auto& l : labels)
    if (std::find(t.names.begin(), t.names.end(), l) == t.names.end()) fail(path, "no attribute column named '" + l + "'");
  t.values.resize(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(keep.size()));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (std::size_t k = 0; k < keep.size(); ++k) t.values(r, k) = rows[r][keep[k]];
    if (has_position) t.positions.emplace_back(rows[r][xyz[0]], rows[r][xyz[1]], rows[r][xyz[2]]);
  }
  return t;
}

VertexTable read_csv(const std::string& path, const std::vector<std::string>& labels) {
  std::ifstream in(path);
  if (!in) fail(path, "cannot read");
  std::string line;
  if (!std::getline(in, line)) fail(path, "empty CSV");
  std::vector<std::string> names;
  {
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) names.push_back(trim(cell));
  }
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    if (trim(line).empty()) continue;
    std::stringstream ss(line);
    std::string cell;
    std::vector<double> row;
    while (std::getline(ss, cell, ',')) {
      const std::string c = trim(cell);
      char* end = nullptr;
      const double x = std::strtod(c.c_str(), &end);
      if (c.empty() || *end != '\0') fail(path, fmt::format("line {}: '{}' is not a number", rows.size() + 2, c));
      row.push_back(x);
    }
    if (row.size() != names.size()) fail(path, fmt::format("line {}: {} values for {} columns", rows.size() + 2, row.size(), names.size()));
    rows.push_back(std::move(row));
  }
  return make_table(path, names, rows, labels);
}

// --- PLY ---------------------------------------------------------------

enum class Type { i8, u8, i16, u16, i32, u32, f32, f64 };

Type type_from(const std::string& t, const std::string& path) {
  if (t == "char" || t == "int8") return Type::i8;
  if (t == "uchar" || t == "uint8") return Type::u8;
  if (t == "short" || t == "int16") return Type::i16;
  if (t == "ushort" || t == "uint16") return Type::u16;
  if (t == "int" || t == "int32") return Type::i32;
  if (t == "uint" || t == "uint32") return Type::u32;
  if (t == "float" || t == "float32") return Type::f32;
  if (t == "double" || t == "float64") return Type::f64;
  fail(path, "PLY: unknown type '" + t + "'");
}

std::size_t type_size(Type t) {
  switch (t) {
    case Type::i8: case Type::u8: return 1;
    case Type::i16: case Type::u16: return 2;
    case Type::i32: case Type::u32: case Type::f32: return 4;
    case Type::f64: return 8;
  }
  return 0;
}

template <class T>
double load(const char* p, bool swap) {
  char b[sizeof(T)];
  std::memcpy(b, p, sizeof(T));
  if (swap) std::reverse(b, b + sizeof(T));
  T v;
  std::memcpy(&v, b, sizeof(T));
  return static_cast<double>(v);
}

double load(Type t, const char* p, bool swap) {
  switch (t) {
    case Type::i8: return load<std::int8_t>(p, swap);
    case Type::u8: return load<std::uint8_t>(p, swap);
    case Type::i16: return load<std::int16_t>(p, swap);
    case Type::u16: return load<std::uint16_t>(p, swap);
    case Type::i32: return load<std::int32_t>(p, swap);
    case Type::u32: return load<std::uint32_t>(p, swap);
    case Type::f32: return load<float>(p, swap);
    case Type::f64: return load<double>(p, swap);
  }
  return 0;
}

struct Property {
  std::string name;
  Type type = Type::f64;
  bool list = false;
  Type count_type = Type::u8;
};
struct Element {
  std::string name;
  std::size_t count = 0;
  std::vector<Property> props;
};

VertexTable read_ply(const std::string& path, const std::vector<std::string>& labels) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot read");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto end_header = bytes.find("end_header");
  if (bytes.rfind("ply", 0) != 0 || end_header == std::string::npos) fail(path, "not a PLY file");
  std::size_t body = bytes.find('\n', end_header);
  if (body == std::string::npos) fail(path, "PLY: header not terminated");
  ++body;
  std::istringstream header(bytes.substr(0, end_header));
  std::string line, format;
  std::vector<Element> elements;
  while (std::getline(header, line)) {
    std::istringstream ls(line);
    std::string word;
    ls >> word;
    if (word == "format") ls >> format;
    else if (word == "element") {
      Element e;
      ls >> e.name >> e.count;
      elements.push_back(e);
    } else if (word == "property") {
      if (elements.empty()) fail(path, "PLY: property before element");
      Property p;
      std::string t;
      ls >> t;
      if (t == "list") {
        std::string ct, it;
        ls >> ct >> it >> p.name;
        p.list = true;
        p.count_type = type_from(ct, path);
        p.type = type_from(it, path);
      } else {
        p.type = type_from(t, path);
        ls >> p.name;
      }
      elements.back().props.push_back(p);
    }
  }
  const bool ascii = format == "ascii";
  const bool swap = (format == "binary_big_endian") == (std::endian::native == std::endian::little);
  if (!ascii && format != "binary_little_endian" && format != "binary_big_endian") fail(path, "PLY: unknown format " + format);

  std::vector<std::string> names;
  std::vector<std::vector<double>> rows;
  std::istringstream text(ascii ? bytes.substr(body) : std::string());
  std::size_t pos = body;
  auto next = [&](Type t) -> double {
    if (ascii) {
      double v;
      if (!(text >> v)) fail(path, "PLY: truncated ASCII body");
      return v;
    }
    if (bytes.size() - pos < type_size(t)) fail(path, "PLY: truncated binary body");
    const double v = load(t, bytes.data() + pos, swap);
    pos += type_size(t);
    return v;
  };
  for (const auto& e : elements) {
    const bool vertex = e.name == "vertex";
    if (vertex)
      for (const auto& p : e.props)
        if (!p.list) names.push_back(p.name);
    for (std::size_t r = 0; r < e.count; ++r) {
      std::vector<double> row;
      for (const auto& p : e.props) {
        if (p.list) {
          const double n = next(p.count_type);
          if (n < 0 || n > 1e6) fail(path, "PLY: bad list length");
          for (int k = 0; k < static_cast<int>(n); ++k) next(p.type);
        } else {
          const double v = next(p.type);
          if (vertex) row.push_back(v);
        }
      }
      if (vertex) rows.push_back(std::move(row));
    }
    if (vertex) break; // later elements are not needed
  }
  return make_table(path, names, rows, labels);
}

std::string number(double x) { return fmt::format("{:.17g}", x); }

} // namespace

VertexTable read_vertex_table(const std::string& path, const std::vector<std::string>& labels) {
  const auto ext = lower_extension(path);
  if (ext == "csv") return read_csv(path, labels);
  if (ext == "ply") return read_ply(path, labels);
  fail(path, "attribute files must be .csv or .ply");
}

void write_vertex_table(const std::string& path, const VertexTable& t, const std::vector<mesh::Tri>& faces) {
  const auto ext = lower_extension(path);
  const auto rows = static_cast<std::size_t>(t.values.rows());
  if (!t.positions.empty() && t.positions.size() != rows) fail(path, "positions and attribute rows differ");
  const bool xyz = !t.positions.empty();
  AtomicFile file(path);
  auto& out = file.stream();
  auto cell = [&](std::size_t r, std::size_t c) {
    return t.is_label[c] ? fmt::format("{}", static_cast<long long>(std::llround(t.values(r, c)))) : number(t.values(r, c));
  };
  if (ext == "csv") {
    std::vector<std::string> header;
    if (xyz) header = {"x", "y", "z"};
    header.insert(header.end(), t.names.begin(), t.names.end());
    out << fmt::format("{}\n", fmt::join(header, ","));
    for (std::size_t r = 0; r < rows; ++r) {
      std::vector<std::string> cells;
      if (xyz)
        for (int d = 0; d < 3; ++d) cells.push_back(number(t.positions[r][d]));
      for (std::size_t c = 0; c < t.names.size(); ++c) cells.push_back(cell(r, c));
      out << fmt::format("{}\n", fmt::join(cells, ","));
    }
  } else if (ext == "ply") {
    out << "ply\nformat ascii 1.0\ncomment curvetet transfer\n" << "element vertex " << rows << '\n';
    if (xyz) out << "property double x\nproperty double y\nproperty double z\n";
    for (std::size_t c = 0; c < t.names.size(); ++c) out << "property " << (t.is_label[c] ? "int " : "double ") << t.names[c] << '\n';
    if (!faces.empty()) out << "element face " << faces.size() << "\nproperty list uchar int vertex_indices\n";
    out << "end_header\n";
    for (std::size_t r = 0; r < rows; ++r) {
      std::vector<std::string> cells;
      if (xyz)
        for (int d = 0; d < 3; ++d) cells.push_back(number(t.positions[r][d]));
      for (std::size_t c = 0; c < t.names.size(); ++c) cells.push_back(cell(r, c));
      out << fmt::format("{}\n", fmt::join(cells, " "));
    }
    for (const auto& f : faces) out << "3 " << f[0] << ' ' << f[1] << ' ' << f[2] << '\n';
  } else {
    fail(path, "attribute files must be .csv or .ply");
  }
  file.commit();
}

} // namespace curvetet::io
