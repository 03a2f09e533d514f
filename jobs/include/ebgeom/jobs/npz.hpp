// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// NumPy `.npz` archives (a ZIP of `.npy` members, stored uncompressed), and the two `.npz` outputs
// of `ebgeom sdf`: the sparse narrow band (with --band) and the dense grid with its geometry
// (without); both layouts are documented in docs/cli.md.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "ebgeom/eval/sparse_grid.hpp"
#include "ebgeom/eval/write_grid.hpp"

namespace ebgeom::jobs {

/// One member of an `.npz`: stored as `name + ".npy"`, the bytes `header` (an `npy_header`) then
/// `bytes` bytes at `data` (not owned; must outlive the write).
struct NpzMember {
  std::string name;
  std::string header;
  const void* data = nullptr;
  std::uint64_t bytes = 0;
};

/// When `write_npz` uses ZIP64 records.
enum class Zip64 : std::uint8_t {
  as_needed, ///< only for a member, offset or directory at or past 4 GiB (or 65535 members)
  always,    ///< on every member and the end record (for tests of readers)
};

struct NpzOptions {
  Zip64 zip64 = Zip64::as_needed;
};

/// Writes `members` to `path` as a ZIP archive that `numpy.load` reads: stored (method 0)
/// entries with zlib's CRC-32, ZIP64 records where a size or offset reaches 4 GiB, and a fixed
/// timestamp (1980-01-01 00:00) so that equal arrays give equal files. Written to a temporary
/// beside `path` and renamed on success. Returns the archive's size in bytes. Errors: `io`.
Result<std::uint64_t> write_npz(const std::string& path, const std::vector<NpzMember>& members,
                                const NpzOptions& opt = {});

/// `text` as numpy's 'U' dtype: UTF-32 code units in the host's byte order.
inline std::string npy_unicode(const std::string& text) {
  const bool le = ebgeom::host_is_little_endian();
  std::string out;
  for (char c : text) {
    const char unit[4] = {le ? c : '\0', '\0', '\0', le ? '\0' : c};
    out.append(unit, 4);
  }
  return out;
}

/// The geometry members both grid archives hold (`origin`, `spacing`, `box`, `centering`), as the
/// bytes written for them.
template <class T> struct NpzGeometry {
  double origin[3], spacing[3], box[6];
  std::string centering;   ///< `cell` or `node`
  std::string centering_u; ///< the same as numpy's 'U' text (`npy_unicode`)

  explicit NpzGeometry(const GridSpec<T>& s)
      : centering(to_string(s.centering)), centering_u(npy_unicode(centering)) {
    const Vec3<T> o = s.origin(), h = s.spacing();
    for (int a = 0; a < 3; ++a) {
      origin[a] = double(o[a]);
      spacing[a] = double(h[a]);
      box[a] = double(s.box.lo[a]);
      box[3 + a] = double(s.box.hi[a]);
    }
  }
};

/// The `.npz` of a narrow-band grid (docs/cli.md, "Sparse output"):
///  - `tiles` (M, 3) uint32: tile coordinates (tx, ty, tz) of kept tile b, from
///    `SparseGrid::kept_tiles` (the member was named `blocks` in 0.1);
///  - `values` (M, 8, 8, 8) of T: `values[b, z, y, x]` is sample (8 tx + x, 8 ty + y, 8 tz + z);
///    local samples past the grid's last sample hold +band;
///  - `tile_code` (TZ, TY, TX) int32: the index b (>= 0) of each kept tile, or -1 (skipped, every
///    sample -band: inside) or -2 (skipped, +band: outside);
///  - `dims` (3,) uint64 [NX, NY, NZ]; `tile` () int64 = 8; `origin`, `spacing` (3,) float64
///    (x, y, z); `box` (2, 3) float64 (lo, hi); `band` () of T (the fill value of skipped tiles);
///    `centering` () unicode `cell` or `node`.
template <class T>
Result<std::uint64_t> write_sparse_npz(const std::string& path, const SparseGrid<T>& g,
                                       const NpzOptions& opt = {}) {
  static_assert(sizeof(g.kept_tiles[0]) == 3 * sizeof(std::uint32_t), "tiles must be packed");
  const std::string bo(1, host_is_little_endian() ? '<' : '>');
  const std::string vt = npy_descr(sizeof(T) == 4 ? DType::float32 : DType::float64);
  const GridSpec<T>& s = g.spec;
  const std::size_t W = grid_tile;
  const std::uint64_t dims[3] = {s.nx(), s.ny(), s.nz()};
  const std::int64_t tile = std::int64_t(W);
  const NpzGeometry<T> geo(s);
  const std::size_t m = g.kept_tiles.size();
  using Shape = std::vector<std::size_t>;
  const std::vector<NpzMember> members = {
      {"dims", npy_header(bo + "u8", Shape{3}), dims, sizeof dims},
      {"tile", npy_header(bo + "i8", Shape{}), &tile, sizeof tile},
      {"origin", npy_header(bo + "f8", Shape{3}), geo.origin, sizeof geo.origin},
      {"spacing", npy_header(bo + "f8", Shape{3}), geo.spacing, sizeof geo.spacing},
      {"box", npy_header(bo + "f8", Shape{2, 3}), geo.box, sizeof geo.box},
      {"band", npy_header(vt, Shape{}), &g.band, sizeof(T)},
      {"centering", npy_header(bo + "U" + std::to_string(geo.centering.size()), Shape{}),
       geo.centering_u.data(), geo.centering_u.size()},
      {"tiles", npy_header(bo + "u4", Shape{m, 3}), g.kept_tiles.data(),
       std::uint64_t(m) * sizeof(g.kept_tiles[0])},
      {"tile_code", npy_header(bo + "i4", Shape{g.tiles[2], g.tiles[1], g.tiles[0]}),
       g.tile_code.data(), std::uint64_t(g.tile_code.size()) * sizeof(std::int32_t)},
      {"values", npy_header(vt, Shape{m, W, W, W}), g.values.data(),
       std::uint64_t(g.values.size()) * sizeof(T)},
  };
  return write_npz(path, members, opt);
}

/// The dense `.npz` of a grid (docs/cli.md, "Dense .npz output"): the grid and its geometry in one
/// file that `numpy.load` reads:
///  - `sdf` (NZ, NY, NX) of T: `sdf[k, j, i]` is the sample at `origin + (i, j, k) * spacing`;
///  - `origin`, `spacing` (3,) float64 (x, y, z); `box` (2, 3) float64 (lo, hi);
///  - `centering` () unicode `cell` or `node`.
template <class T>
Result<std::uint64_t> write_dense_npz(const std::string& path, const GridSpec<T>& s,
                                      Span<const T> values, const NpzOptions& opt = {}) {
  const std::string bo(1, ebgeom::host_is_little_endian() ? '<' : '>');
  const std::string vt = npy_descr(sizeof(T) == 4 ? DType::float32 : DType::float64);
  const NpzGeometry<T> geo(s);
  using Shape = std::vector<std::size_t>;
  const std::vector<NpzMember> members = {
      {"sdf", npy_header(vt, Shape{s.nz(), s.ny(), s.nx()}), values.data(),
       std::uint64_t(values.size()) * sizeof(T)},
      {"origin", npy_header(bo + "f8", Shape{3}), geo.origin, sizeof geo.origin},
      {"spacing", npy_header(bo + "f8", Shape{3}), geo.spacing, sizeof geo.spacing},
      {"box", npy_header(bo + "f8", Shape{2, 3}), geo.box, sizeof geo.box},
      {"centering", npy_header(bo + "U" + std::to_string(geo.centering.size()), Shape{}),
       geo.centering_u.data(), geo.centering_u.size()},
  };
  return write_npz(path, members, opt);
}

/// True when `path` ends in `.npz` (the sparse output with --band, the dense one without).
inline bool is_npz_path(const std::string& path) {
  return path.size() > 4 && path.compare(path.size() - 4, 4, ".npz") == 0;
}

} // namespace ebgeom::jobs
