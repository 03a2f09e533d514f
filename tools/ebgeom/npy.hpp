// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// Reading .npy arrays of points for `ebgeom query`.

#include <string>
#include <vector>

#include "ebgeom/core/vec.hpp"

namespace ebgeom::cli {

/// Reads an (N, 3) float32 or float64 little-endian C-order .npy file (format 1.0, 2.0 or 3.0).
/// Throws CliError (input) `FILE: byte OFFSET: what` for anything else (bad magic, dtype, shape,
/// Fortran order, truncated data).
std::vector<Vec3<double>> read_npy_points(const std::string& path);

} // namespace ebgeom::cli
