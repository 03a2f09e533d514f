// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `read_mesh` (from a file) and `parse_mesh` (from memory): format detection by content first,
/// extension second, then the matching reader. Also `read_file`, the bounded file loader.

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <memory>
#include <new>
#include <string>

#include "ebgeom/core/result.hpp"
#include "ebgeom/io/obj.hpp"
#include "ebgeom/io/off.hpp"
#include "ebgeom/io/ply.hpp"
#include "ebgeom/io/read_options.hpp"
#include "ebgeom/io/stl.hpp"
#include "ebgeom/io/text_reader.hpp"
#include "ebgeom/io/vtk.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"

namespace ebgeom::io {

/// The bytes of a whole file, owned.
struct FileBytes {
  std::unique_ptr<char[]> data;
  std::size_t size = 0;
  ByteView view() const noexcept { return ByteView(data.get(), size); }
};

/// What a non-regular file is, for messages: "a FIFO (named pipe)", "a character device", ...
inline const char* file_type_name(unsigned mode) noexcept {
  return S_ISDIR(mode)    ? "a directory"
         : S_ISFIFO(mode) ? "a FIFO (named pipe)"
         : S_ISCHR(mode)  ? "a character device"
         : S_ISBLK(mode)  ? "a block device"
         : S_ISSOCK(mode) ? "a socket"
                          : "not a regular file";
}

/// Reads the file `path` into memory. Only regular files are read: a FIFO, device, socket or
/// directory is refused without blocking (opened non-blocking, checked with `fstat`). A file
/// whose first 64 KiB (or all of it, if shorter) are zero bytes is refused before the rest is
/// read: no mesh format starts so (a blank or sparse file). Errors: `io` (cannot open or read, not
/// a regular file), `size_mismatch` (larger than `opt.max_bytes`, checked before allocating),
/// `out_of_memory` (the file's size cannot be allocated), `bad_magic` (zero bytes). The error's
/// path is `path`.
inline Result<FileBytes, ParseError> read_file(const std::string& path,
                                               const ReadOptions& opt = {}) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0)
    return make_parse_error(ErrorCode::io, path, 0, 0, "cannot open the file (",
                            std::strerror(errno), ")");
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st;
  if (::fstat(fd, &st) != 0)
    return make_parse_error(ErrorCode::io, path, 0, 0, "cannot determine the file size (",
                            std::strerror(errno), ")");
  if (!S_ISREG(st.st_mode))
    return make_parse_error(ErrorCode::io, path, 0, 0, "is ", file_type_name(st.st_mode),
                            ", not a regular file; only regular files are read (save the data "
                            "to a file first)");
  const std::uint64_t end = std::uint64_t(st.st_size);
  if (end > opt.max_bytes)
    return make_parse_error(ErrorCode::size_mismatch, path, 0, 0, "file of ", end,
                            " bytes exceeds the limit of ", opt.max_bytes, " bytes");
  FileBytes out;
  out.size = std::size_t(end);
  out.data.reset(new (std::nothrow) char[out.size > 0 ? out.size : 1]);
  if (!out.data)
    return make_parse_error(ErrorCode::out_of_memory, path, 0, 0, "cannot allocate ", out.size,
                            " bytes to read the file (out of memory)");
  std::size_t got = 0;
  auto read_up_to = [&](std::size_t want) -> bool {
    while (got < want) {
      const ssize_t r = ::read(fd, out.data.get() + got, want - got);
      if (r < 0 && errno == EINTR) continue;
      if (r <= 0) return false;
      got += std::size_t(r);
    }
    return true;
  };
  const std::size_t head = out.size < 65536 ? out.size : 65536;
  if (!read_up_to(head))
    return make_parse_error(ErrorCode::io, path, got, 0, "cannot read the file's ", out.size,
                            " bytes (", got == 0 ? "no data" : std::strerror(errno), ")");
  // A large file whose first 64 KiB are zero is a blank or sparse file: refused before the rest is
  // read. Smaller files go to the parsers, whose errors say precisely what is missing.
  if (head == 65536 &&
      std::all_of(out.data.get(), out.data.get() + head, [](char c) { return c == 0; }))
    return make_parse_error(ErrorCode::bad_magic, path, 0, 0, "the first ", head, " of its ",
                            out.size, " bytes are all zero: not a mesh (a blank or sparse file?)");
  if (!read_up_to(out.size))
    return make_parse_error(ErrorCode::io, path, got, 0, "cannot read the file's ", out.size,
                            " bytes (", errno != 0 ? std::strerror(errno) : "it got shorter", ")");
  return out;
}

