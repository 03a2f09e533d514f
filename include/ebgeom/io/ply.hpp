// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// PLY reader: ASCII, binary little- and big-endian; every scalar type; faces as `face` lists of
/// any count and index type, and `tristrips` (strips with -1 restarts); other elements and
/// properties are skipped.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "ebgeom/core/result.hpp"
#include "ebgeom/io/byte_reader.hpp"
#include "ebgeom/io/detail/scalar_source.hpp"
#include "ebgeom/io/detail/strip.hpp"
#include "ebgeom/io/read_options.hpp"
#include "ebgeom/io/scalar_type.hpp"
#include "ebgeom/io/text_reader.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"

namespace ebgeom::io {

/// PLY property types are the shared scalar types.
using PlyType = ScalarType;

/// Encodings of the PLY body.
enum class PlyEncoding : std::uint8_t { ascii, binary_little_endian, binary_big_endian };

/// One `property` line: a scalar (`count_type == none`) or a list.
struct PlyProperty {
  std::string name;
  PlyType type = PlyType::none;
  PlyType count_type = PlyType::none;
  bool is_list() const noexcept { return count_type != PlyType::none; }
};

/// One `element` line with its properties; `line` is where it was declared.
struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
  std::uint64_t line = 0;
};

/// A parsed PLY header. `data_offset` is the first byte after `end_header`'s line break.
struct PlyHeader {
  PlyEncoding encoding = PlyEncoding::ascii;
  std::vector<PlyElement> elements;
  std::size_t data_offset = 0;
};

