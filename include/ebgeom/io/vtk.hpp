// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Legacy VTK reader: `DATASET POLYDATA`, ASCII or BINARY (big-endian), `POINTS`, `POLYGONS` and
/// `TRIANGLE_STRIPS` in the classic form and in the `OFFSETS`/`CONNECTIVITY` form of VTK 5.1.

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
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

namespace detail {

/// VTK data type names (case-insensitive); `none` when unknown or unsupported (`bit`).
inline ScalarType vtk_type_from_name(std::string_view s) noexcept {
  struct Entry {
    const char* name;
    ScalarType t;
  };
  static const Entry table[] = {
      {"unsigned_char", ScalarType::u8},   {"char", ScalarType::i8},
      {"unsigned_short", ScalarType::u16}, {"short", ScalarType::i16},
      {"unsigned_int", ScalarType::u32},   {"int", ScalarType::i32},
      {"unsigned_long", ScalarType::u64},  {"long", ScalarType::i64},
      {"float", ScalarType::f32},          {"double", ScalarType::f64},
      {"vtktypeint8", ScalarType::i8},     {"vtktypeuint8", ScalarType::u8},
      {"vtktypeint16", ScalarType::i16},   {"vtktypeuint16", ScalarType::u16},
      {"vtktypeint32", ScalarType::i32},   {"vtktypeuint32", ScalarType::u32},
      {"vtktypeint64", ScalarType::i64},   {"vtktypeuint64", ScalarType::u64},
      {"vtktypefloat32", ScalarType::f32}, {"vtktypefloat64", ScalarType::f64},
      {"vtkidtype", ScalarType::i64}};
  for (const Entry& e : table)
    if (iequals(s, e.name)) return e.t;
  return ScalarType::none;
}

} // namespace detail

