// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Mesh writers: STL (binary, ASCII), PLY (binary little-endian, ASCII), OBJ, OFF (ASCII) and
/// legacy VTK (BINARY, ASCII). `encode_mesh` builds the bytes in memory; `write_mesh` writes a
/// file.

#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>

#include "ebgeom/core/result.hpp"
#include "ebgeom/io/byte_reader.hpp"
#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/io/read_options.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"

namespace ebgeom::io {

/// Binary or text output (OBJ and OFF are always text).
enum class Encoding : std::uint8_t { binary, ascii };

/// What `encode_mesh`/`write_mesh` produce.
struct WriteOptions {
  /// `unknown`: taken from the extension of the path given to `write_mesh`.
  MeshFormat format = MeshFormat::unknown;
  Encoding encoding = Encoding::binary;
};

/// The encoding `format` really gets when `requested` is asked for (OBJ and OFF are text).
inline Encoding effective_encoding(MeshFormat format, Encoding requested) noexcept {
  return format == MeshFormat::obj || format == MeshFormat::off ? Encoding::ascii : requested;
}

namespace detail {

template <class V> inline void append_number(std::string& out, V v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v); // shortest round-trip form
  out.append(buf, std::size_t(r.ptr - buf));
}

/// Checks that `soup` can be written; `float_coordinates`: the format stores float, so every
/// coordinate must be finite once rounded to float (a double 1e300 would become infinity).
template <class T>
inline Result<Ok> check_writable(const PolygonSoup<T>& soup, bool float_coordinates) {
  if (soup.face_count() == 0) return make_error(ErrorCode::empty, "mesh without faces");
  for (std::size_t i = 0; i < soup.vertex_count(); ++i) {
    const Vec3<T>& v = soup.vertices[i];
    if (!all_finite(v))
      return make_error(ErrorCode::invalid_argument, "mesh has a non-finite vertex");
    if (float_coordinates && !all_finite(Vec3<float>::from(v)))
      return make_error(ErrorCode::invalid_argument, "vertex ", i, " (", v.x, ", ", v.y, ", ", v.z,
                        ") is outside the range of float (about 3.4e38), which this format "
                        "stores; choose PLY, OBJ, OFF or VTK to keep double coordinates");
  }
  for (std::size_t f = 0; f < soup.face_count(); ++f) {
    if (soup.face_size(f) < 3)
      return make_error(ErrorCode::invalid_argument, "face ", f, " has fewer than 3 vertices");
    for (Index i : soup.face(f))
      if (i >= soup.vertex_count())
        return make_error(ErrorCode::invalid_argument, "face ", f, " has vertex index ", i,
                          " >= vertex count ", soup.vertex_count());
  }
  return Ok{};
}

template <class T> std::string encode_stl(const PolygonSoup<T>& soup, Encoding enc) {
  std::string out;
  const std::size_t ntri = soup.triangle_count();
  auto each_triangle = [&](auto&& fn) {
    for (std::size_t f = 0; f < soup.face_count(); ++f) {
      const auto c = soup.face(f);
      for (std::size_t k = 2; k < c.size(); ++k) { // fan
        const Vec3<double> a = Vec3<double>::from(soup.vertices[c[0]]);
        const Vec3<double> b = Vec3<double>::from(soup.vertices[c[k - 1]]);
        const Vec3<double> d = Vec3<double>::from(soup.vertices[c[k]]);
        // the normal in double: a cross product of float coordinates near 1e20 overflows
        fn(Vec3<float>::from(normalized(cross(b - a, d - a))), Vec3<float>::from(a),
           Vec3<float>::from(b), Vec3<float>::from(d));
      }
    }
  };
  if (enc == Encoding::binary) {
    out.reserve(84 + 50 * ntri);
    out.append("binary STL written by ebgeom");
    out.resize(80, ' ');
    store(out, std::uint32_t(ntri), Endian::little);
    each_triangle([&](const Vec3<float>& n, const Vec3<float>& a, const Vec3<float>& b,
                      const Vec3<float>& d) {
      for (const Vec3<float>* v : {&n, &a, &b, &d}) {
        store(out, v->x, Endian::little);
        store(out, v->y, Endian::little);
        store(out, v->z, Endian::little);
      }
      store(out, std::uint16_t(0), Endian::little);
    });
    return out;
  }
  out = "solid ebgeom\n";
  auto vec = [&](const Vec3<float>& v) {
    append_number(out, v.x);
    out += ' ';
    append_number(out, v.y);
    out += ' ';
    append_number(out, v.z);
    out += '\n';
  };
  each_triangle(
      [&](const Vec3<float>& n, const Vec3<float>& a, const Vec3<float>& b, const Vec3<float>& d) {
        out += "facet normal ";
        vec(n);
        out += " outer loop\n";
        for (const Vec3<float>* v : {&a, &b, &d}) {
          out += "  vertex ";
          vec(*v);
        }
        out += " endloop\nendfacet\n";
      });
  out += "endsolid ebgeom\n";
  return out;
}

template <class T> std::string encode_ply(const PolygonSoup<T>& soup, Encoding enc) {
  std::size_t max_face = 0;
  for (std::size_t f = 0; f < soup.face_count(); ++f)
    max_face = std::max(max_face, soup.face_size(f));
  const bool small = max_face <= 255;
  std::string out = "ply\nformat ";
  out += enc == Encoding::binary ? "binary_little_endian 1.0\n" : "ascii 1.0\n";
  out += "comment written by ebgeom\nelement vertex ";
  append_number(out, soup.vertex_count());
  const char* ty = sizeof(T) == 4 ? "float" : "double";
  for (const char* c : {"x", "y", "z"}) out += std::string("\nproperty ") + ty + " " + c;
  out += "\nelement face ";
  append_number(out, soup.face_count());
  out += small ? "\nproperty list uchar uint vertex_indices\nend_header\n"
               : "\nproperty list uint uint vertex_indices\nend_header\n";
  if (enc == Encoding::binary) {
    for (const Vec3<T>& v : soup.vertices) {
      store(out, v.x, Endian::little);
      store(out, v.y, Endian::little);
      store(out, v.z, Endian::little);
    }
    for (std::size_t f = 0; f < soup.face_count(); ++f) {
      if (small)
        store(out, std::uint8_t(soup.face_size(f)), Endian::little);
      else
        store(out, std::uint32_t(soup.face_size(f)), Endian::little);
      for (Index i : soup.face(f)) store(out, std::uint32_t(i), Endian::little);
    }
    return out;
  }
  for (const Vec3<T>& v : soup.vertices) {
    append_number(out, v.x);
    out += ' ';
    append_number(out, v.y);
    out += ' ';
    append_number(out, v.z);
    out += '\n';
  }
  for (std::size_t f = 0; f < soup.face_count(); ++f) {
    append_number(out, soup.face_size(f));
    for (Index i : soup.face(f)) {
      out += ' ';
      append_number(out, i);
    }
    out += '\n';
  }
  return out;
}

template <class T> std::string encode_obj(const PolygonSoup<T>& soup) {
  std::string out = "# written by ebgeom\n";
  for (const Vec3<T>& v : soup.vertices) {
    out += "v ";
    append_number(out, v.x);
    out += ' ';
    append_number(out, v.y);
    out += ' ';
    append_number(out, v.z);
    out += '\n';
  }
  for (std::size_t f = 0; f < soup.face_count(); ++f) {
    out += 'f';
    for (Index i : soup.face(f)) {
      out += ' ';
      append_number(out, std::uint64_t(i) + 1);
    }
    out += '\n';
  }
  return out;
}

template <class T> std::string encode_off(const PolygonSoup<T>& soup) {
  std::string out = "OFF\n# written by ebgeom\n";
  append_number(out, soup.vertex_count());
  out += ' ';
  append_number(out, soup.face_count());
  out += " 0\n";
  for (const Vec3<T>& v : soup.vertices) {
    append_number(out, v.x);
    out += ' ';
    append_number(out, v.y);
    out += ' ';
    append_number(out, v.z);
    out += '\n';
  }
  for (std::size_t f = 0; f < soup.face_count(); ++f) {
    append_number(out, soup.face_size(f));
    for (Index i : soup.face(f)) {
      out += ' ';
      append_number(out, i);
    }
    out += '\n';
  }
  return out;
}

template <class T> std::string encode_vtk(const PolygonSoup<T>& soup, Encoding enc) {
  const bool bin = enc == Encoding::binary;
  std::string out = "# vtk DataFile Version 3.0\nwritten by ebgeom\n";
  out += bin ? "BINARY\n" : "ASCII\n";
  out += "DATASET POLYDATA\nPOINTS ";
  append_number(out, soup.vertex_count());
  out += sizeof(T) == 4 ? " float\n" : " double\n";
  for (const Vec3<T>& v : soup.vertices) {
    if (bin) {
      store(out, v.x, Endian::big);
      store(out, v.y, Endian::big);
      store(out, v.z, Endian::big);
      continue;
    }
    append_number(out, v.x);
    out += ' ';
    append_number(out, v.y);
    out += ' ';
    append_number(out, v.z);
    out += '\n';
  }
  out += bin ? "\nPOLYGONS " : "POLYGONS ";
  append_number(out, soup.face_count());
  out += ' ';
  append_number(out, soup.face_count() + soup.indices.size());
  out += '\n';
  for (std::size_t f = 0; f < soup.face_count(); ++f) {
    if (bin) {
      store(out, std::int32_t(soup.face_size(f)), Endian::big);
      for (Index i : soup.face(f)) store(out, std::int32_t(i), Endian::big);
      continue;
    }
    append_number(out, soup.face_size(f));
    for (Index i : soup.face(f)) {
      out += ' ';
      append_number(out, i);
    }
    out += '\n';
  }
  if (bin) out += '\n';
  return out;
}

} // namespace detail

