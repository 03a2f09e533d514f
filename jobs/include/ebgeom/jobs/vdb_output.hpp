// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// OpenVDB output of `ebgeom sdf -o OUT.vdb --band W`: the narrow band as a level set. Built with
// OpenVDB when it is found (EBGEOM_WITH_OPENVDB); otherwise `write_vdb` says how to get it.

#include <cstdint>
#include <string>

#include "ebgeom/core/result.hpp"
#include "ebgeom/eval/sparse_grid.hpp"

namespace ebgeom::jobs {

/// True when this build writes OpenVDB files.
bool vdb_available();

/// Writes `g` to `path` as an OpenVDB file holding one level-set grid named "sdf" (a FloatGrid
/// for float, a DoubleGrid for double): class GRID_LEVEL_SET, background `g.band`, voxel (i, j, k)
/// at index coordinate (i, j, k) with the transform mapping it to `origin + (i, j, k) * spacing`
/// (sample positions, cell- or node-centred alike). Each kept 8^3 tile becomes a leaf node whose
/// samples with |S| < band are active (the others inactive at ±band); tiles inside the surface
/// (skipped, or kept with every sample at -band) become inactive tiles of value -band; outside is
/// the background. Written through a temporary file renamed on success.
/// Returns the file size. Errors: `io`, `unsupported` (built without OpenVDB).
Result<std::uint64_t> write_vdb(const std::string& path, const SparseGrid<float>& g);
Result<std::uint64_t> write_vdb(const std::string& path, const SparseGrid<double>& g);

/// True when `path` ends in `.vdb`.
inline bool is_vdb_path(const std::string& path) {
  return path.size() > 4 && path.compare(path.size() - 4, 4, ".vdb") == 0;
}

} // namespace ebgeom::jobs
