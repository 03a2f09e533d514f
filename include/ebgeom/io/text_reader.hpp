// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `TextReader`: a bounds-checked cursor over text that counts lines, reads whitespace-separated
/// tokens and parses numbers with `std::from_chars` (no locale, no exceptions, overflow detected).

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>

#include "ebgeom/core/config.hpp"
#include "ebgeom/io/parse_error.hpp"
#include "ebgeom/io/read_options.hpp"

namespace ebgeom::io {

/// Outcome of a number read; the reader turns it into a message.
enum class NumberStatus : std::uint8_t {
  ok,
  missing,      ///< end of line or of input where a number was expected
  malformed,    ///< the token is not a number of the requested kind
  out_of_range, ///< a number too large for the requested type
};

/// Per-format lexical rules of a `TextReader`.
struct TextOptions {
  /// A backslash immediately before a line break joins the two lines (OBJ).
  bool line_continuation = false;
};

namespace detail {

/// `s` quoted for a message: at most 32 characters, non-printable bytes as `\xNN`.
inline std::string quote(std::string_view s) {
  static const char* hex = "0123456789abcdef";
  std::string out = "'";
  const std::size_t n = s.size() < 32 ? s.size() : 32;
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c >= 32 && c < 127) {
      out += char(c);
    } else {
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  if (s.size() > n) out += "...";
  out += "'";
  return out;
}

inline bool is_blank(char c) noexcept {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}
inline bool is_space(char c) noexcept { return is_blank(c) || c == '\n'; }

/// Case-insensitive ASCII comparison.
inline bool iequals(std::string_view a, std::string_view b) noexcept {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    char x = a[i], y = b[i];
    if (x >= 'A' && x <= 'Z') x = char(x - 'A' + 'a');
    if (y >= 'A' && y <= 'Z') y = char(y - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

inline bool starts_with(std::string_view s, std::string_view prefix) noexcept {
  return s.substr(0, prefix.size()) == prefix;
}

} // namespace detail

/// Cursor over text. Lines are separated by `\n` (a preceding `\r` is a blank, so CRLF files
/// work). A UTF-8 byte-order mark at the start is skipped. `line()` is 1-based. Errors made with
/// `fail` carry the line and byte offset of the last token read (or of the cursor).
class TextReader {
 public:
  TextReader(ByteView text, const std::string& path, TextOptions opt = {}) noexcept
      : begin_(text.data()), p_(text.data()), end_(text.data() + text.size()), path_(&path),
        opt_(opt) {
    if (text.size() >= 3 && (unsigned char)p_[0] == 0xEF && (unsigned char)p_[1] == 0xBB &&
        (unsigned char)p_[2] == 0xBF)
      p_ += 3;
    mark();
  }

  std::size_t offset() const noexcept { return std::size_t(p_ - begin_); }
  std::uint64_t line() const noexcept { return line_; }
  bool at_end() const noexcept { return p_ == end_; }
  /// The current byte, or '\0' at the end.
  char peek() const noexcept { return p_ < end_ ? *p_ : '\0'; }
  const char* cur() const noexcept { return p_; }
  const char* end() const noexcept { return end_; }
  const std::string& path() const noexcept { return *path_; }
  /// Moves within the current line (callers never cross a '\n' this way).
  void set_cur(const char* p) noexcept { p_ = p; }

  /// Skips blanks (not line breaks, except a continued line when the options allow it).
  void skip_blanks() noexcept {
    for (;;) {
      while (p_ < end_ && detail::is_blank(*p_)) ++p_;
      if (opt_.line_continuation && p_ < end_ && *p_ == '\\' && continuation_at(p_)) {
        skip_continuation();
        continue;
      }
      return;
    }
  }
  /// Skips blanks and line breaks, counting lines.
  void skip_space() noexcept {
    for (;;) {
      skip_blanks();
      if (p_ < end_ && *p_ == '\n') {
        ++p_;
        ++line_;
        continue;
      }
      return;
    }
  }
  /// After skipping blanks: at a line break or the end?
  bool at_eol() noexcept {
    skip_blanks();
    return p_ == end_ || *p_ == '\n';
  }
  /// True when `p` ends a token: the end, a blank, a line break or a continuation.
  bool is_terminator(const char* p) const noexcept {
    return p == end_ || detail::is_space(*p) ||
           (opt_.line_continuation && *p == '\\' && continuation_at(p));
  }
  /// Next token on the current line (empty at the end of the line).
  std::string_view token_in_line() noexcept {
    skip_blanks();
    return take_token();
  }
  /// Next token, crossing line breaks (empty at the end of the input).
  std::string_view token() noexcept {
    skip_space();
    return take_token();
  }
  /// Moves past the next line break (or to the end).
  void skip_line() noexcept {
    while (p_ < end_ && *p_ != '\n') {
      if (opt_.line_continuation && *p_ == '\\' && continuation_at(p_)) {
        skip_continuation();
        continue;
      }
      ++p_;
    }
    if (p_ < end_) {
      ++p_;
      ++line_;
    }
  }
  /// The rest of the current line without its line break (and without a trailing '\r'); moves
  /// past the line break.
  std::string_view rest_of_line() noexcept {
    const char* b = p_;
    while (p_ < end_ && *p_ != '\n') ++p_;
    const char* e = p_;
    if (e > b && e[-1] == '\r') --e;
    if (p_ < end_) {
      ++p_;
      ++line_;
    }
    return std::string_view(b, std::size_t(e - b));
  }

  /// Reads a real number on the current line (a leading '+' is accepted; NaN and infinity
  /// are returned as such, for the caller to reject). Values that underflow become 0.
  template <class T> NumberStatus real_in_line(T& v) noexcept {
    skip_blanks();
    return parse_real(v);
  }
  /// Reads a real number, crossing line breaks.
  template <class T> NumberStatus real(T& v) noexcept {
    skip_space();
    return parse_real(v);
  }
  /// Reads an integer on the current line. When `stop` is not '\0', the integer may also end at
  /// that character (OBJ's `v/vt/vn`).
  template <class I> NumberStatus integer_in_line(I& v, char stop = '\0') noexcept {
    skip_blanks();
    return parse_integer(v, stop);
  }
  /// Reads an integer, crossing line breaks.
  template <class I> NumberStatus integer(I& v) noexcept {
    skip_space();
    return parse_integer(v, '\0');
  }

  /// Records the cursor as the location for the next error.
  void mark() noexcept {
    tok_ = p_;
    tok_line_ = line_;
  }
  /// Byte offset of the last token (or number) read.
  std::size_t mark_offset() const noexcept { return std::size_t(tok_ - begin_); }
  /// 1-based column (in bytes) of the last token (or number) read.
  std::size_t mark_column() const noexcept {
    const char* b = tok_;
    while (b > begin_ && b[-1] != '\n') --b;
    return std::size_t(tok_ - b) + 1;
  }
  /// The last token (or number) read.
  std::string_view last_token() const noexcept {
    const char* e = tok_;
    while (e < end_ && !detail::is_space(*e) && e - tok_ < 64) ++e;
    return std::string_view(tok_, std::size_t(e - tok_));
  }

  /// An error at the last token read.
  template <class... A> ParseError fail(ErrorCode code, const A&... parts) const {
    return make_parse_error(code, *path_, std::uint64_t(tok_ - begin_), tok_line_, parts...);
  }
  /// The error for a number read that returned `s` (not `ok`); `what` names the value.
  template <class... A> ParseError number_error(NumberStatus s, const A&... what) const {
    switch (s) {
    case NumberStatus::missing:
      return at_end() ? fail(ErrorCode::truncated, "input ends where ", what..., " was expected")
                      : fail(ErrorCode::syntax, "line ends where ", what..., " was expected");
    case NumberStatus::out_of_range:
      return fail(ErrorCode::bad_number, what...,
                  " is out of range: ", detail::quote(last_token()));
    default:
      return fail(ErrorCode::bad_number, "expected ", what..., ", found ",
                  detail::quote(last_token()));
    }
  }

 private:
  bool continuation_at(const char* p) const noexcept {
    // p points at a backslash: a continuation when followed by "\n" or "\r\n"
    if (p + 1 < end_ && p[1] == '\n') return true;
    return p + 2 < end_ && p[1] == '\r' && p[2] == '\n';
  }
  void skip_continuation() noexcept {
    while (*p_ != '\n') ++p_;
    ++p_;
    ++line_;
  }
  std::string_view take_token() noexcept {
    mark();
    const char* b = p_;
    while (!is_terminator(p_)) ++p_;
    return std::string_view(b, std::size_t(p_ - b));
  }
  template <class T> NumberStatus parse_real(T& v) noexcept {
    mark();
    if (p_ == end_ || *p_ == '\n') return NumberStatus::missing;
    const char* b = p_;
    if (*b == '+' && b + 1 < end_ && *(b + 1) != '-' && *(b + 1) != '+') ++b;
    auto r = std::from_chars(b, end_, v);
    if (r.ec == std::errc::result_out_of_range) {
      // Underflow (a tiny exponent) becomes zero; overflow is an error.
      const char* e = b;
      bool neg_exp = false;
      while (e < end_ && !detail::is_space(*e)) {
        if ((*e == 'e' || *e == 'E') && e + 1 < end_ && e[1] == '-') neg_exp = true;
        ++e;
      }
      if (!neg_exp) return NumberStatus::out_of_range;
      v = (*b == '-') ? -T(0) : T(0);
    } else if (r.ec != std::errc()) {
      return NumberStatus::malformed;
    }
    if (!is_terminator(r.ptr)) return NumberStatus::malformed;
    p_ = r.ptr;
    return NumberStatus::ok;
  }
  template <class I> NumberStatus parse_integer(I& v, char stop) noexcept {
    mark();
    if (p_ == end_ || *p_ == '\n') return NumberStatus::missing;
    const char* b = p_;
    if (*b == '+' && b + 1 < end_ && *(b + 1) != '-' && *(b + 1) != '+') ++b;
    auto r = std::from_chars(b, end_, v);
    if (r.ec == std::errc::result_out_of_range) return NumberStatus::out_of_range;
    if (r.ec != std::errc()) return NumberStatus::malformed;
    if (!is_terminator(r.ptr) && !(stop != '\0' && *r.ptr == stop)) return NumberStatus::malformed;
    p_ = r.ptr;
    return NumberStatus::ok;
  }

  const char* begin_;
  const char* p_;
  const char* end_;
  const std::string* path_;
  TextOptions opt_;
  std::uint64_t line_ = 1;
  const char* tok_ = nullptr;
  std::uint64_t tok_line_ = 1;
};

} // namespace ebgeom::io
