#pragma once
// Whitespace tokenizer over a whole file held in memory. Numbers are parsed
// with std::from_chars, which is correctly rounded: decimal coordinates read
// into the same double every time (bit-exact round trips).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace curvetet::io {

class TextCursor {
 public:
  // comment: lines starting (after blanks) with this char are skipped, 0 = none.
  TextCursor(std::string_view text, char comment = '#') : text_(text), comment_(comment) {}

  // Next whitespace-separated token, or empty at end of input.
  std::string_view token();
  // Rest of the current line (without the newline), and moves past it.
  std::string_view line();
  bool at_end();
  std::size_t line_number() const { return line_; }

  std::optional<double> real();
  std::optional<std::int64_t> integer();

 private:
  void skip_blank();
  std::string_view text_;
  char comment_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
};

std::optional<double> parse_real(std::string_view s);
std::optional<std::int64_t> parse_integer(std::string_view s);

// Whole file as bytes; throws Error(InputDefect::unreadable) if it cannot.
std::string read_file_bytes(const std::string& path);

} // namespace curvetet::io