/// Encodes `soup` as `opt.format` (which must not be `unknown`) with `opt.encoding`. STL
/// stores float coordinates and fan-triangulates polygons (normals from the winding); PLY
/// stores T-precision coordinates and `list uchar uint` faces (`list uint uint` when a face has
/// more than 255 corners); OBJ, OFF (always ASCII) and VTK store T-precision coordinates and
/// polygons. `effective_encoding` says what a format/encoding pair really writes. Text numbers
/// use the shortest form that reads back exactly. Errors: `invalid_argument` (unknown format, a
/// face with fewer than 3 corners, an index out of range, a non-finite vertex, or for STL a
/// coordinate outside the range of float), `empty` (no faces). O(size).
template <class T>
Result<std::string> encode_mesh(const PolygonSoup<T>& soup, const WriteOptions& opt) {
  auto ok = detail::check_writable(soup, opt.format == MeshFormat::stl);
  if (!ok) return ok.error();
  switch (opt.format) {
  case MeshFormat::stl:
    return detail::encode_stl(soup, opt.encoding);
  case MeshFormat::ply:
    return detail::encode_ply(soup, opt.encoding);
  case MeshFormat::obj:
    return detail::encode_obj(soup);
  case MeshFormat::off:
    return detail::encode_off(soup);
  case MeshFormat::vtk:
    return detail::encode_vtk(soup, opt.encoding);
  case MeshFormat::unknown:
    break;
  }
  return make_error(ErrorCode::invalid_argument, "no output format given");
}

/// Writes `soup` to `path` (see `encode_mesh`); an `unknown` format is taken from the extension
/// of `path`. Errors: those of `encode_mesh`, `io` when the file cannot be written.
template <class T>
Result<Ok> write_mesh(const std::string& path, const PolygonSoup<T>& soup, WriteOptions opt = {}) {
  if (opt.format == MeshFormat::unknown) opt.format = detail::format_from_extension(path);
  if (opt.format == MeshFormat::unknown)
    return make_error(ErrorCode::invalid_argument, path,
                      ": cannot tell the format from the extension");
  auto bytes = encode_mesh(soup, opt);
  if (!bytes) return bytes.error();
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (!f) return make_error(ErrorCode::io, path, ": cannot open for writing");
  f.write(bytes->data(), std::streamsize(bytes->size()));
  f.close();
  if (!f) return make_error(ErrorCode::io, path, ": write failed");
  return Ok{};
}

} // namespace ebgeom::io
