// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Writers for dense grids (and plain arrays), dependency-free; one header per format:
///  - `.vti`: VTK XML ImageData (`write_vti.hpp`, with `.pvti` pieces);
///  - `.npy`: NumPy format 1.0 (`write_npy.hpp`);
///  - `.raw` + `.json` sidecar (`write_raw.hpp`).
/// `write_grid` picks the writer by the output path's extension. Every writer is atomic: it writes
/// to a temporary file beside the target and renames it on success, so a failure never leaves a
/// partial output behind.

#include <string>

#include "ebgeom/eval/grid_writer_common.hpp"
#include "ebgeom/eval/write_npy.hpp"
#include "ebgeom/eval/write_raw.hpp"
#include "ebgeom/eval/write_vti.hpp"

namespace ebgeom {

/// Writes a grid in the format given by the extension of `path` (`.vti`, `.npy`, `.raw`).
/// Errors: `unsupported` extension, `invalid_argument`, `io`.
template <class T>
Result<Ok> write_grid(const std::string& path, const GridSpec<T>& spec, Span<const T> values,
                      const WriteGridOptions& opt = {}) {
  auto fmt = grid_format_of(path);
  if (!fmt) return fmt.error();
  switch (*fmt) {
  case GridFormat::vti:
    return write_vti(path, spec, values, opt);
  case GridFormat::npy:
    return write_npy(path, spec, values, opt);
  case GridFormat::raw:
    return write_raw(path, spec, values, opt);
  }
  return make_error(ErrorCode::unsupported, path, ": unknown output format");
}

} // namespace ebgeom
