// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Wavefront OBJ reader: `v` and polygonal `f` statements; everything else is skipped.

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "ebgeom/core/result.hpp"
#include "ebgeom/io/read_options.hpp"
#include "ebgeom/io/text_reader.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"

namespace ebgeom::io {

/// Reads an OBJ file. `v x y z [w | r g b ...]` adds a vertex (values after z are ignored);
/// `f` adds a polygon whose corners are `v`, `v/vt`, `v/vt/vn` or `v//vn` (only `v` is used):
/// 1-based, or negative for "relative to the last vertex defined" (-1 is the last). Forward
/// references (an index past the vertices defined so far) are errors. `vt`, `vn`, `vp`, `g`,
/// `o`, `s`, `usemtl`, `mtllib`, `l`, `p`, comments (`#`, also after a statement) and any other
/// alphabetic statement are skipped. A backslash at the end of a line continues it; CRLF and a
/// UTF-8 BOM are accepted. Errors carry the line: `bad_number`, `non_finite`, `bad_index` (zero,
/// past the vertices defined so far, or before the first), `degenerate` (face with fewer than 3
/// corners), `syntax`, `size_mismatch` (more than `max_triangles`), `empty` (no faces). O(size).
template <class T>
Result<PolygonSoup<T>, ParseError> parse_obj(ByteView bytes, const ReadOptions& opt) {
  TextOptions topt;
  topt.line_continuation = true;
  TextReader in(bytes, opt.path, topt);
  PolygonSoup<T> soup;
  std::vector<Index> corners;
  std::uint64_t triangles = 0;
  for (;;) {
    in.skip_blanks();
    if (in.at_end()) break;
    const char c = in.peek();
    if (c == '\n' || c == '#') {
      in.skip_line();
      continue;
    }
    const std::string_view kw = in.token_in_line();
    if (kw == "v") {
      T x[3];
      for (int k = 0; k < 3; ++k) {
        const NumberStatus s = in.real_in_line(x[k]);
        if (s != NumberStatus::ok) return in.number_error(s, "a vertex coordinate");
        if (!std::isfinite(x[k]))
          return in.fail(ErrorCode::non_finite, "vertex coordinate ",
                         detail::quote(in.last_token()), " is not finite");
      }
      if (soup.vertices.size() >= std::numeric_limits<Index>::max())
        return in.fail(ErrorCode::size_mismatch, "more vertices than the index range holds");
      soup.vertices.push_back(Vec3<T>{x[0], x[1], x[2]});
      in.skip_line();
    } else if (kw == "f") {
      corners.clear();
      const std::uint64_t nv = soup.vertices.size();
      for (;;) {
        if (in.at_eol() || in.peek() == '#') break;
        std::int64_t v = 0;
        const NumberStatus s = in.integer_in_line(v, '/');
        if (s != NumberStatus::ok) return in.number_error(s, "a vertex index");
        // The texture and normal indices of `v/vt/vn` are not used, but the corner must be one
        // of `v`, `v/vt`, `v/vt/vn` or `v//vn` (each index an integer, perhaps negative).
        const char* q = in.cur();
        auto index_at = [&](const char*& r) {
          if (!in.is_terminator(r) && *r == '-') ++r;
          const char* first = r;
          while (!in.is_terminator(r) && *r >= '0' && *r <= '9') ++r;
          return r > first;
        };
        bool good = true;
        if (!in.is_terminator(q)) { // after `v`: "/vt", "/vt/vn" or "//vn"
          ++q;                      // the '/' that stopped the vertex index
          if (!in.is_terminator(q) && *q == '/') {
            ++q;
            good = index_at(q);
          } else {
            good = index_at(q);
            if (good && !in.is_terminator(q) && *q == '/') {
              ++q;
              good = index_at(q);
            }
          }
          good = good && in.is_terminator(q);
        }
        if (!good) {
          return in.fail(ErrorCode::syntax, "column ", in.mark_column(), ": malformed face corner ",
                         detail::quote(in.last_token()), " (expected v, v/vt, v/vt/vn or v//vn)");
        }
        in.set_cur(q);
        if (v == 0) return in.fail(ErrorCode::bad_index, "vertex index 0 (OBJ indices start at 1)");
        if (v > 0 && std::uint64_t(v) > nv)
          return in.fail(ErrorCode::bad_index, "vertex index ", v, " refers past the ", nv,
                         " vertices defined so far");
        if (v < 0 && std::uint64_t(-(v + 1)) >= nv)
          return in.fail(ErrorCode::bad_index, "relative vertex index ", v,
                         " refers before the first of the ", nv, " vertices defined so far");
        corners.push_back(Index(v > 0 ? std::uint64_t(v) - 1 : nv - std::uint64_t(-(v + 1)) - 1));
      }
      if (corners.size() < 3)
        return in.fail(ErrorCode::degenerate, "face with ", corners.size(),
                       " corners (at least 3 needed)");
      triangles += corners.size() - 2;
      if (triangles > opt.max_triangles)
        return in.fail(ErrorCode::size_mismatch, "more than the limit of ", opt.max_triangles,
                       " triangles");
      if (soup.indices.size() + corners.size() >= std::numeric_limits<Index>::max())
        return in.fail(ErrorCode::size_mismatch, "more face corners than the index range holds");
      soup.add_face(corners);
      in.skip_line();
    } else {
      const char k0 = kw.empty() ? '\0' : kw[0];
      if (!((k0 >= 'a' && k0 <= 'z') || (k0 >= 'A' && k0 <= 'Z')))
        return in.fail(ErrorCode::syntax, "unknown OBJ statement ", detail::quote(kw));
      in.skip_line(); // vt, vn, g, o, s, usemtl, mtllib, l, p and unknown statements
    }
  }
  in.mark(); // at the end
  if (soup.face_count() == 0) return in.fail(ErrorCode::empty, "OBJ file without faces");
  return soup;
}

} // namespace ebgeom::io
