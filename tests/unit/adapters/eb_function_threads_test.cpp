// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// EbFunction under concurrent calls: many threads on one object and on per-thread copies give
// exactly the serial values (bit for bit), for a mesh SDF and an analytic CSG scene. Run under
// TSan (EBGEOM_SANITIZE=thread) to check for races, and ASan for lifetime errors.
#include "ebgeom/adapters/eb_function.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "eb_test_scenes.hpp"
#include "ebgeom/sdf/any_sdf.hpp"

using namespace ebgeom;
using namespace ebgeom::adapter_test;

namespace {

const Aabb<double> probe_box = Aabb<double>::of({-1.2, -1.2, -1.2}, {1.2, 1.2, 1.2});

template <class S>
std::vector<double> serial_values(const EbFunction<S>& f, const std::vector<Vec3<double>>& pts) {
  std::vector<double> out(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) out[i] = f(pts[i].x, pts[i].y, pts[i].z);
  return out;
}

// Every thread evaluates every point (so all of them hit the same geometry at the same time),
// either through `f` itself or through its own copy; each writes its own output row.
template <class S> void expect_concurrent_equals_serial(const EbFunction<S>& f) {
  const auto pts = points_in(probe_box, 3000, 11);
  const auto serial = serial_values(f, pts);
  const int n = test_threads();
  for (const bool own_copy : {false, true}) {
    std::vector<std::vector<double>> rows(std::size_t(n), std::vector<double>(pts.size()));
    on_threads(n, [&](int t) {
      const EbFunction<S> mine = f; // copying concurrently is part of the test
      const EbFunction<S>& use = own_copy ? mine : f;
      auto& row = rows[std::size_t(t)];
      // each thread starts at a different point, so that threads work on different parts of
      // the tree at the same instant
      const std::size_t start = std::size_t(t) * pts.size() / std::size_t(n);
      for (std::size_t k = 0; k < pts.size(); ++k) {
        const std::size_t i = (start + k) % pts.size();
        row[i] = use(pts[i].x, pts[i].y, pts[i].z);
      }
    });
    for (int t = 0; t < n; ++t) EXPECT_EQ(rows[std::size_t(t)], serial) << "thread " << t;
  }
  EXPECT_EQ(f.shared_sdf().use_count(), 1); // all thread copies are gone
}

} // namespace

TEST(EbFunctionThreads, MeshSdfOneObjectAndCopies) {
  expect_concurrent_equals_serial(make_eb_function(icosphere_sdf<double>()));
  expect_concurrent_equals_serial(make_eb_function(icosphere_sdf<float>(2)));
}

TEST(EbFunctionThreads, CsgSceneOneObjectAndCopies) {
  expect_concurrent_equals_serial(make_eb_function(csg_scene()));
  expect_concurrent_equals_serial(make_eb_function(AnySdf<double>(csg_scene())));
}

TEST(EbFunctionThreads, TwoDimensionalSliceUnderConcurrency) {
  EbOptions opt;
  opt.z_slice = 0.2;
  const auto f = make_eb_function(icosphere_sdf<double>(), opt);
  const auto pts = points_in(probe_box, 2000, 13);
  std::vector<double> serial(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) serial[i] = f(pts[i].x, pts[i].y);
  const int n = test_threads();
  std::vector<double> par(pts.size());
  on_threads(n, [&](int t) { // interleaved partition of one output, as OpenMP tiles would be
    for (std::size_t i = std::size_t(t); i < pts.size(); i += std::size_t(n))
      par[i] = f(pts[i].x, pts[i].y);
  });
  EXPECT_EQ(par, serial);
}

TEST(EbFunctionThreads, ConcurrentCopiesAndDestructionKeepTheGeometryAlive) {
  auto f = std::make_unique<EbFunction<SignedMeshSdf<double>>>(icosphere_sdf<double>());
  const auto pts = points_in(probe_box, 200, 17);
  const auto serial = serial_values(*f, pts);
  const int n = test_threads();
  std::vector<int> mismatches(std::size_t(n), 0);
  on_threads(n, [&](int t) {
    for (int round = 0; round < 20; ++round) {
      std::vector<EbFunction<SignedMeshSdf<double>>> mine(8, *f); // copy concurrently
      for (std::size_t i = 0; i < pts.size(); ++i)
        mismatches[std::size_t(t)] += mine[i % 8](pts[i].x, pts[i].y, pts[i].z) != serial[i];
    } // and destroy concurrently
  });
  for (int m : mismatches) EXPECT_EQ(m, 0);
  EXPECT_EQ(f->shared_sdf().use_count(), 1);
  // the last owner may be any adapter: the geometry outlives the original
  const EbFunction<SignedMeshSdf<double>> survivor = *f;
  f.reset();
  EXPECT_EQ(survivor(pts[0].x, pts[0].y, pts[0].z), serial[0]);
}
