// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// fcpw peer for bench/mesh_sdf_bench.cpp and bench/grid_bench.cpp, compiled in its own
// translation unit with fcpw's own recommended options (enoki, `-march=native`, SIMD width of the
// host's widest vector unit: 16 floats with AVX-512). fcpw (Sawhney, MIT) computes in float.
// Its source is not part of ebgeom: bench/fetch-fcpw.sh unpacks the snapshot from
// ../shared/peers, and CMake builds this peer when EBGEOM_FCPW_DIR points at it.

#include <cstddef>
#include <cstdint>
#include <memory>

namespace ebgeom_bench {

/// Signed distance with fcpw: a vectorised surface-area BVH (`AggregateType::Bvh_SurfaceArea`,
/// `vectorize = true`) over one triangle object, angle-weighted vertex and edge normals
/// (`computeObjectNormals(0, true)`) for the sign, `findClosestPoint` then
/// `Interaction::signedDistance` per query. Queries are const and thread-safe.
class FcpwPeer {
 public:
  /// `xyz`: 3 `nv` coordinates; `tri`: 3 `nt` vertex indices (CCW from outside).
  FcpwPeer(const float* xyz, std::size_t nv, const std::uint32_t* tri, std::size_t nt);
  ~FcpwPeer();
  FcpwPeer(const FcpwPeer&) = delete;
  FcpwPeer& operator=(const FcpwPeer&) = delete;

  /// Signed distance (negative inside, by the pseudonormal at the closest point), in float.
  float signed_distance(float x, float y, float z) const;
  /// The SIMD width fcpw was compiled with (FCPW_SIMD_WIDTH).
  static int simd_width() noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace ebgeom_bench