namespace detail {

inline PlyType ply_type_from_name(std::string_view s) noexcept {
  struct Entry {
    const char* a;
    const char* b;
    PlyType t;
  };
  static const Entry table[] = {
      {"char", "int8", PlyType::i8},      {"uchar", "uint8", PlyType::u8},
      {"short", "int16", PlyType::i16},   {"ushort", "uint16", PlyType::u16},
      {"int", "int32", PlyType::i32},     {"uint", "uint32", PlyType::u32},
      {"float", "float32", PlyType::f32}, {"double", "float64", PlyType::f64},
      {"int64", "long", PlyType::i64},    {"uint64", "ulong", PlyType::u64}};
  for (const Entry& e : table)
    if (s == e.a || s == e.b) return e.t;
  return PlyType::none;
}

inline int ply_find(const PlyElement& el, std::string_view name) noexcept {
  for (std::size_t i = 0; i < el.properties.size(); ++i)
    if (el.properties[i].name == name) return int(i);
  return -1;
}

/// Index of the list property holding a face's or strip's vertex indices, or -1.
inline int ply_index_list(const PlyElement& el) noexcept {
  for (const char* n : {"vertex_indices", "vertex_index"}) {
    const int i = ply_find(el, n);
    if (i >= 0) return i;
  }
  int found = -1;
  for (std::size_t i = 0; i < el.properties.size(); ++i)
    if (el.properties[i].is_list()) {
      if (found >= 0) return -1;
      found = int(i);
    }
  return found;
}

/// The body reader shared by ASCII and binary sources.
template <class T, class Src> class PlyBody {
 public:
  PlyBody(Src& src, const ReadOptions& opt, PolygonSoup<T>& soup, std::uint64_t nverts)
      : src_(&src), opt_(&opt), soup_(&soup), nverts_(nverts) {}

  /// Skips a whole record of `el`.
  bool skip_record(const PlyElement& el, ParseError& err) {
    for (std::size_t p = 0; p < el.properties.size(); ++p)
      if (!skip_one(el, p, err)) return false;
    return true;
  }

  bool vertices(const PlyElement& el, ParseError& err) {
    const int ix = ply_find(el, "x"), iy = ply_find(el, "y"), iz = ply_find(el, "z");
    std::uint64_t r = 0;
    if constexpr (std::is_same_v<Src, BinarySource>) r = fast_vertices(el, ix, iy, iz);
    for (; r < el.count; ++r) {
      T xyz[3] = {T(0), T(0), T(0)};
      for (std::size_t p = 0; p < el.properties.size(); ++p) {
        const int pi = int(p);
        const int k = pi == ix ? 0 : pi == iy ? 1 : pi == iz ? 2 : -1;
        if (k < 0) {
          if (!skip_one(el, p, err)) return false;
          continue;
        }
        if (!src_->real(el.properties[p].type, xyz[k]))
          return err = src_->error("coordinate ", "xyz"[k], " of vertex ", r), false;
        if (!std::isfinite(xyz[k]))
          return err = src_->fail(ErrorCode::non_finite, "vertex ", r, " has a NaN or infinite ",
                                  "xyz"[k]),
                 false;
      }
      soup_->vertices.push_back(Vec3<T>{xyz[0], xyz[1], xyz[2]});
    }
    return true;
  }

  /// Faces (`strips` false) or triangle strips.
  bool faces(const PlyElement& el, bool strips, ParseError& err) {
    const int il = ply_index_list(el);
    const PlyProperty& list = el.properties[std::size_t(il)];
    std::vector<Index> corners;
    std::uint64_t r = 0;
    if constexpr (std::is_same_v<Src, BinarySource>)
      if (!strips) r = fast_faces(el);
    for (; r < el.count; ++r) {
      for (std::size_t p = 0; p < el.properties.size(); ++p) {
        if (int(p) != il) {
          if (!skip_one(el, p, err)) return false;
          continue;
        }
        std::int64_t c = 0;
        if (!src_->integer(list.count_type, c))
          return err = src_->error("the vertex count of ", el.name, " ", r), false;
        if (c < 0)
          return err = src_->fail(ErrorCode::bad_number, el.name, " ", r, " has a negative count ",
                                  c),
                 false;
        if (!strips && c < 3)
          return err = src_->fail(ErrorCode::degenerate, "face ", r, " has ", c,
                                  " vertices (at least 3 needed)"),
                 false;
        corners.clear();
        for (std::int64_t k = 0; k < c; ++k) {
          std::int64_t v = 0;
          if (!src_->integer(list.type, v))
            return err = src_->error("vertex index ", k, " of ", el.name, " ", r), false;
          if (strips && v == -1) {
            if (!emit_strip(corners, err)) return false;
            corners.clear();
            continue;
          }
          if (v < 0 || std::uint64_t(v) >= nverts_)
            return err = src_->fail(ErrorCode::bad_index, el.name, " ", r, ": vertex index ", v,
                                    " is out of range [0, ", nverts_, ")"),
                   false;
          corners.push_back(Index(v));
        }
        if (strips) {
          if (!emit_strip(corners, err)) return false;
        } else {
          if (!count_triangles(std::uint64_t(c) - 2, err)) return false;
          soup_->add_face(corners);
        }
      }
    }
    return true;
  }

 private:
  // Binary fast paths: they consume the records they can read without any error and return how
  // many; the general loop continues from there (and reports the error, if any, precisely).
  std::uint64_t fast_vertices(const PlyElement& el, int ix, int iy, int iz) {
    std::size_t stride = 0, off[3] = {0, 0, 0};
    ScalarType ty[3] = {};
    for (std::size_t p = 0; p < el.properties.size(); ++p) {
      const PlyProperty& pr = el.properties[p];
      if (pr.is_list()) return 0;
      const int k = int(p) == ix ? 0 : int(p) == iy ? 1 : int(p) == iz ? 2 : -1;
      if (k >= 0) {
        off[k] = stride;
        ty[k] = pr.type;
      }
      stride += scalar_size(pr.type);
    }
    ByteReader& in = src_->reader();
    const Endian e = src_->endian();
    const std::uint64_t n = std::min<std::uint64_t>(el.count, in.remaining() / stride);
    const char* base = in.data();
    std::uint64_t r = 0;
    for (; r < n; ++r) {
      const char* rec = base + r * stride;
      const T x = load_as<T>(rec + off[0], ty[0], e), y = load_as<T>(rec + off[1], ty[1], e),
              z = load_as<T>(rec + off[2], ty[2], e);
      if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) break;
      soup_->vertices.push_back(Vec3<T>{x, y, z});
    }
    in.skip(r * stride);
    return r;
  }
  std::uint64_t fast_faces(const PlyElement& el) {
    if (el.properties.size() != 1) return 0;
    const PlyProperty& list = el.properties[0];
    const std::ptrdiff_t cs = std::ptrdiff_t(scalar_size(list.count_type));
    const std::ptrdiff_t is = std::ptrdiff_t(scalar_size(list.type));
    ByteReader& in = src_->reader();
    const Endian e = src_->endian();
    const char* p = in.data();
    const char* const end = p + in.remaining();
    std::vector<Index>& idx = soup_->indices;
    std::uint64_t r = 0;
    for (; r < el.count; ++r) {
      if (end - p < cs) break;
      const std::int64_t c = load_as<std::int64_t>(p, list.count_type, e);
      if (c < 3 || (end - p - cs) / is < c ||
          triangles_ + std::uint64_t(c) - 2 > opt_->max_triangles)
        break;
      const char* q = p + cs;
      const std::size_t first = idx.size();
      bool ok = true;
      for (std::int64_t k = 0; k < c; ++k) {
        const std::int64_t v = load_as<std::int64_t>(q + k * is, list.type, e);
        if (v < 0 || std::uint64_t(v) >= nverts_) {
          ok = false;
          break;
        }
        idx.push_back(Index(v));
      }
      if (!ok) {
        idx.resize(first);
        break;
      }
      soup_->offsets.push_back(Index(idx.size()));
      triangles_ += std::uint64_t(c) - 2;
      p = q + c * is;
    }
    in.skip(std::size_t(p - in.data()));
    return r;
  }

