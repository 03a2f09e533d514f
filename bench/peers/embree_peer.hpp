// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// Embree 3 peer shared by bench/mesh_sdf_bench.cpp and bench/grid_bench.cpp: per-point signed
// distance through rtcPointQuery (closest triangle in float), then ebgeom's kernel and
// pseudonormals on the winning triangle for the sign. Include only when Embree 3 is found
// (EBGEOM_BENCH_HAVE_EMBREE; bench/CMakeLists.txt and bench/grid_bench.cmake link it).

#include <embree3/rtcore.h>

#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "ebgeom/geom/closest_point_triangle.hpp"
#include "ebgeom/mesh/triangle_mesh.hpp"
#include "ebgeom/sdf/brute_force_mesh_sdf.hpp"

namespace ebgeom_bench {

using namespace ebgeom;

/// Embree device memory monitor: adds every allocation (bytes > 0) and release to `user`, an
/// `std::atomic<long long>`.
inline bool embree_memory_monitor(void* user, ssize_t bytes, bool /*post*/) {
  static_cast<std::atomic<long long>*>(user)->fetch_add(bytes, std::memory_order_relaxed);
  return true;
}

// Embree's BVH over float copies of the triangles; the closest triangle comes from rtcPointQuery
// with a callback that computes the closest point on each candidate triangle and shrinks the
// query radius (Embree's closest_point tutorial). The sign (and, in double runs, the distance) is
// then computed on the winning triangle with ebgeom's kernel and pseudonormals: what a user of
// Embree needing signed distances would write.
template <class T> class EmbreePeer {
 public:
  EmbreePeer(RTCDevice device, const TriangleMesh<T>& mesh) : mesh_(mesh) {
    // +1: Embree reads vertex buffers 16 bytes at a time, so the last one needs 4 bytes of padding.
    vertices_.resize(mesh.vertex_count() + 1, Vec3<float>{0, 0, 0});
    for (std::size_t i = 0; i < mesh.vertex_count(); ++i)
      vertices_[i] = Vec3<float>::from(mesh.vertices[i]);
    triangles_ = mesh.triangles;
    scene_ = rtcNewScene(device);
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, vertices_.data(), 0,
                               sizeof(Vec3<float>), mesh.vertex_count());
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, triangles_.data(), 0,
                               sizeof(triangles_[0]), triangles_.size());
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene_, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(scene_);
  }
  ~EmbreePeer() { rtcReleaseScene(scene_); }
  EmbreePeer(const EmbreePeer&) = delete;
  EmbreePeer& operator=(const EmbreePeer&) = delete;

  std::size_t buffer_bytes() const noexcept {
    return vertices_.size() * sizeof(vertices_[0]) + triangles_.size() * sizeof(triangles_[0]);
  }

  T operator()(const Vec3<T>& p) const noexcept {
    RTCPointQuery q; // 16-byte aligned by its declaration
    q.x = float(p.x);
    q.y = float(p.y);
    q.z = float(p.z);
    q.time = 0.f;
    q.radius = std::numeric_limits<float>::infinity();
    RTCPointQueryContext ctx;
    rtcInitPointQueryContext(&ctx);
    Closest c{vertices_.data(), triangles_.data(), MeshClosestPoint<T>::invalid_triangle};
    rtcPointQuery(scene_, &q, &ctx, &EmbreePeer::callback, &c);
    if (c.triangle == MeshClosestPoint<T>::invalid_triangle)
      return std::numeric_limits<T>::infinity();
    return triangle_signed_distance(mesh_, c.triangle, p).distance;
  }

 private:
  struct Closest {
    const Vec3<float>* vertices;
    const std::array<Index, 3>* triangles;
    Index triangle;
  };
  static bool callback(RTCPointQueryFunctionArguments* args) {
    Closest& c = *static_cast<Closest*>(args->userPtr);
    const auto& t = c.triangles[args->primID];
    const Vec3<float> q{args->query->x, args->query->y, args->query->z};
    const TriangleClosestPoint<float> cp =
        closest_point_triangle(q, c.vertices[t[0]], c.vertices[t[1]], c.vertices[t[2]]);
    const float d = std::sqrt(cp.distance2);
    if (d < args->query->radius) {
      args->query->radius = d;
      c.triangle = args->primID;
      return true;
    }
    return false;
  }

  const TriangleMesh<T>& mesh_;
  std::vector<Vec3<float>> vertices_;
  std::vector<std::array<Index, 3>> triangles_;
  RTCScene scene_ = nullptr;
};

} // namespace ebgeom_bench
