#include "curvetet/io/text_cursor.hpp"

#include "curvetet/core/error.hpp"

#include <charconv>
#include <cmath>
#include <cctype>
#include <fstream>
#include <sstream>

namespace curvetet::io {

void TextCursor::skip_blank() {
  while (pos_ < text_.size()) {
    char c = text_[pos_];
    if (c == '\n') {
      ++line_;
      ++pos_;
    } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
      ++pos_;
    } else if (comment_ && c == comment_) {
      while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    } else {
      break;
    }
  }
}

std::string_view TextCursor::token() {
  skip_blank();
  std::size_t start = pos_;
  while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  return text_.substr(start, pos_ - start);
}

std::string_view TextCursor::line() {
  std::size_t start = pos_;
  while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
  std::string_view out = text_.substr(start, pos_ - start);
  if (pos_ < text_.size()) {
    ++pos_;
    ++line_;
  }
  if (!out.empty() && out.back() == '\r') out.remove_suffix(1);
  return out;
}

bool TextCursor::at_end() {
  skip_blank();
  return pos_ >= text_.size();
}

std::optional<double> TextCursor::real() { return parse_real(token()); }
std::optional<std::int64_t> TextCursor::integer() { return parse_integer(token()); }

std::optional<double> parse_real(std::string_view s) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double v = 0;
  auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  // out-of-range still yields +-inf / 0 in some libstdc++ versions: treat
  // overflow as infinity so the non-finite check names it.
  if (ec == std::errc::result_out_of_range) {
    if (s.find_first_of("eE") != std::string_view::npos && s.find("e-") == std::string_view::npos &&
        s.find("E-") == std::string_view::npos)
      return (!s.empty() && s.front() == '-') ? -HUGE_VAL : HUGE_VAL;
    return 0.0;
  }
  if (ec != std::errc() || ptr != s.data() + s.size() || s.empty()) return std::nullopt;
  return v;
}

std::optional<std::int64_t> parse_integer(std::string_view s) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  std::int64_t v = 0;
  auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || ptr != s.data() + s.size() || s.empty()) return std::nullopt;
  return v;
}

std::string read_file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(InputDefect::unreadable, "cannot open '" + path + "'");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

} // namespace curvetet::io