  /// Skips property `p` of one record (a scalar or a whole list).
  bool skip_one(const PlyElement& el, std::size_t p, ParseError& err) {
    const PlyProperty& pr = el.properties[p];
    if (!pr.is_list()) {
      if (!src_->skip(pr.type)) return err = src_->error("property '", pr.name, "'"), false;
      return true;
    }
    std::int64_t c = 0;
    if (!src_->integer(pr.count_type, c))
      return err = src_->error("the count of list '", pr.name, "'"), false;
    if (c < 0)
      return err = src_->fail(ErrorCode::bad_number, "negative list count ", c, " in '", pr.name,
                              "'"),
             false;
    for (std::int64_t k = 0; k < c; ++k)
      if (!src_->skip(pr.type))
        return err = src_->error("item ", k, " of list '", pr.name, "'"), false;
    return true;
  }
  bool count_triangles(std::uint64_t n, ParseError& err) {
    triangles_ += n;
    if (triangles_ > opt_->max_triangles)
      return err = src_->fail(ErrorCode::size_mismatch, "more than the limit of ",
                              opt_->max_triangles, " triangles"),
             false;
    return true;
  }
  bool emit_strip(const std::vector<Index>& s, ParseError& err) {
    return count_triangles(append_strip(*soup_, s), err);
  }

  Src* src_;
  const ReadOptions* opt_;
  PolygonSoup<T>* soup_;
  std::uint64_t nverts_;
  std::uint64_t triangles_ = 0;
};

} // namespace detail

