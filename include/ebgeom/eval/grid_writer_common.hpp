// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// What the grid writers (`write_vti.hpp`, `write_npy.hpp`, `write_raw.hpp`) share: the element
/// type `DType`, `WriteGridOptions`, the format of a path (`grid_format_of`), the `.raw` sidecar's
/// path, and the streaming, escaping and checking helpers. Every writer is atomic: it writes to a
/// temporary file beside the target and renames it on success, so a failure never leaves a partial
/// output behind.

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <locale>
#include <sstream>
#include <string>
#include <vector>

#include "ebgeom/core/error.hpp"
#include "ebgeom/core/result.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/eval/grid.hpp"
#include "ebgeom/io/atomic_file.hpp"

namespace ebgeom {

/// Element type written to a file.
enum class DType : std::uint8_t { float32, float64 };

inline const char* to_string(DType d) noexcept {
  return d == DType::float32 ? "float32" : "float64";
}
inline std::size_t dtype_size(DType d) noexcept { return d == DType::float32 ? 4 : 8; }

/// Options of the grid writers.
struct WriteGridOptions {
  DType dtype = DType::float32;
  /// Name of the data array (VTI array name, JSON sidecar "name").
  std::string name = "sdf";
};

/// File format of a grid, chosen from the output path's extension.
enum class GridFormat : std::uint8_t { vti, npy, raw };

/// The format for `path` by its (case-sensitive, lower-case) extension `.vti`, `.npy` or `.raw`.
/// Errors: `unsupported` for any other extension.
inline Result<GridFormat> grid_format_of(const std::string& path) {
  auto ends = [&](const char* ext) {
    const std::size_t n = std::strlen(ext);
    return path.size() > n && path.compare(path.size() - n, n, ext) == 0;
  };
  if (ends(".vti")) return GridFormat::vti;
  if (ends(".npy")) return GridFormat::npy;
  if (ends(".raw")) return GridFormat::raw;
  return make_error(ErrorCode::unsupported, path,
                    ": unknown output format; expected an extension .vti, .npy or .raw");
}

/// Path of the JSON sidecar of a `.raw` file: `out.raw` -> `out.json`.
inline std::string raw_sidecar_path(const std::string& raw_path) {
  const std::size_t dot = raw_path.rfind('.');
  const std::size_t slash = raw_path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
    return raw_path + ".json";
  return raw_path.substr(0, dot) + ".json";
}

/// True on a little-endian host (the byte order the grid writers record in their headers).
inline bool host_is_little_endian() noexcept {
  const std::uint16_t one = 1;
  unsigned char b;
  std::memcpy(&b, &one, 1);
  return b == 1;
}

namespace detail {

using ebgeom::host_is_little_endian; // its former, internal name

/// Streams `values` converted to `dtype`, in chunks, in host byte order.
template <class T> void write_values(std::ostream& os, Span<const T> values, DType dtype) {
  constexpr std::size_t chunk = 1 << 14;
  if (dtype == DType::float32) {
    std::vector<float> buf(std::min(chunk, values.size()));
    for (std::size_t s = 0; s < values.size(); s += chunk) {
      const std::size_t n = std::min(chunk, values.size() - s);
      for (std::size_t i = 0; i < n; ++i) buf[i] = static_cast<float>(values[s + i]);
      os.write(reinterpret_cast<const char*>(buf.data()), std::streamsize(n * sizeof(float)));
    }
  } else {
    std::vector<double> buf(std::min(chunk, values.size()));
    for (std::size_t s = 0; s < values.size(); s += chunk) {
      const std::size_t n = std::min(chunk, values.size() - s);
      for (std::size_t i = 0; i < n; ++i) buf[i] = static_cast<double>(values[s + i]);
      os.write(reinterpret_cast<const char*>(buf.data()), std::streamsize(n * sizeof(double)));
    }
  }
}

inline std::ostringstream number_stream() {
  std::ostringstream os;
  os.imbue(std::locale::classic());
  os.precision(17);
  return os;
}

inline std::string json_escape(const std::string& s) {
  std::string r;
  for (char c : s) {
    if (c == '"' || c == '\\') {
      r += '\\';
      r += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char b[8];
      std::snprintf(b, sizeof b, "\\u%04x", c);
      r += b;
    } else {
      r += c;
    }
  }
  return r;
}

inline std::string xml_escape(const std::string& s) {
  std::string r;
  for (char c : s) {
    switch (c) {
    case '&':
      r += "&amp;";
      break;
    case '<':
      r += "&lt;";
      break;
    case '>':
      r += "&gt;";
      break;
    case '"':
      r += "&quot;";
      break;
    default:
      r += c;
    }
  }
  return r;
}

template <class T> Result<Ok> check_grid_values(const GridSpec<T>& spec, std::size_t count) {
  if (auto ok = spec.validate(); !ok) return ok;
  if (count != spec.size())
    return make_error(ErrorCode::invalid_argument, "grid has ", spec.size(), " samples but ", count,
                      " values were given");
  return Ok{};
}

} // namespace detail

} // namespace ebgeom
