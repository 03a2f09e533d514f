// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// STL reader (ASCII and binary). STL stores three vertices per triangle; by default exact
/// duplicates are welded (`ReadOptions::stl_vertices`). Facet normals are ignored (the winding
/// defines the orientation).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "ebgeom/core/result.hpp"
#include "ebgeom/io/byte_reader.hpp"
#include "ebgeom/io/detail/exact_weld.hpp"
#include "ebgeom/io/read_options.hpp"
#include "ebgeom/io/text_reader.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"

namespace ebgeom::io {

namespace detail {

/// Does the text start (after a BOM and blanks) with the keyword `solid`?
inline bool starts_with_solid(ByteView b) noexcept {
  std::size_t i = 0;
  if (b.size() >= 3 && (unsigned char)b[0] == 0xEF && (unsigned char)b[1] == 0xBB &&
      (unsigned char)b[2] == 0xBF)
    i = 3;
  while (i < b.size() && is_space(b[i])) ++i;
  if (b.size() - i < 5 || !iequals(b.substr(i, 5), "solid")) return false;
  return b.size() - i == 5 || is_space(b[i + 5]);
}

/// Appends a vertex, welded or not.
template <class T> struct StlVertexSink {
  StlVertexSink(PolygonSoup<T>& out, StlVertices mode, std::size_t expected)
      : soup(&out), weld(mode == StlVertices::weld_exact),
        welder(out.vertices, weld ? expected : 0) {}
  Index add(const Vec3<T>& p) { return weld ? welder.insert(p) : soup->add_vertex(p); }
  PolygonSoup<T>* soup;
  bool weld;
  ExactWelder<T> welder;
};

} // namespace detail

/// True when `bytes` is a binary STL by the size rule: the uint32 at byte 80 is a triangle count
/// n with 84 + 50 n == size. A file that does not start with `solid` is also binary when
/// 84 + 50 n <= size (trailing bytes are tolerated). O(1).
inline bool is_binary_stl(ByteView bytes) noexcept {
  if (bytes.size() < 84) return false;
  const std::uint64_t n = detail::load<std::uint32_t>(bytes.data() + 80, Endian::little);
  const std::uint64_t need = 84 + 50 * n;
  if (need == bytes.size()) return true;
  return !detail::starts_with_solid(bytes) && need <= bytes.size();
}

/// Reads a binary STL: 80-byte header, uint32 count n, n records of 12 little-endian floats
/// (normal, 3 vertices) and a uint16. Errors carry byte offsets: `truncated` (no full header),
/// `size_mismatch` (n records do not fit in the data, or n > `max_triangles`; checked before
/// allocating), `empty` (n == 0), `non_finite` (NaN/Inf vertex coordinate). O(n).
template <class T>
Result<PolygonSoup<T>, ParseError> parse_stl_binary(ByteView bytes, const ReadOptions& opt) {
  ByteReader in(bytes, opt.path);
  std::uint32_t n = 0;
  if (!in.skip(80) || !in.read_le(n))
    return in.fail_at(bytes.size(), ErrorCode::truncated,
                      "binary STL needs an 80-byte header and a uint32 count (", bytes.size(),
                      " bytes)");
  const std::uint64_t need = std::uint64_t(n) * 50; // trailing bytes are tolerated
  if (n > opt.max_triangles)
    return in.fail_at(80, ErrorCode::size_mismatch, "header declares ", n,
                      " triangles, more than the limit of ", opt.max_triangles);
  if (in.remaining() < need)
    return in.fail_at(80, ErrorCode::size_mismatch, "header declares ", n, " triangles (", need,
                      " bytes) but only ", in.remaining(), " bytes follow");
  if (n == 0) return in.fail_at(80, ErrorCode::empty, "binary STL with 0 triangles");
  PolygonSoup<T> soup;
  const bool weld = opt.stl_vertices == StlVertices::weld_exact;
  soup.reserve(weld ? n / 2 + 16 : std::size_t(n) * 3, n, std::size_t(n) * 3);
  detail::StlVertexSink<T> sink(soup, opt.stl_vertices, n / 2 + 16);
  const char* base = in.data();
  // Batches of triangles: load and check, then prefetch the weld table's slots and the vertices
  // they hold, then weld in order (the table lookups are the cost of this loop).
  constexpr std::uint32_t batch = 16;
  Vec3<T> p[3 * batch];
  std::size_t h[3 * batch];
  for (std::uint32_t first = 0; first < n; first += batch) {
    const std::uint32_t count = std::min(batch, n - first);
    for (std::uint32_t t = 0; t < count; ++t) {
      const char* rec = base + std::size_t(first + t) * 50;
      for (int k = 0; k < 3; ++k) {
        const char* q = rec + 12 + 12 * k;
        const float x = detail::load<float>(q, Endian::little);
        const float y = detail::load<float>(q + 4, Endian::little);
        const float z = detail::load<float>(q + 8, Endian::little);
        if (EBGEOM_UNLIKELY(!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)))
          return in.fail_at(std::size_t(q - bytes.data()), ErrorCode::non_finite, "triangle ",
                            first + t, " vertex ", k, " has a NaN or infinite coordinate");
        p[3 * t + k] = Vec3<T>{T(x), T(y), T(z)};
      }
    }
    if (!weld) {
      for (std::uint32_t t = 0; t < count; ++t) {
        const Index a = soup.add_vertex(p[3 * t]), b = soup.add_vertex(p[3 * t + 1]);
        soup.add_triangle(a, b, soup.add_vertex(p[3 * t + 2]));
      }
      continue;
    }
    auto& w = sink.welder;
    for (std::uint32_t k = 0; k < 3 * count; ++k) {
      p[k] = w.canonical(p[k]);
      h[k] = w.hash(p[k]);
      w.prefetch(h[k]);
    }
    for (std::uint32_t k = 0; k < 3 * count; ++k) w.prefetch_vertex(h[k]);
    for (std::uint32_t t = 0; t < count; ++t) {
      const Index a = w.insert_canonical(p[3 * t], h[3 * t]);
      const Index b = w.insert_canonical(p[3 * t + 1], h[3 * t + 1]);
      soup.add_triangle(a, b, w.insert_canonical(p[3 * t + 2], h[3 * t + 2]));
    }
  }
  return soup;
}