/// Parses the header of a PLY file (also used by the tests to compare counts). Errors carry the
/// line: `bad_magic` (first line is not `ply`), `unsupported` (unknown format or property type),
/// `syntax` (unknown keyword, property before any element, duplicate element or property),
/// `bad_number` (bad element count), `truncated` (no `end_header`).
inline Result<PlyHeader, ParseError> parse_ply_header(ByteView bytes, const ReadOptions& opt) {
  TextReader in(bytes, opt.path);
  if (in.at_end()) return in.fail(ErrorCode::empty, "empty PLY file");
  const std::string_view magic = in.rest_of_line();
  if (magic != "ply")
    return in.fail(ErrorCode::bad_magic, "expected 'ply' on the first line, found ",
                   detail::quote(magic));
  PlyHeader h;
  bool have_format = false;
  for (;;) {
    in.mark();
    if (in.at_end()) return in.fail(ErrorCode::truncated, "input ends before 'end_header'");
    const std::string_view kw = in.token_in_line();
    if (kw.empty()) {
      in.skip_line();
      continue;
    }
    if (kw == "end_header") {
      if (!in.at_eol()) return in.fail(ErrorCode::syntax, "text after 'end_header'");
      in.skip_line();
      break;
    }
    if (kw == "comment" || kw == "obj_info") {
      in.skip_line();
      continue;
    }
    if (kw == "format") {
      const std::string_view f = in.token_in_line();
      if (f == "ascii")
        h.encoding = PlyEncoding::ascii;
      else if (f == "binary_little_endian")
        h.encoding = PlyEncoding::binary_little_endian;
      else if (f == "binary_big_endian")
        h.encoding = PlyEncoding::binary_big_endian;
      else
        return in.fail(ErrorCode::unsupported, "unknown PLY format ", detail::quote(f));
      if (have_format) return in.fail(ErrorCode::syntax, "second 'format' line");
      have_format = true;
      in.skip_line(); // version
      continue;
    }
    if (kw == "element") {
      PlyElement el;
      el.line = in.line();
      el.name = std::string(in.token_in_line());
      if (el.name.empty()) return in.fail(ErrorCode::syntax, "element without a name");
      for (const PlyElement& e : h.elements)
        if (e.name == el.name)
          return in.fail(ErrorCode::syntax, "duplicate element '", el.name, "' (first on line ",
                         e.line, ")");
      const NumberStatus s = in.integer_in_line(el.count);
      if (s != NumberStatus::ok) return in.number_error(s, "the count of element '", el.name, "'");
      if (!in.at_eol()) return in.fail(ErrorCode::syntax, "text after the element count");
      h.elements.push_back(std::move(el));
      in.skip_line();
      continue;
    }
    if (kw == "property") {
      if (h.elements.empty()) return in.fail(ErrorCode::syntax, "'property' before any 'element'");
      PlyProperty p;
      std::string_view t = in.token_in_line();
      if (t == "list") {
        const std::string_view ct = in.token_in_line();
        p.count_type = detail::ply_type_from_name(ct);
        if (p.count_type == PlyType::none)
          return in.fail(ErrorCode::unsupported, "unknown list count type ", detail::quote(ct));
        if (!is_integer(p.count_type))
          return in.fail(ErrorCode::unsupported, "list count type ", detail::quote(ct),
                         " is not an integer type");
        t = in.token_in_line();
      }
      p.type = detail::ply_type_from_name(t);
      if (p.type == PlyType::none)
        return in.fail(ErrorCode::unsupported, "unknown property type ", detail::quote(t));
      p.name = std::string(in.token_in_line());
      if (p.name.empty()) return in.fail(ErrorCode::syntax, "property without a name");
      PlyElement& el = h.elements.back();
      if (detail::ply_find(el, p.name) >= 0)
        return in.fail(ErrorCode::syntax, "duplicate property '", p.name, "' in element '", el.name,
                       "'");
      el.properties.push_back(std::move(p));
      in.skip_line();
      continue;
    }
    return in.fail(ErrorCode::syntax, "unknown PLY header keyword ", detail::quote(kw));
  }
  if (!have_format) return in.fail(ErrorCode::syntax, "PLY header without a 'format' line");
  h.data_offset = in.offset();
  return h;
}