namespace detail {

inline MeshFormat format_from_extension(const std::string& path) noexcept {
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of("/\\");
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
    return MeshFormat::unknown;
  const std::string_view ext = std::string_view(path).substr(dot + 1);
  if (iequals(ext, "stl")) return MeshFormat::stl;
  if (iequals(ext, "ply")) return MeshFormat::ply;
  if (iequals(ext, "obj")) return MeshFormat::obj;
  if (iequals(ext, "vtk")) return MeshFormat::vtk;
  if (iequals(ext, "off")) return MeshFormat::off;
  return MeshFormat::unknown;
}

/// Does the first statement (skipping blank and `#` lines in the first 64 KiB) start with an OBJ
/// keyword?
inline bool looks_like_obj(std::string_view t) noexcept {
  static const char* const keywords[] = {"v", "vt", "vn", "vp",     "f",      "o",
                                         "g", "s",  "l",  "usemtl", "mtllib", "p"};
  std::size_t i = 0;
  const std::size_t n = t.size() < 65536 ? t.size() : 65536;
  while (i < n) {
    while (i < n && is_space(t[i])) ++i;
    if (i >= n) return false;
    if (t[i] == '#') {
      while (i < n && t[i] != '\n') ++i;
      continue;
    }
    std::size_t j = i;
    while (j < t.size() && !is_space(t[j])) ++j;
    if (j >= t.size() || t[j] == '\n') return false; // a keyword is followed by arguments
    const std::string_view kw = t.substr(i, j - i);
    for (const char* k : keywords)
      if (kw == k) return true;
    return false;
  }
  return false;
}

} // namespace detail

/// Detects the format of `bytes`, by content first: a binary STL by the exact size rule
/// (84 + 50 n == size), `ply` on the first line, `# vtk` on the first line, `solid` as the first
/// word (ASCII STL), an OFF keyword (`OFF`, `COFF`, `NOFF`, `OFF BINARY`, ...) as the first word,
/// an OBJ keyword (`v`, `f`, `o`, `g`, `vn`, ...) as the first statement after
/// comments. Then by the extension of `path` (case-insensitive `.stl .ply .obj .vtk .off`); then a
/// binary STL with trailing bytes. Returns `unknown` otherwise. O(1) except the OBJ probe
/// (at most 64 KiB).
inline MeshFormat detect_format(ByteView bytes, const std::string& path = {}) noexcept {
  if (bytes.size() >= 84) {
    const std::uint64_t n = detail::load<std::uint32_t>(bytes.data() + 80, Endian::little);
    if (84 + 50 * n == bytes.size()) return MeshFormat::stl;
  }
  std::string_view t = bytes;
  if (t.size() >= 3 && (unsigned char)t[0] == 0xEF && (unsigned char)t[1] == 0xBB &&
      (unsigned char)t[2] == 0xBF)
    t.remove_prefix(3);
  if (t.size() >= 4 && t.substr(0, 3) == "ply" && (t[3] == '\n' || t[3] == '\r'))
    return MeshFormat::ply;
  if (t.size() >= 5 && detail::iequals(t.substr(0, 5), "# vtk")) return MeshFormat::vtk;
  if (detail::starts_with_solid(t)) return MeshFormat::stl;
  if (is_off(t)) return MeshFormat::off;
  if (detail::looks_like_obj(t)) return MeshFormat::obj;
  const MeshFormat ext = detail::format_from_extension(path);
  if (ext != MeshFormat::unknown) return ext;
  if (is_binary_stl(bytes)) return MeshFormat::stl;
  return MeshFormat::unknown;
}

/// Reads a mesh from memory: `opt.format`, or the detected format (`detect_format(bytes,
/// opt.path)`), then `parse_stl`, `parse_ply`, `parse_obj`, `parse_vtk` or `parse_off`. Errors:
/// `empty` for no bytes, `bad_magic` when no format is recognised, otherwise the reader's.
template <class T>
Result<PolygonSoup<T>, ParseError> parse_mesh(ByteView bytes, const ReadOptions& opt = {}) {
  if (bytes.empty()) return make_parse_error(ErrorCode::empty, opt.path, 0, 0, "empty input");
  const MeshFormat f =
      opt.format != MeshFormat::unknown ? opt.format : detect_format(bytes, opt.path);
  switch (f) {
  case MeshFormat::stl:
    return parse_stl<T>(bytes, opt);
  case MeshFormat::ply:
    return parse_ply<T>(bytes, opt);
  case MeshFormat::obj:
    return parse_obj<T>(bytes, opt);
  case MeshFormat::vtk:
    return parse_vtk<T>(bytes, opt);
  case MeshFormat::off:
    return parse_off<T>(bytes, opt);
  case MeshFormat::unknown:
    break;
  }
  return make_parse_error(ErrorCode::bad_magic, opt.path, 0, 0,
                          "not a recognised mesh format (STL, PLY, OBJ, OFF or legacy VTK)");
}

/// Reads the mesh file `path` (see `parse_mesh`). `opt.path` defaults to `path` for messages.
/// Not thread-hostile: reads only its own file; allocates the file size plus the mesh.
template <class T>
Result<PolygonSoup<T>, ParseError> read_mesh(const std::string& path, ReadOptions opt = {}) {
  if (opt.path.empty()) opt.path = path;
  auto bytes = read_file(path, opt);
  if (!bytes) return std::move(bytes).error();
  return parse_mesh<T>(bytes->view(), opt);
}

} // namespace ebgeom::io
