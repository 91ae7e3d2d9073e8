// OBJ: "v x y z [w]" and "f a b c ..." where a corner is "i", "i/t", "i//n" or
// "i/t/n"; indices are 1-based, negative ones count back from the last vertex.
// Other statements (vn, vt, g, o, s, usemtl, l, ...) are ignored.
#include "curvetet/core/error.hpp"
#include "curvetet/io/read_surface.hpp"
#include "curvetet/io/text_cursor.hpp"

#include <fmt/format.h>

namespace curvetet::io {

mesh::PolygonSoup parse_obj(std::string_view bytes, const std::string& name) {
  TextCursor c(bytes, 0);
  mesh::PolygonSoup soup;
  while (!c.at_end()) {
    std::size_t at = c.line_number();
    TextCursor l(c.line(), '#');
    std::string_view kw = l.token();
    if (kw == "v") {
      mesh::Vec3 p;
      for (int k = 0; k < 3; ++k) {
        auto x = l.real();
        if (!x) throw Error(InputDefect::unreadable, fmt::format("{}:{}: OBJ: bad vertex", name, at));
        p[k] = *x;
      }
      soup.points.push_back(p);
    } else if (kw == "f") {
      std::vector<std::int64_t> poly;
      for (std::string_view t = l.token(); !t.empty(); t = l.token()) {
        auto i = parse_integer(t.substr(0, t.find('/')));
        if (!i || *i == 0) throw Error(InputDefect::unreadable, fmt::format("{}:{}: OBJ: bad face corner '{}'", name, at, t));
        // 1-based; negative = relative to the vertices read so far.
        poly.push_back(*i > 0 ? *i - 1 : static_cast<std::int64_t>(soup.points.size()) + *i);
      }
      soup.polygons.push_back(std::move(poly));
    }
  }
  return soup;
}

} // namespace curvetet::io
