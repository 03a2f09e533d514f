// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/scene/scene.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <iterator>
#include <set>
#include <string>
#include <vector>

namespace ebgeom::scene {

namespace {

/// A `const char*` that records the furthest byte the JSON lexer has read, so that errors the
/// checking pass finds (depth, duplicate keys) get a line and column.
struct CountingIterator {
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;
  const char* p;
  const char** furthest;
  const char& operator*() const { return *p; }
  CountingIterator& operator++() {
    ++p;
    if (p > *furthest) *furthest = p;
    return *this;
  }
  bool operator==(const CountingIterator& o) const { return p == o.p; }
  bool operator!=(const CountingIterator& o) const { return p != o.p; }
};

/// SAX pass before any tree is built: limits the nesting depth (the tree's recursive copy, dump
/// and the compiler then stay within the stack) and rejects duplicate object keys (nlohmann-json
/// silently keeps the last).
struct CheckingSax {
  std::size_t depth = 0;
  std::vector<std::set<std::string>> keys; // one per open object (empty for arrays)
  std::string error;                       // what stopped the parse ("" for a syntax error)
  std::size_t error_byte = 0;              // for syntax errors: nlohmann's position
  bool syntax = false;

  bool open() {
    if (++depth > max_json_depth) {
      error = "JSON nested deeper than " + std::to_string(max_json_depth) + " levels";
      return false;
    }
    return true;
  }
  bool null() { return true; }
  bool boolean(bool) { return true; }
  bool number_integer(Json::number_integer_t) { return true; }
  bool number_unsigned(Json::number_unsigned_t) { return true; }
  bool number_float(Json::number_float_t, const std::string&) { return true; }
  bool string(std::string&) { return true; }
  bool binary(Json::binary_t&) { return true; }
  bool start_object(std::size_t) {
    keys.emplace_back();
    return open();
  }
  bool key(std::string& k) {
    if (!keys.back().insert(k).second) {
      error = "duplicate key \"" + shorten(k, 40) + "\" (each key may appear once in an object)";
      return false;
    }
    return true;
  }
  bool end_object() {
    keys.pop_back();
    --depth;
    return true;
  }
  bool start_array(std::size_t) {
    keys.emplace_back();
    return open();
  }
  bool end_array() {
    keys.pop_back();
    --depth;
    return true;
  }
  bool parse_error(std::size_t position, const std::string& token,
                   const nlohmann::detail::exception& e) {
    syntax = true;
    error_byte = position;
    error = e.what();
    if (const auto b = error.find("] "); b != std::string::npos) error = error.substr(b + 2);
    // "parse error at line 1, column 2: syntax error ..." -> "syntax error ..." (the line and
    // column are added from the byte position).
    if (error.rfind("parse error", 0) == 0)
      if (const auto c = error.find(": "); c != std::string::npos) error = error.substr(c + 2);
    if (e.id == 406) // number overflow
      error = "the number " + shorten(token, 40) + " is out of the range of a double";
    return false;
  }
};

std::string line_column(const std::string& text, std::size_t at) {
  at = std::min(at, text.size());
  const std::size_t line = 1 + std::size_t(std::count(text.begin(), text.begin() + long(at), '\n'));
  const std::size_t nl = at == 0 ? std::string::npos : text.rfind('\n', at - 1);
  const std::size_t col = nl == std::string::npos ? at + 1 : at - nl;
  return "line " + std::to_string(line) + ", column " + std::to_string(col);
}

} // namespace

std::string shorten(const std::string& s, std::size_t max) {
  if (s.size() <= max || max < 8) return s;
  const std::size_t head = (max - 3) / 3, tail = max - 3 - head;
  return s.substr(0, head) + "..." + s.substr(s.size() - tail);
}

std::string printable(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\n')
      out += "\\n";
    else if (c == '\t')
      out += "\\t";
    else if (u < 0x20 || u == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", unsigned(u));
      out += buf;
    } else
      out += c;
  }
  return out;
}

Json parse_json_text(const std::string& text, const std::string& path) {
  const char* furthest = text.data();
  CheckingSax sax;
  const bool ok = Json::sax_parse(CountingIterator{text.data(), &furthest},
                                  CountingIterator{text.data() + text.size(), &furthest}, &sax,
                                  Json::input_format_t::json, /*strict=*/true,
                                  /*ignore_comments=*/true);
  if (!ok) {
    // nlohmann's position counts characters read, one past the offending one.
    const std::size_t at = sax.syntax ? (sax.error_byte == 0 ? 0 : sax.error_byte - 1)
                                      : std::size_t(furthest - text.data());
    fail(exit_input, printable(path + ": " + line_column(text, at) + ": " +
                               (sax.syntax ? "invalid JSON: " : "") + shorten(sax.error, 160)));
  }
  try {
    return Json::parse(text, nullptr, true, /*ignore_comments=*/true);
  } catch (const Json::exception& e) { // not reached: the checking pass parsed the same text
    fail(exit_input, path + ": invalid JSON: " + shorten(e.what(), 160));
  }
}

Json read_json_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(exit_input, path + ": cannot open (" + std::string(std::strerror(errno)) + ")");
  std::string text;
  try {
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  } catch (const std::exception& e) {
    fail(exit_input, path + ": cannot read (" + e.what() + ")");
  }
  if (in.bad()) fail(exit_input, path + ": cannot read");
  return parse_json_text(text, path);
}

bool is_scene_path(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  return ext == ".json" || ext == ".JSON";
}

} // namespace ebgeom::scene
