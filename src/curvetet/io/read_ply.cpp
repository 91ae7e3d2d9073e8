// PLY, ASCII or binary (little or big endian). Reads element "vertex"
// (properties x, y, z of any numeric type) and element "face" (list property
// vertex_indices or vertex_index); every other element and property is
// skipped according to its declared type.
#include "curvetet/core/error.hpp"
#include "curvetet/io/read_surface.hpp"
#include "curvetet/io/text_cursor.hpp"

#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace curvetet::io {
namespace {

enum class Scalar { i8, u8, i16, u16, i32, u32, f32, f64 };

struct Property {
  std::string name;
  Scalar type;
  bool is_list = false;
  Scalar count_type = Scalar::u8;
};

struct Element {
  std::string name;
  std::size_t count = 0;
  std::vector<Property> props;
};

enum class Encoding { ascii, little, big };

[[noreturn]] void fail(const std::string& name, const std::string& what) {
  throw Error(InputDefect::unreadable, fmt::format("{}: PLY: {}", name, what));
}

Scalar scalar_from(std::string_view t, const std::string& name) {
  if (t == "char" || t == "int8") return Scalar::i8;
  if (t == "uchar" || t == "uint8") return Scalar::u8;
  if (t == "short" || t == "int16") return Scalar::i16;
  if (t == "ushort" || t == "uint16") return Scalar::u16;
  if (t == "int" || t == "int32") return Scalar::i32;
  if (t == "uint" || t == "uint32") return Scalar::u32;
  if (t == "float" || t == "float32") return Scalar::f32;
  if (t == "double" || t == "float64") return Scalar::f64;
  fail(name, "unknown property type '" + std::string(t) + "'");
}

std::size_t scalar_size(Scalar s) {
  switch (s) {
    case Scalar::i8: case Scalar::u8: return 1;
    case Scalar::i16: case Scalar::u16: return 2;
    case Scalar::i32: case Scalar::u32: case Scalar::f32: return 4;
    case Scalar::f64: return 8;
  }
  return 0;
}

// Reads scalar values from the body, in the file's encoding. Values are
// returned as double, which holds every PLY scalar exactly.
class BodyReader {
 public:
  BodyReader(std::string_view body, Encoding enc, const std::string& name)
      : body_(body), enc_(enc), name_(name), text_(body, 0) {}

  double next(Scalar s) {
    if (enc_ == Encoding::ascii) {
      auto v = text_.real();
      if (!v) fail(name_, fmt::format("bad or missing ASCII value near line {}", text_.line_number()));
      return *v;
    }
    std::size_t n = scalar_size(s);
    if (pos_ + n > body_.size()) fail(name_, "binary body is shorter than the header says");
    unsigned char raw[8];
    std::memcpy(raw, body_.data() + pos_, n);
    pos_ += n;
    bool swap = (enc_ == Encoding::little) != (std::endian::native == std::endian::little);
    if (swap) std::reverse(raw, raw + n);
    switch (s) {
      case Scalar::i8: { std::int8_t v; std::memcpy(&v, raw, 1); return v; }
      case Scalar::u8: { std::uint8_t v; std::memcpy(&v, raw, 1); return v; }
      case Scalar::i16: { std::int16_t v; std::memcpy(&v, raw, 2); return v; }
      case Scalar::u16: { std::uint16_t v; std::memcpy(&v, raw, 2); return v; }
      case Scalar::i32: { std::int32_t v; std::memcpy(&v, raw, 4); return v; }
      case Scalar::u32: { std::uint32_t v; std::memcpy(&v, raw, 4); return v; }
      case Scalar::f32: { float v; std::memcpy(&v, raw, 4); return v; }
      case Scalar::f64: { double v; std::memcpy(&v, raw, 8); return v; }
    }
    return 0;
  }

 private:
  std::string_view body_;
  Encoding enc_;
  const std::string& name_;
  TextCursor text_;
  std::size_t pos_ = 0;
};

} // namespace

mesh::PolygonSoup parse_ply(std::string_view bytes, const std::string& name) {
  auto end = bytes.find("end_header");
  if (bytes.substr(0, 3) != "ply" || end == std::string_view::npos) fail(name, "missing 'ply' magic or 'end_header'");
  std::size_t body_start = bytes.find('\n', end);
  body_start = body_start == std::string_view::npos ? bytes.size() : body_start + 1;

  Encoding enc = Encoding::ascii;
  std::vector<Element> elements;
  TextCursor header(bytes.substr(0, end), 0);
  while (!header.at_end()) {
    TextCursor l(header.line(), 0);
    std::string_view kw = l.token();
    if (kw == "format") {
      std::string_view f = l.token();
      enc = f == "ascii" ? Encoding::ascii : f == "binary_little_endian" ? Encoding::little
            : f == "binary_big_endian" ? Encoding::big : (fail(name, "unknown format"), Encoding::ascii);
    } else if (kw == "element") {
      Element e;
      e.name = std::string(l.token());
      auto n = l.integer();
      if (!n || *n < 0) fail(name, "bad element count for '" + e.name + "'");
      // Every entry takes at least a byte: a larger count cannot be right.
      if (static_cast<std::uint64_t>(*n) > bytes.size()) fail(name, "element count for '" + e.name + "' larger than the file");
      e.count = static_cast<std::size_t>(*n);
      elements.push_back(std::move(e));
    } else if (kw == "property") {
      if (elements.empty()) fail(name, "property before any element");
      Property p;
      std::string_view t = l.token();
      if (t == "list") {
        p.is_list = true;
        p.count_type = scalar_from(l.token(), name);
        p.type = scalar_from(l.token(), name);
      } else {
        p.type = scalar_from(t, name);
      }
      p.name = std::string(l.token());
      elements.back().props.push_back(std::move(p));
    }
  }

  mesh::PolygonSoup soup;
  BodyReader body(bytes.substr(body_start), enc, name);
  for (const Element& e : elements) {
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    if (is_vertex) soup.points.resize(e.count, mesh::Vec3::Zero());
    for (std::size_t i = 0; i < e.count; ++i) {
      for (const Property& p : e.props) {
        if (!p.is_list) {
          double v = body.next(p.type);
          if (is_vertex && p.name.size() == 1 && p.name[0] >= 'x' && p.name[0] <= 'z') soup.points[i][p.name[0] - 'x'] = v;
          continue;
        }
        double n = body.next(p.count_type);
        if (!(n >= 0) || n != std::floor(n) || n > static_cast<double>(bytes.size()))
          fail(name, "bad list length (negative, fractional or larger than the file)");
        std::vector<std::int64_t> list(static_cast<std::size_t>(n));
        for (auto& x : list) {
          // Indices travel as doubles here; only integers an int64 holds convert.
          const double v = body.next(p.type);
          if (!(std::abs(v) < 0x1p62) || v != std::floor(v)) fail(name, "list entry not an integer index");
          x = static_cast<std::int64_t>(v);
        }
        if (is_face && (p.name == "vertex_indices" || p.name == "vertex_index")) soup.polygons.push_back(std::move(list));
      }
    }
  }
  return soup;
}

} // namespace curvetet::io
