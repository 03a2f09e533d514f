// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Object File Format (OFF, from Geomview) reader: ASCII and binary. Vertices and polygonal
/// faces; colours, normals and texture coordinates are skipped.

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "ebgeom/core/result.hpp"
#include "ebgeom/io/byte_reader.hpp"
#include "ebgeom/io/read_options.hpp"
#include "ebgeom/io/text_reader.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"

namespace ebgeom::io {

namespace detail {

/// The OFF header keyword: `[ST][C][N][4][n]OFF`, optionally followed (after blanks) by `BINARY`;
/// blank space and `#` comment lines may come before it.
struct OffHeader {
  bool valid = false;
  bool homogeneous = false; ///< `4`: vertices carry a fourth coordinate
  bool ndim = false;        ///< `n`: a dimension follows the keyword
  bool binary = false;
  std::size_t keyword_end = 0; ///< offset after the keyword (and `BINARY`)
};

/// Parses the OFF keyword at the start of `t` (after a BOM, blank space and comments). O(size of
/// the leading comments).
inline OffHeader off_header(std::string_view t) noexcept {
  OffHeader h;
  std::size_t i = 0;
  if (t.size() >= 3 && (unsigned char)t[0] == 0xEF && (unsigned char)t[1] == 0xBB &&
      (unsigned char)t[2] == 0xBF)
    i = 3;
  for (;;) {
    while (i < t.size() && is_space(t[i])) ++i;
    if (i >= t.size() || t[i] != '#') break;
    while (i < t.size() && t[i] != '\n') ++i;
  }
  if (t.substr(i, 2) == "ST") i += 2;
  if (t.substr(i, 1) == "C") i += 1;
  if (t.substr(i, 1) == "N") i += 1;
  if (t.substr(i, 1) == "4") {
    h.homogeneous = true;
    i += 1;
  }
  if (t.substr(i, 1) == "n") {
    h.ndim = true;
    i += 1;
  }
  if (t.substr(i, 3) != "OFF") return h;
  i += 3;
  // the keyword ends at a blank, a line break, the end or a '#'
  if (i < t.size() && !is_space(t[i]) && t[i] != '#') return h;
  h.valid = true;
  std::size_t j = i;
  while (j < t.size() && is_blank(t[j])) ++j;
  if (t.substr(j, 6) == "BINARY" && (j + 6 == t.size() || is_space(t[j + 6]))) {
    h.binary = true;
    i = j + 6;
    // the binary data starts after the header line
    while (i < t.size() && t[i] != '\n') ++i;
    if (i < t.size()) ++i;
  }
  h.keyword_end = i;
  return h;
}

/// Skips blanks, line breaks and `#` comments.
inline void off_skip(TextReader& in) noexcept {
  for (;;) {
    in.skip_space();
    if (in.peek() != '#') return;
    in.skip_line();
  }
}

/// Bytes of text at least needed per vertex ("0 0 0\n") and per face ("3 0 1 2\n"): counts are
/// checked against the input size before anything is allocated.
inline constexpr std::uint64_t off_min_vertex_bytes = 6;
inline constexpr std::uint64_t off_min_face_bytes = 8;

} // namespace detail

/// True when `bytes` starts (after a BOM, blank space and `#` comment lines) with an OFF keyword
/// (`OFF`, `COFF`, `NOFF`, `STOFF`, `4OFF`, `nOFF`, ...).
inline bool is_off(ByteView bytes) noexcept { return detail::off_header(bytes).valid; }

namespace detail {

template <class T>
Result<PolygonSoup<T>, ParseError> parse_off_binary(ByteView bytes, std::size_t start,
                                                    const ReadOptions& opt) {
  ByteReader in(bytes, opt.path);
  in.seek(start);
  std::int32_t nv = 0, nf = 0, ne = 0;
  if (!in.read_be(nv) || !in.read_be(nf) || !in.read_be(ne))
    return in.fail_at(bytes.size(), ErrorCode::truncated,
                      "binary OFF needs three big-endian int32 counts after 'OFF BINARY'");
  if (nv < 0 || nf < 0)
    return in.fail_at(start, ErrorCode::size_mismatch, "negative count in the header (", nv,
                      " vertices, ", nf, " faces)");
  if (nf == 0) return in.fail_at(start, ErrorCode::empty, "OFF file with 0 faces");
  if (std::uint64_t(nf) > opt.max_triangles)
    return in.fail_at(start, ErrorCode::size_mismatch, "header declares ", nf,
                      " faces, more than the limit of ", opt.max_triangles, " triangles");
  // each vertex takes 12 bytes, each face at least 16 (count, 3 indices... counted loosely)
  const std::uint64_t need = std::uint64_t(nv) * 12 + std::uint64_t(nf) * 16;
  if (need > in.remaining())
    return in.fail_at(start, ErrorCode::size_mismatch, "header declares ", nv, " vertices and ", nf,
                      " faces (at least ", need, " bytes) but only ", in.remaining(),
                      " bytes follow");
  PolygonSoup<T> soup;
  soup.reserve(std::size_t(nv), std::size_t(nf), std::size_t(nf) * 3);
  for (std::int32_t v = 0; v < nv; ++v) {
    const std::size_t at = in.offset();
    float x[3];
    in.read_be(x); // fits: checked above
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
      return in.fail_at(at, ErrorCode::non_finite, "vertex ", v,
                        " has a NaN or infinite coordinate");
    soup.add_vertex(Vec3<T>{T(x[0]), T(x[1]), T(x[2])});
  }
  std::vector<Index> corners;
  std::uint64_t triangles = 0;
  for (std::int32_t f = 0; f < nf; ++f) {
    const std::size_t at = in.offset();
    std::int32_t n = 0;
    if (!in.read_be(n)) return in.fail(ErrorCode::truncated, "input ends at face ", f, " of ", nf);
    if (n < 3)
      return in.fail_at(at, ErrorCode::degenerate, "face ", f, " with ", n,
                        " corners (at least 3 needed)");
    if (std::uint64_t(n) * 4 > in.remaining())
      return in.fail_at(at, ErrorCode::truncated, "face ", f, " declares ", n, " corners but only ",
                        in.remaining(), " bytes follow");
    corners.clear();
    for (std::int32_t k = 0; k < n; ++k) {
      const std::size_t iat = in.offset();
      std::int32_t i = 0;
      in.read_be(i);
      if (i < 0 || i >= nv)
        return in.fail_at(iat, ErrorCode::bad_index, "face ", f, " has vertex index ", i,
                          " outside 0..", nv - 1);
      corners.push_back(Index(i));
    }
    std::int32_t ncolor = 0;
    if (!in.read_be(ncolor))
      return in.fail(ErrorCode::truncated, "input ends in face ", f, " (colour count)");
    if (ncolor < 0 || ncolor > 4)
      return in.fail_at(in.offset() - 4, ErrorCode::syntax, "face ", f, " has ", ncolor,
                        " colour components (0 to 4 expected)");
    if (!in.skip(std::size_t(ncolor) * 4))
      return in.fail(ErrorCode::truncated, "input ends in face ", f, "'s colour");
    triangles += std::uint64_t(n) - 2;
    if (triangles > opt.max_triangles)
      return in.fail_at(at, ErrorCode::size_mismatch, "more than the limit of ", opt.max_triangles,
                        " triangles");
    if (soup.indices.size() + corners.size() >= std::numeric_limits<Index>::max())
      return in.fail_at(at, ErrorCode::size_mismatch,
                        "more face corners than the index range holds");
    soup.add_face(corners);
  }
  return soup;
}

} // namespace detail

/// Reads an OFF file. ASCII: the keyword `[ST][C][N]OFF` (`4OFF`, `nOFF` are `unsupported`),
/// then the counts `vertices faces edges` (the edge count is ignored; it may be missing), then
/// one vertex per line (`x y z`, values after z such as normals or colours are skipped), then one
/// face per line (`n i0 ... i(n-1)`, 0-based; a colour after the indices is skipped). `#`
/// comments and blank lines may appear anywhere. Binary (`OFF BINARY` on the first line):
/// big-endian int32 counts, float32 vertices, and per face int32 `n`, n int32 indices, int32
/// colour count and that many float32. Counts are checked against the input size before
/// anything is allocated. Errors carry the line (ASCII) or byte offset (binary): `bad_magic`,
/// `bad_number`, `non_finite`, `bad_index` (outside 0..vertices-1), `degenerate` (a face with
/// fewer than 3 corners), `truncated`, `size_mismatch` (counts larger than the data or than
/// `max_triangles`), `syntax` (extra values on a count line), `empty` (no faces). O(size).
template <class T>
Result<PolygonSoup<T>, ParseError> parse_off(ByteView bytes, const ReadOptions& opt) {
  const detail::OffHeader h = detail::off_header(bytes);
  if (!h.valid) {
    TextReader in(bytes, opt.path);
    detail::off_skip(in);
    return in.fail(ErrorCode::bad_magic, "expected the OFF keyword, found ",
                   detail::quote(in.token_in_line()));
  }
  if (h.homogeneous || h.ndim) {
    TextReader in(bytes, opt.path);
    detail::off_skip(in);
    return in.fail(ErrorCode::unsupported, "OFF variant ", detail::quote(in.token_in_line()),
                   " (4D or n-dimensional vertices) is not supported");
  }
  if (h.binary) return detail::parse_off_binary<T>(bytes, h.keyword_end, opt);

  TextReader in(bytes, opt.path);
  detail::off_skip(in);
  in.token_in_line(); // the keyword
  std::uint64_t counts[3] = {0, 0, 0};
  detail::off_skip(in);
  for (int k = 0; k < 3; ++k) {
    if (k == 2 && (in.at_eol() || in.peek() == '#')) break; // the edge count is often left out
    const NumberStatus s = k == 0 ? in.integer(counts[k]) : in.integer_in_line(counts[k]);
    if (s != NumberStatus::ok)
      return in.number_error(s, k == 0   ? "the vertex count"
                                : k == 1 ? "the face count"
                                         : "the edge count");
  }
  if (!in.at_eol() && in.peek() != '#')
    return in.fail(ErrorCode::syntax, "unexpected ", detail::quote(in.token_in_line()),
                   " after the counts (expected 'vertices faces edges')");
  const std::uint64_t nv = counts[0], nf = counts[1];
  in.mark();
  if (nf == 0) return in.fail(ErrorCode::empty, "OFF file with 0 faces");
  if (nf > opt.max_triangles)
    return in.fail(ErrorCode::size_mismatch, "header declares ", nf,
                   " faces, more than the limit of ", opt.max_triangles, " triangles");
  if (nv >= std::numeric_limits<Index>::max())
    return in.fail(ErrorCode::size_mismatch, "header declares ", nv,
                   " vertices, more than the index range holds");
  const std::uint64_t left = std::uint64_t(in.end() - in.cur());
  if (nv * detail::off_min_vertex_bytes + nf * detail::off_min_face_bytes > left + 1)
    return in.fail(ErrorCode::size_mismatch, "header declares ", nv, " vertices and ", nf,
                   " faces but only ", left, " bytes follow");
  PolygonSoup<T> soup;
  soup.reserve(std::size_t(nv), std::size_t(nf), std::size_t(nf) * 3);
  for (std::uint64_t v = 0; v < nv; ++v) {
    detail::off_skip(in);
    T x[3];
    for (int k = 0; k < 3; ++k) {
      const NumberStatus s = in.real_in_line(x[k]);
      if (s != NumberStatus::ok) return in.number_error(s, "a coordinate of vertex ", v);
      if (!std::isfinite(x[k]))
        return in.fail(ErrorCode::non_finite, "coordinate ", detail::quote(in.last_token()),
                       " of vertex ", v, " is not finite");
    }
    soup.add_vertex(Vec3<T>{x[0], x[1], x[2]});
    in.skip_line(); // normals, colours, texture coordinates
  }
  std::vector<Index> corners;
  std::uint64_t triangles = 0;
  for (std::uint64_t f = 0; f < nf; ++f) {
    detail::off_skip(in);
    std::uint64_t n = 0;
    NumberStatus s = in.integer_in_line(n);
    if (s != NumberStatus::ok) return in.number_error(s, "the corner count of face ", f);
    if (n < 3)
      return in.fail(ErrorCode::degenerate, "face ", f, " with ", n,
                     " corners (at least 3 needed)");
    if (n > std::uint64_t(in.end() - in.cur()))
      return in.fail(ErrorCode::size_mismatch, "face ", f, " declares ", n,
                     " corners, more than the rest of the input holds");
    corners.clear();
    for (std::uint64_t k = 0; k < n; ++k) {
      std::int64_t i = 0;
      s = in.integer_in_line(i);
      if (s != NumberStatus::ok) return in.number_error(s, "a vertex index of face ", f);
      if (i < 0 || std::uint64_t(i) >= nv)
        return in.fail(ErrorCode::bad_index, "vertex index ", i, " of face ", f, " is outside 0..",
                       nv == 0 ? 0 : nv - 1);
      corners.push_back(Index(i));
    }
    triangles += n - 2;
    if (triangles > opt.max_triangles)
      return in.fail(ErrorCode::size_mismatch, "more than the limit of ", opt.max_triangles,
                     " triangles");
    if (soup.indices.size() + corners.size() >= std::numeric_limits<Index>::max())
      return in.fail(ErrorCode::size_mismatch, "more face corners than the index range holds");
    soup.add_face(corners);
    in.skip_line(); // a face colour
  }
  return soup;
}

} // namespace ebgeom::io
