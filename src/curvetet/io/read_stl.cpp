// STL, ASCII ("solid ... facet normal ... outer loop vertex x y z ...") or
// binary (80-byte header, uint32 count, 50 bytes per triangle, little
// endian). A file is binary when its size is exactly 84 + 50 * count, even if
// its header starts with "solid" (many exporters do that).
// Corners with bit-identical coordinates are welded: STL stores no indices.
#include "curvetet/core/error.hpp"
#include "curvetet/io/read_surface.hpp"
#include "curvetet/io/text_cursor.hpp"

#include <fmt/format.h>

#include <array>
#include <cstring>
#include <map>

namespace curvetet::io {
namespace {

// Exact weld: the key is the coordinates' bit patterns.
class Welder {
 public:
  explicit Welder(mesh::PolygonSoup& soup) : soup_(soup) {}
  std::int64_t index(const mesh::Vec3& p) {
    std::array<std::uint64_t, 3> key;
    std::memcpy(key.data(), p.data(), sizeof key);
    auto [it, inserted] = ids_.try_emplace(key, static_cast<std::int64_t>(soup_.points.size()));
    if (inserted) soup_.points.push_back(p);
    return it->second;
  }

 private:
  mesh::PolygonSoup& soup_;
  std::map<std::array<std::uint64_t, 3>, std::int64_t> ids_;
};

float read_f32_le(const char* p) {
  std::uint32_t u = std::uint32_t(static_cast<unsigned char>(p[0])) | std::uint32_t(static_cast<unsigned char>(p[1])) << 8 |
                    std::uint32_t(static_cast<unsigned char>(p[2])) << 16 |
                    std::uint32_t(static_cast<unsigned char>(p[3])) << 24;
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

mesh::PolygonSoup parse_binary(std::string_view b, std::uint32_t count) {
  mesh::PolygonSoup soup;
  Welder weld(soup);
  soup.polygons.reserve(count);
  for (std::uint32_t t = 0; t < count; ++t) {
    const char* rec = b.data() + 84 + 50 * std::size_t(t) + 12; // skip normal
    std::vector<std::int64_t> tri(3);
    for (int k = 0; k < 3; ++k) {
      mesh::Vec3 p(read_f32_le(rec + 12 * k), read_f32_le(rec + 12 * k + 4), read_f32_le(rec + 12 * k + 8));
      tri[k] = weld.index(p);
    }
    soup.polygons.push_back(std::move(tri));
  }
  return soup;
}

mesh::PolygonSoup parse_ascii(std::string_view b, const std::string& name) {
  mesh::PolygonSoup soup;
  Welder weld(soup);
  TextCursor c(b, 0);
  std::vector<std::int64_t> loop;
  for (std::string_view t = c.token(); !t.empty(); t = c.token()) {
    if (t == "vertex") {
      mesh::Vec3 p;
      for (int k = 0; k < 3; ++k) {
        auto x = c.real();
        if (!x) throw Error(InputDefect::unreadable, fmt::format("{}:{}: STL: bad vertex", name, c.line_number()));
        p[k] = *x;
      }
      loop.push_back(weld.index(p));
    } else if (t == "endloop") {
      soup.polygons.push_back(std::move(loop));
      loop.clear();
    }
  }
  return soup;
}

} // namespace

mesh::PolygonSoup parse_stl(std::string_view bytes, const std::string& name) {
  if (bytes.size() >= 84) {
    std::uint32_t count = 0;
    for (int k = 0; k < 4; ++k) count |= std::uint32_t(static_cast<unsigned char>(bytes[80 + k])) << (8 * k);
    if (bytes.size() == 84 + 50 * std::size_t(count)) return parse_binary(bytes, count);
  }
  if (bytes.substr(0, 5) != "solid")
    throw Error(InputDefect::unreadable, name + ": STL: neither binary (size mismatch) nor ASCII ('solid' header)");
  return parse_ascii(bytes, name);
}

} // namespace curvetet::io
