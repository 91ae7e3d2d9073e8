// OFF: "OFF" (optionally with C/N/ST prefixes), "nv nf ne", nv vertex lines
// (x y z, extra columns such as colours ignored), nf face lines
// (n i0 .. in-1, extra columns ignored). '#' starts a comment.
#include "curvetet/core/error.hpp"
#include "curvetet/io/read_surface.hpp"
#include "curvetet/io/text_cursor.hpp"

#include <fmt/format.h>

#include <cstdint>

namespace curvetet::io {
namespace {

// Next non-empty, non-comment line.
std::string_view content_line(TextCursor& c) {
  while (!c.at_end()) {
    std::string_view l = c.line();
    auto first = l.find_first_not_of(" \t\r");
    if (first == std::string_view::npos || l[first] == '#') continue;
    return l;
  }
  return {};
}

[[noreturn]] void fail(const std::string& name, std::size_t line, const std::string& what) {
  throw Error(InputDefect::unreadable, fmt::format("{}:{}: OFF: {}", name, line, what));
}

} // namespace

mesh::PolygonSoup parse_off(std::string_view bytes, const std::string& name) {
  TextCursor c(bytes);
  std::string_view header = c.token();
  if (header.size() < 3 || header.substr(header.size() - 3) != "OFF")
    fail(name, c.line_number(), "file does not start with 'OFF'");
  auto nv = c.integer(), nf = c.integer(), ne = c.integer();
  if (!nv || !nf || !ne || *nv < 0 || *nf < 0) fail(name, c.line_number(), "bad vertex/face/edge counts");
  // Every entry takes at least a byte: larger counts cannot be right, and
  // must not size an allocation.
  if (static_cast<std::uint64_t>(*nv) > bytes.size() || static_cast<std::uint64_t>(*nf) > bytes.size())
    fail(name, c.line_number(), "vertex/face counts larger than the file");
  c.line();

  mesh::PolygonSoup soup;
  soup.points.resize(static_cast<std::size_t>(*nv));
  for (auto& p : soup.points) {
    std::size_t at = c.line_number();
    TextCursor l(content_line(c), 0);
    for (int k = 0; k < 3; ++k) {
      auto x = l.real();
      if (!x) fail(name, at, "expected three vertex coordinates");
      p[k] = *x;
    }
  }
  soup.polygons.resize(static_cast<std::size_t>(*nf));
  for (auto& poly : soup.polygons) {
    std::size_t at = c.line_number();
    const std::string_view text = content_line(c);
    TextCursor l(text, 0);
    auto n = l.integer();
    if (!n || *n < 0) fail(name, at, "expected a face corner count");
    if (static_cast<std::uint64_t>(*n) > text.size()) fail(name, at, "more face corners than the line holds");
    poly.resize(static_cast<std::size_t>(*n));
    for (auto& idx : poly) {
      auto i = l.integer();
      if (!i) fail(name, at, "expected a vertex index");
      idx = *i;
    }
  }
  return soup;
}

} // namespace curvetet::io