/// Reads a PLY file. Vertices come from the `vertex` element's `x`, `y`, `z` (any scalar type);
/// faces from `face` (list `vertex_indices` or `vertex_index`, or its only list) and triangle
/// strips from `tristrips` (alternating winding, -1 restarts a strip, triangles with a repeated
/// vertex are dropped). Everything else is skipped. Before anything is allocated, the declared
/// counts are checked against the bytes that follow the header (`size_mismatch`). Errors carry the
/// line (ASCII) or byte offset (binary): `non_finite`, `bad_index` (negative or >= vertex count),
/// `degenerate` (face with fewer than 3 vertices), `truncated`, `bad_number`, `syntax`,
/// `empty` (no faces). O(size).
template <class T>
Result<PolygonSoup<T>, ParseError> parse_ply(ByteView bytes, const ReadOptions& opt) {
  auto hr = parse_ply_header(bytes, opt);
  if (!hr) return std::move(hr).error();
  const PlyHeader& h = *hr;
  const bool ascii = h.encoding == PlyEncoding::ascii;
  auto header_error = [&](const PlyElement& el, ErrorCode code, auto&&... parts) {
    return make_parse_error(code, opt.path, 0, el.line, parts...);
  };
  // Declared counts against the bytes that follow, before any allocation: each ASCII value
  // needs at least 2 bytes (digit and separator), each binary record its scalars and list counts.
  const std::uint64_t avail = bytes.size() - h.data_offset;
  std::uint64_t need = 0;
  const PlyElement* vert = nullptr;
  std::uint64_t face_count = 0;
  for (const PlyElement& el : h.elements) {
    std::uint64_t rec = 0;
    for (const PlyProperty& p : el.properties)
      rec += ascii ? 2 : scalar_size(p.is_list() ? p.count_type : p.type);
    if (rec > 0 && el.count > (avail + 1 - need) / rec + 0)
      return header_error(el, ErrorCode::size_mismatch, "element '", el.name, "' declares ",
                          el.count, " entries (at least ", rec, " bytes each) but only ",
                          avail - std::min(avail, need), " bytes of data remain");
    need += el.count * rec;
    if (el.name == "vertex") {
      vert = &el;
      for (const char* c : {"x", "y", "z"}) {
        const int i = detail::ply_find(el, c);
        if (i < 0)
          return header_error(el, ErrorCode::syntax, "element 'vertex' has no property '", c, "'");
        if (el.properties[std::size_t(i)].is_list())
          return header_error(el, ErrorCode::syntax, "vertex property '", c, "' is a list");
      }
      if (el.count >= std::numeric_limits<Index>::max())
        return header_error(el, ErrorCode::size_mismatch, el.count,
                            " vertices exceed the index range");
    } else if (el.name == "face" || el.name == "tristrips") {
      const int il = detail::ply_index_list(el);
      if (il < 0)
        return header_error(el, ErrorCode::syntax, "element '", el.name,
                            "' has no vertex index list");
      if (!is_integer(el.properties[std::size_t(il)].type))
        return header_error(el, ErrorCode::unsupported, "vertex indices of '", el.name,
                            "' are not of an integer type");
      if (el.name == "face") {
        face_count += el.count;
        if (face_count > opt.max_triangles)
          return header_error(el, ErrorCode::size_mismatch, "element 'face' declares ", el.count,
                              " faces, more than the limit of ", opt.max_triangles, " triangles");
      }
    }
  }
  if (!vert)
    return make_parse_error(ErrorCode::syntax, opt.path, 0, 0,
                            "PLY header has no 'vertex' element");

  PolygonSoup<T> soup;
  soup.reserve(vert->count, face_count, face_count * 3);
  ParseError err;
  auto body = [&](auto& src) -> bool {
    detail::PlyBody<T, std::decay_t<decltype(src)>> b(src, opt, soup, vert->count);
    for (const PlyElement& el : h.elements) {
      bool ok;
      if (&el == vert)
        ok = b.vertices(el, err);
      else if (el.name == "face" || el.name == "tristrips")
        ok = b.faces(el, el.name == "tristrips", err);
      else {
        ok = true;
        if (!el.properties.empty()) // without properties nothing to read, whatever its count
          for (std::uint64_t r = 0; r < el.count && ok; ++r) ok = b.skip_record(el, err);
      }
      if (!ok) return false;
    }
    return true;
  };
  if (ascii) {
    TextReader in(bytes, opt.path);
    // continue with the line count of the header
    while (in.offset() < h.data_offset) in.skip_line();
    detail::AsciiSource src(in);
    if (!body(src)) return err;
  } else {
    ByteReader in(bytes, opt.path);
    in.seek(h.data_offset);
    detail::BinarySource src(in, h.encoding == PlyEncoding::binary_little_endian ? Endian::little
                                                                                 : Endian::big);
    if (!body(src)) return err;
  }
  if (soup.face_count() == 0)
    return make_parse_error(ErrorCode::empty, opt.path, 0, 0, "PLY file without faces");
  return soup;
}

} // namespace ebgeom::io
