// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `ByteView`, `MeshFormat` and `ReadOptions`: what every mesh reader takes.

#include <cstdint>
#include <string>
#include <string_view>

namespace ebgeom::io {

/// Read-only bytes of a whole file (or any buffer). Non-owning; the caller keeps them alive for the
/// duration of a parse. Build one from a `std::string`, a literal or `{pointer, size}`.
using ByteView = std::string_view;

/// The mesh file formats ebgeom reads. `unknown` means "detect" in options and "not recognised"
/// in results.
enum class MeshFormat : std::uint8_t { unknown = 0, stl, ply, obj, vtk, off };

/// Stable lower-case name ("stl", "ply", "obj", "vtk", "off", "unknown").
inline const char* to_string(MeshFormat f) noexcept {
  switch (f) {
  case MeshFormat::stl:
    return "stl";
  case MeshFormat::ply:
    return "ply";
  case MeshFormat::obj:
    return "obj";
  case MeshFormat::vtk:
    return "vtk";
  case MeshFormat::off:
    return "off";
  case MeshFormat::unknown:
    break;
  }
  return "unknown";
}

/// What to do with STL's per-triangle vertices (STL stores no shared vertices).
enum class StlVertices : std::uint8_t {
  weld_exact, ///< merge vertices with bit-identical coordinates (+0 and -0 are equal); default
  keep,       ///< three new vertices per triangle (a triangle soup)
};

/// Options shared by all readers. Limits protect against lying headers and huge inputs: a file
/// that declares or holds more than a limit gets `ErrorCode::size_mismatch` before anything large
/// is allocated.
struct ReadOptions {
  /// Used in error messages and, when the content does not say, for the extension.
  std::string path;
  /// Forces a format; `unknown` detects it (content first, then the extension of `path`).
  MeshFormat format = MeshFormat::unknown;
  /// Largest number of triangles (faces after fan triangulation) accepted.
  std::uint64_t max_triangles = std::uint64_t(1) << 30;
  /// Largest file read by `read_mesh` / `read_file` (bytes).
  std::uint64_t max_bytes = std::uint64_t(1) << 36;
  /// STL only: weld exact duplicate vertices (default) or keep three per triangle.
  StlVertices stl_vertices = StlVertices::weld_exact;
};

} // namespace ebgeom::io