/// Reads an ASCII STL: one or more `solid [name] ... endsolid [name]` blocks of
/// `facet normal nx ny nz / outer loop / vertex x y z (3 or more) / endloop / endfacet`.
/// Keywords are case-insensitive; CRLF and a UTF-8 BOM are accepted. Errors carry the line:
/// `syntax` (unexpected keyword), `bad_number`, `non_finite`, `degenerate` (a facet with fewer
/// than 3 vertices), `truncated` (input ends inside a solid), `empty`, `size_mismatch` (more than
/// `max_triangles`). O(size).
template <class T>
Result<PolygonSoup<T>, ParseError> parse_stl_ascii(ByteView bytes, const ReadOptions& opt) {
  using detail::iequals;
  TextReader in(bytes, opt.path);
  PolygonSoup<T> soup;
  detail::StlVertexSink<T> sink(soup, opt.stl_vertices, bytes.size() / 200);
  std::vector<Index> corners;
  std::uint64_t triangles = 0;
  in.skip_space();
  if (in.at_end()) return in.fail(ErrorCode::empty, "empty STL file");
  auto expect = [&](const char* kw) -> bool { return iequals(in.token(), kw); };
  for (;;) {
    const std::string_view tok = in.token();
    if (tok.empty()) break;
    if (!iequals(tok, "solid"))
      return in.fail(ErrorCode::syntax, "expected 'solid', found ", detail::quote(tok));
    in.rest_of_line(); // the solid's name
    for (;;) {
      std::string_view kw = in.token();
      if (kw.empty())
        return in.fail(ErrorCode::truncated, "input ends inside a solid (no 'endsolid')");
      if (iequals(kw, "endsolid")) {
        in.rest_of_line();
        break;
      }
      if (!iequals(kw, "facet"))
        return in.fail(ErrorCode::syntax, "expected 'facet' or 'endsolid', found ",
                       detail::quote(kw));
      if (!expect("normal"))
        return in.fail(ErrorCode::syntax, "expected 'normal', found ",
                       detail::quote(in.last_token()));
      for (int k = 0; k < 3; ++k) {
        double nk; // normals are ignored; NaN normals (common in the wild) are accepted
        const NumberStatus s = in.real(nk);
        if (s != NumberStatus::ok && s != NumberStatus::out_of_range)
          return in.number_error(s, "a normal component");
      }
      if (!expect("outer"))
        return in.fail(ErrorCode::syntax, "expected 'outer loop', found ",
                       detail::quote(in.last_token()));
      if (!expect("loop"))
        return in.fail(ErrorCode::syntax, "expected 'loop', found ",
                       detail::quote(in.last_token()));
      corners.clear();
      const std::uint64_t facet_line = in.line();
      for (;;) {
        kw = in.token();
        if (iequals(kw, "endloop")) break;
        if (!iequals(kw, "vertex")) {
          if (kw.empty()) return in.fail(ErrorCode::truncated, "input ends inside a facet");
          return in.fail(ErrorCode::syntax, "expected 'vertex' or 'endloop', found ",
                         detail::quote(kw));
        }
        T x[3];
        for (int k = 0; k < 3; ++k) {
          const NumberStatus s = in.real(x[k]);
          if (s != NumberStatus::ok) return in.number_error(s, "a vertex coordinate");
          if (!std::isfinite(x[k]))
            return in.fail(ErrorCode::non_finite, "vertex coordinate ",
                           detail::quote(in.last_token()), " is not finite");
        }
        corners.push_back(sink.add(Vec3<T>{x[0], x[1], x[2]}));
      }
      if (corners.size() < 3)
        return in.fail(ErrorCode::degenerate, "facet starting on line ", facet_line, " has ",
                       corners.size(), " vertices (at least 3 needed)");
      triangles += corners.size() - 2;
      if (triangles > opt.max_triangles)
        return in.fail(ErrorCode::size_mismatch, "more than the limit of ", opt.max_triangles,
                       " triangles");
      soup.add_face(corners);
      if (!expect("endfacet"))
        return in.fail(ErrorCode::syntax, "expected 'endfacet', found ",
                       detail::quote(in.last_token()));
    }
  }
  in.mark(); // at the end
  if (soup.face_count() == 0) return in.fail(ErrorCode::empty, "STL file without facets");
  return soup;
}

/// Reads an STL, deciding ASCII or binary by content: binary when `is_binary_stl`, ASCII when the
/// text starts with `solid`, otherwise binary (which then reports what is wrong). An empty input
/// gets `ErrorCode::empty`.
template <class T>
Result<PolygonSoup<T>, ParseError> parse_stl(ByteView bytes, const ReadOptions& opt) {
  if (bytes.empty()) return make_parse_error(ErrorCode::empty, opt.path, 0, 0, "empty STL file");
  if (!is_binary_stl(bytes) && detail::starts_with_solid(bytes))
    return parse_stl_ascii<T>(bytes, opt);
  return parse_stl_binary<T>(bytes, opt);
}

} // namespace ebgeom::io