/// Reads a legacy VTK file holding `DATASET POLYDATA`. Points may have any numeric type; cells
/// come from `POLYGONS` (polygons of any size) and `TRIANGLE_STRIPS` (alternating winding,
/// triangles with a repeated vertex dropped); `VERTICES`, `LINES`, `FIELD` and `METADATA`
/// sections are skipped and reading stops at `POINT_DATA`/`CELL_DATA`. Other datasets
/// (`STRUCTURED_POINTS`, `UNSTRUCTURED_GRID`, ...) get `unsupported`. Counts are checked against
/// the remaining bytes before allocating (`size_mismatch`). Errors carry the line (ASCII) or the
/// byte offset (BINARY): `bad_magic`, `syntax`, `bad_number`, `non_finite`, `bad_index`,
/// `degenerate`, `truncated`, `size_mismatch`, `empty` (no faces). O(size).
template <class T>
Result<PolygonSoup<T>, ParseError> parse_vtk(ByteView bytes, const ReadOptions& opt) {
  using detail::iequals;
  TextReader in(bytes, opt.path);
  if (in.at_end()) return in.fail(ErrorCode::empty, "empty VTK file");
  const std::string_view first = in.rest_of_line();
  if (first.size() < 5 || !iequals(first.substr(0, 5), "# vtk"))
    return in.fail(ErrorCode::bad_magic,
                   "expected '# vtk DataFile Version ...' on the first line, found ",
                   detail::quote(first));
  in.mark();
  if (in.at_end()) return in.fail(ErrorCode::truncated, "input ends before the title line");
  in.rest_of_line(); // title
  const std::string_view enc = in.token();
  const bool binary = iequals(enc, "BINARY");
  if (!binary && !iequals(enc, "ASCII")) {
    if (enc.empty()) return in.fail(ErrorCode::truncated, "input ends before 'ASCII' or 'BINARY'");
    return in.fail(ErrorCode::syntax, "expected 'ASCII' or 'BINARY', found ", detail::quote(enc));
  }
  in.skip_line();
  const std::string_view ds = in.token();
  if (!iequals(ds, "DATASET")) {
    if (ds.empty()) return in.fail(ErrorCode::truncated, "input ends before 'DATASET'");
    return in.fail(ErrorCode::syntax, "expected 'DATASET', found ", detail::quote(ds));
  }
  const std::string_view type = in.token_in_line();
  if (!iequals(type, "POLYDATA"))
    return in.fail(ErrorCode::unsupported, "VTK dataset ", detail::quote(type),
                   " is not supported (only POLYDATA)");
  in.skip_line();

  PolygonSoup<T> soup;
  ByteReader bin(bytes, opt.path);
  ParseError err;
  bool have_points = false;
  std::uint64_t triangles = 0;
  std::vector<Index> corners;
  // Errors at a keyword: the line in ASCII files; in BINARY files lines are not counted past the
  // first binary block, so the byte offset is given.
  auto fail_kw = [&](ErrorCode code, const auto&... parts) -> ParseError {
    if (binary) return make_parse_error(code, opt.path, in.mark_offset(), 0, parts...);
    return in.fail(code, parts...);
  };
  // Runs `fn(source)` on the data after the current (section header) line.
  auto run = [&](auto&& fn) -> bool {
    if (binary) {
      bin.seek(in.offset());
      detail::BinarySource src(bin, Endian::big);
      const bool ok = fn(src);
      in.set_cur(bytes.data() + bin.offset());
      return ok;
    }
    detail::AsciiSource src(in);
    return fn(src);
  };
  auto remaining = [&]() -> std::uint64_t { return bytes.size() - in.offset(); };
  auto read_count = [&](std::uint64_t& v, const char* what) -> bool {
    const NumberStatus s = in.integer_in_line(v);
    if (s != NumberStatus::ok) return err = in.number_error(s, what), false;
    return true;
  };
  auto read_type = [&](ScalarType& t) -> bool {
    const std::string_view name = in.token_in_line();
    t = detail::vtk_type_from_name(name);
    if (t == ScalarType::none)
      return err = fail_kw(ErrorCode::unsupported, "VTK data type ", detail::quote(name),
                           " is not supported"),
             false;
    return true;
  };
  // One cell's corners are in `corners`: appends a polygon or a strip.
  auto emit = [&](bool strips, std::uint64_t cell, auto& src) -> bool {
    std::uint64_t added;
    if (strips) {
      added = detail::append_strip(soup, corners);
    } else {
      if (corners.size() < 3)
        return err = src.fail(ErrorCode::degenerate, "polygon ", cell, " has ", corners.size(),
                              " vertices (at least 3 needed)"),
               false;
      soup.add_face(corners);
      added = corners.size() - 2;
    }
    triangles += added;
    if (triangles > opt.max_triangles)
      return err = src.fail(ErrorCode::size_mismatch, "more than the limit of ", opt.max_triangles,
                            " triangles"),
             false;
    return true;
  };
  auto read_index = [&](auto& src, ScalarType t, std::uint64_t cell) -> bool {
    std::int64_t v = 0;
    if (!src.integer(t, v)) return err = src.error("a point index of cell ", cell), false;
    if (v < 0 || std::uint64_t(v) >= soup.vertices.size())
      return err = src.fail(ErrorCode::bad_index, "cell ", cell, ": point index ", v,
                            " is out of range [0, ", soup.vertices.size(), ")"),
             false;
    corners.push_back(Index(v));
    return true;
  };

  for (;;) {
    const std::string_view kw = in.token();
    if (kw.empty()) break;
    if (iequals(kw, "POINTS")) {
      std::uint64_t n = 0;
      ScalarType t;
      if (!read_count(n, "the number of points") || !read_type(t)) return err;
      if (have_points) return fail_kw(ErrorCode::syntax, "second POINTS section");
      in.skip_line();
      const std::uint64_t per = 3 * (binary ? scalar_size(t) : 2);
      if (n > remaining() / per + (binary ? 0 : 1))
        return fail_kw(ErrorCode::size_mismatch, "POINTS declares ", n, " points (at least ", per,
                       " bytes each) but only ", remaining(), " bytes follow");
      if (n >= std::numeric_limits<Index>::max())
        return fail_kw(ErrorCode::size_mismatch, n, " points exceed the index range");
      have_points = true;
      soup.vertices.reserve(n);
      const bool ok = run([&](auto& src) {
        for (std::uint64_t i = 0; i < n; ++i) {
          T x[3];
          for (int k = 0; k < 3; ++k) {
            if (!src.real(t, x[k]))
              return err = src.error("coordinate ", "xyz"[k], " of point ", i), false;
            if (!std::isfinite(x[k]))
              return err = src.fail(ErrorCode::non_finite, "point ", i, " has a NaN or infinite ",
                                    "xyz"[k]),
                     false;
          }
          soup.vertices.push_back(Vec3<T>{x[0], x[1], x[2]});
        }
        return true;
      });
      if (!ok) return err;
    } else if (iequals(kw, "POLYGONS") || iequals(kw, "TRIANGLE_STRIPS") ||
               iequals(kw, "VERTICES") || iequals(kw, "LINES")) {
      const std::string section(kw);
      const std::size_t sec_off = in.mark_offset();
      const std::uint64_t sec_line = binary ? 0 : in.line();
      auto fail_sec = [&](ErrorCode code, const auto&... parts) {
        return make_parse_error(code, opt.path, sec_off, sec_line, parts...);
      };
      const bool strips = iequals(kw, "TRIANGLE_STRIPS");
      const bool keep = strips || iequals(kw, "POLYGONS");
      std::uint64_t a = 0, b = 0;
      if (!read_count(a, "the number of cells") || !read_count(b, "the size of the cell list"))
        return err;
      in.skip_line();
      TextReader peek = in;
      if (iequals(in.token(), "OFFSETS")) {
        // VTK 5.1: OFFSETS (a values) then CONNECTIVITY (b values)
        ScalarType ot, ct;
        if (!read_type(ot)) return err;
        in.skip_line();
        const std::uint64_t per = binary ? scalar_size(ot) : 2;
        if (a > remaining() / per + 1)
          return fail_kw(ErrorCode::size_mismatch, section, " declares ", a, " offsets but only ",
                         remaining(), " bytes follow");
        std::vector<std::int64_t> offs;
        offs.reserve(a);
        const bool ok = run([&](auto& src) {
          for (std::uint64_t i = 0; i < a; ++i) {
            std::int64_t v = 0;
            if (!src.integer(ot, v)) return err = src.error("offset ", i), false;
            if (v < 0 || std::uint64_t(v) > b || (i == 0 && v != 0) || (i > 0 && v < offs.back()))
              return err =
                         src.fail(ErrorCode::size_mismatch, "offset ", i, " = ", v,
                                  " is not a non-decreasing offset in [0, ", b, "] starting at 0"),
                     false;
            offs.push_back(v);
          }
          if (a > 0 && std::uint64_t(offs.back()) != b)
            return err = src.fail(ErrorCode::size_mismatch, "the last offset is ", offs.back(),
                                  " but CONNECTIVITY has ", b, " values"),
                   false;
          return true;
        });
        if (!ok) return err;
        if (!iequals(in.token(), "CONNECTIVITY"))
          return fail_kw(ErrorCode::syntax, "expected 'CONNECTIVITY', found ",
                         detail::quote(in.last_token()));
        if (!read_type(ct)) return err;
        in.skip_line();
        const std::uint64_t cper = binary ? scalar_size(ct) : 2;
        if (b > remaining() / cper + 1)
          return fail_kw(ErrorCode::size_mismatch, "CONNECTIVITY declares ", b, " values but only ",
                         remaining(), " bytes follow");
        const bool ok2 = run([&](auto& src) {
          for (std::uint64_t c = 0; c + 1 < offs.size(); ++c) {
            corners.clear();
            for (std::int64_t j = offs[c]; j < offs[c + 1]; ++j) {
              if (!keep) {
                if (!src.skip(ct)) return err = src.error("a point index of cell ", c), false;
              } else if (!read_index(src, ct, c)) {
                return false;
              }
            }
            if (keep && !emit(strips, c, src)) return false;
          }
          return true;
        });
        if (!ok2) return err;
        continue;
      }
      in = peek;
      // classic form: a cells, b values in all (each cell: its size, then its point indices)
      const std::uint64_t per = binary ? 4 : 2;
      if (b > remaining() / per + 1)
        return fail_kw(ErrorCode::size_mismatch, section, " declares ", b, " values but only ",
                       remaining(), " bytes follow");
      if (a > b)
        return fail_kw(ErrorCode::size_mismatch, section, " declares ", a, " cells in ", b,
                       " values");
      const bool ok = run([&](auto& src) {
        std::uint64_t used = 0;
        for (std::uint64_t c = 0; c < a; ++c) {
          std::int64_t k = 0;
          if (!src.integer(ScalarType::i32, k))
            return err = src.error("the size of cell ", c), false;
          if (k < 0 || std::uint64_t(k) + 1 > b - used)
            return err = src.fail(ErrorCode::size_mismatch, "cell ", c, " declares ", k,
                                  " points but only ", b - used - (used < b ? 1 : 0), " values of ",
                                  section, " remain"),
                   false;
          used += std::uint64_t(k) + 1;
          corners.clear();
          for (std::int64_t j = 0; j < k; ++j) {
            if (!keep) {
              if (!src.skip(ScalarType::i32))
                return err = src.error("a point index of cell ", c), false;
            } else if (!read_index(src, ScalarType::i32, c)) {
              return false;
            }
          }
          if (keep && !emit(strips, c, src)) return false;
        }
        if (used != b)
          return err = fail_sec(ErrorCode::size_mismatch, section, " declares ", b,
                                " values but its ", a, " cells use ", used),
                 false;
        return true;
      });
      if (!ok) return err;
    } else if (iequals(kw, "METADATA")) {
      in.skip_line();
      while (!in.at_end()) { // up to an empty line
        const std::string_view l = in.rest_of_line();
        bool blank = true;
        for (char ch : l) blank = blank && detail::is_blank(ch);
        if (blank) break;
      }
    } else if (iequals(kw, "FIELD")) {
      in.token_in_line(); // name
      std::uint64_t arrays = 0;
      if (!read_count(arrays, "the number of field arrays")) return err;
      in.skip_line();
      for (std::uint64_t i = 0; i < arrays; ++i) {
        in.token(); // array name
        std::uint64_t comps = 0, tuples = 0;
        ScalarType t;
        if (!read_count(comps, "the number of components") ||
            !read_count(tuples, "the number of tuples") || !read_type(t))
          return err;
        in.skip_line();
        const std::uint64_t per = binary ? scalar_size(t) : 2;
        if (comps != 0 && tuples > remaining() / per / comps + 1)
          return fail_kw(ErrorCode::size_mismatch, "field array declares ", comps, " x ", tuples,
                         " values but only ", remaining(), " bytes follow");
        const std::uint64_t n = comps * tuples;
        const bool ok = run([&](auto& src) {
          for (std::uint64_t j = 0; j < n; ++j)
            if (!src.skip(t)) return err = src.error("field value ", j), false;
          return true;
        });
        if (!ok) return err;
      }
    } else if (iequals(kw, "POINT_DATA") || iequals(kw, "CELL_DATA")) {
      break; // attributes are not needed
    } else {
      return fail_kw(ErrorCode::syntax, "unknown VTK POLYDATA section ", detail::quote(kw));
    }
  }
  if (!have_points) return fail_kw(ErrorCode::empty, "VTK file without POINTS");
  if (soup.face_count() == 0)
    return fail_kw(ErrorCode::empty, "VTK file without POLYGONS or TRIANGLE_STRIPS");
  return soup;
}

} // namespace ebgeom::io
