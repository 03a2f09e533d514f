// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "fcpw_peer.hpp"

#include <fcpw/fcpw.h>

namespace ebgeom_bench {

struct FcpwPeer::Impl {
  fcpw::Scene<3> scene;
};

FcpwPeer::FcpwPeer(const float* xyz, std::size_t nv, const std::uint32_t* tri, std::size_t nt)
    : impl_(std::make_unique<Impl>()) {
  auto& s = impl_->scene;
  s.setObjectTypes({{fcpw::PrimitiveType::Triangle}});
  s.setObjectVertexCount(int(nv), 0);
  s.setObjectTriangleCount(int(nt), 0);
  for (std::size_t i = 0; i < nv; ++i)
    s.setObjectVertex(fcpw::Vector<3>(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]), int(i), 0);
  for (std::size_t t = 0; t < nt; ++t)
    s.setObjectTriangle(fcpw::Vector3i(int(tri[3 * t]), int(tri[3 * t + 1]), int(tri[3 * t + 2])),
                        int(t), 0);
  s.computeObjectNormals(0, true);
  s.build(fcpw::AggregateType::Bvh_SurfaceArea, true);
}

FcpwPeer::~FcpwPeer() = default;

float FcpwPeer::signed_distance(float x, float y, float z) const {
  const fcpw::Vector<3> q(x, y, z);
  fcpw::Interaction<3> hit;
  impl_->scene.findClosestPoint(q, hit, fcpw::maxFloat, /*recordNormal=*/true);
  return hit.signedDistance(q);
}

int FcpwPeer::simd_width() noexcept { return FCPW_SIMD_WIDTH; }

} // namespace ebgeom_bench
