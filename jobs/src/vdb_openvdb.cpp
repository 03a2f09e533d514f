// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// `write_vdb` with OpenVDB: ebgeom's 8^3 tiles are exactly OpenVDB's leaf nodes (LeafNode<T, 3>),
// so each kept tile is copied into one leaf.
#include "ebgeom/jobs/vdb_output.hpp"

#include <openvdb/io/Stream.h>
#include <openvdb/math/Maps.h>
#include <openvdb/openvdb.h>

#include <cmath>
#include <exception>
#include <filesystem>
#include <mutex>
#include <system_error>

#include "ebgeom/eval/write_grid.hpp"

namespace ebgeom::jobs {

namespace {

template <class T> struct VdbGridOf;
template <> struct VdbGridOf<float> { using type = openvdb::FloatGrid; };
template <> struct VdbGridOf<double> { using type = openvdb::DoubleGrid; };

template <class T>
Result<std::uint64_t> write_vdb_as(const std::string& path, const SparseGrid<T>& g) {
  using Grid = typename VdbGridOf<T>::type;
  using Leaf = typename Grid::TreeType::LeafNodeType;
  constexpr std::size_t W = grid_tile;
  static_assert(Leaf::DIM == W, "an ebgeom tile must be one OpenVDB leaf node");
  static std::once_flag init;
  std::call_once(init, [] { openvdb::initialize(); });

  const GridSpec<T>& s = g.spec;
  const T band = g.band;
  typename Grid::Ptr grid = Grid::create(band);
  grid->setName("sdf");
  grid->setGridClass(openvdb::GRID_LEVEL_SET);
  const Vec3<T> o = s.origin(), h = s.spacing();
  // Index (i, j, k) is sample (i, j, k): world = origin + (i, j, k) * spacing. OpenVDB puts voxel
  // centres at integer index coordinates, which is where ebgeom's samples are.
  const openvdb::Vec3d scale(double(h.x), double(h.y), double(h.z));
  const openvdb::Vec3d shift(double(o.x), double(o.y), double(o.z));
  openvdb::math::MapBase::Ptr map;
  if (scale.x() == scale.y() && scale.y() == scale.z())
    map.reset(new openvdb::math::UniformScaleTranslateMap(scale.x(), shift));
  else
    map.reset(new openvdb::math::ScaleTranslateMap(scale, shift));
  grid->setTransform(openvdb::math::Transform::Ptr(new openvdb::math::Transform(map)));
  grid->insertMeta("ebgeom_centering", openvdb::StringMetadata(to_string(s.centering)));

  auto& tree = grid->tree();
  const auto& d = s.dims;
  for (std::size_t tz = 0; tz < g.tiles[2]; ++tz)
    for (std::size_t ty = 0; ty < g.tiles[1]; ++ty)
      for (std::size_t tx = 0; tx < g.tiles[0]; ++tx) {
        const std::int32_t c = g.tile_code[tx + g.tiles[0] * (ty + g.tiles[1] * tz)];
        const openvdb::Coord origin(int(tx * W), int(ty * W), int(tz * W));
        if (c == SparseGrid<T>::outside) continue; // the background
        const std::size_t sx = std::min(W, d[0] - tx * W), sy = std::min(W, d[1] - ty * W),
                          sz = std::min(W, d[2] - tz * W);
        // (partial tiles on the upper faces: samples past the grid's last one are padding)
        if (c == SparseGrid<T>::inside) {
          tree.addTile(1, origin, -band, false); // one inactive tile at leaf level
          continue;
        }
        // A kept tile with nothing in the band and one sign is a tile too (as OpenVDB's
        // pruneLevelSet would make it, but looking only at the grid's own samples: the padding of
        // partial tiles past the last sample must not decide).
        const T* t = g.values.data() + std::size_t(c) * W * W * W;
        bool active = false, neg = false, pos = false;
        for (std::size_t z = 0; z < sz; ++z)
          for (std::size_t y = 0; y < sy; ++y)
            for (std::size_t x = 0; x < sx; ++x) {
              const T v = t[x + W * (y + W * z)];
              active = active || std::abs(v) < band;
              (v < 0 ? neg : pos) = true;
            }
        if (!active && !(neg && pos)) {
          if (neg) tree.addTile(1, origin, -band, false);
          continue; // all +band: the background
        }
        Leaf* leaf = tree.touchLeaf(origin);
        for (std::size_t z = 0; z < sz; ++z)
          for (std::size_t y = 0; y < sy; ++y)
            for (std::size_t x = 0; x < sx; ++x) {
              const T v = t[x + W * (y + W * z)];
              const openvdb::Coord ijk(origin.x() + int(x), origin.y() + int(y),
                                       origin.z() + int(z));
              if (std::abs(v) < band)
                leaf->setValueOn(ijk, v);
              else
                leaf->setValueOff(ijk, v < 0 ? -band : band);
            }
      }

  ebgeom::AtomicFile f(path);
  if (!f.is_open()) return f.open_error();
  try {
    openvdb::GridPtrVec grids{grid};
    openvdb::io::Stream(f.stream()).write(grids);
  } catch (const std::exception& e) {
    return make_error(ErrorCode::io, path, ": OpenVDB could not write the grid (", e.what(), ")");
  }
  if (auto ok = f.close(); !ok) return ok.error();
  // The size of what was written, read before `commit()`: inside an OutputGroup the rename onto
  // `path` happens only when the whole job's outputs are written.
  std::error_code ec;
  const auto size = std::filesystem::file_size(f.temp_path(), ec);
  if (auto ok = f.commit(); !ok) return ok.error();
  return std::uint64_t(ec ? 0 : size);
}

} // namespace

bool vdb_available() { return true; }
Result<std::uint64_t> write_vdb(const std::string& path, const SparseGrid<float>& g) {
  return write_vdb_as(path, g);
}
Result<std::uint64_t> write_vdb(const std::string& path, const SparseGrid<double>& g) {
  return write_vdb_as(path, g);
}

} // namespace ebgeom::jobs
