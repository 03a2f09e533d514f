// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// The BVH mesh SDF on the real meshes of ../shared/meshes (skipped when absent): for every arity
// K = 2, 4, 8, every builder (binned SAH, median, Morton), float and double, `MeshSdf` equals
// `BruteForceMeshSdf` to the last bit. The brute force (O(n) per point) runs on a subset sized to
// the mesh (about 1.2·10^8 triangle tests, threaded); every configuration is then compared, bit for
// bit, with the checked one on 100,000 uniform random points in the bounding box grown by 10%.
// Results must not depend on the thread count.

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "ebgeom/core/parallel.hpp"
#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/sdf/brute_force_mesh_sdf.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"
#include "test_support.hpp"

using namespace ebgeom;

namespace {

template <class T> bool same_bits(T a, T b) { return std::memcmp(&a, &b, sizeof(T)) == 0; }

template <class S, class T>
std::vector<T> evaluate_all(const S& sdf, const std::vector<Vec3<T>>& pts, int threads) {
  std::vector<T> out(pts.size());
  ExecOptions ex;
  ex.threads = threads;
  parallel_for(
      0, pts.size(), 256,
      [&](std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i) out[i] = sdf(pts[i]);
      },
      ex);
  return out;
}

template <class T, int K>
void check_config(const TriangleMesh<T>& mesh, bvh::BuildMethod method,
                  const std::vector<Vec3<T>>& pts, const std::vector<T>& pivot,
                  const std::string& what) {
  auto opt = MeshSdf<T, K>::default_build_options();
  opt.method = method;
  const auto sdf = MeshSdf<T, K>::make(mesh, opt).value();
  const auto got = evaluate_all(sdf, pts, 2);
  std::size_t bad = 0;
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (!same_bits(got[i], pivot[i]) && bad++ < 5)
      ADD_FAILURE() << what << " K=" << K << " method=" << int(method) << " point " << pts[i]
                    << ": " << got[i] << " vs " << pivot[i];
  EXPECT_EQ(bad, 0u) << what << " K=" << K << " method=" << int(method);
}

template <class T> void check_mesh(const std::string& name) {
  auto soup = io::read_mesh<T>(test::mesh_path(name));
  ASSERT_TRUE(soup) << soup.error().what();
  const TriangleMesh<T> mesh = make_triangle_mesh(*soup).value();
  const std::size_t nt = mesh.triangle_count();
  const Aabb<T> box = mesh.bounds().grown(T(0.1) * max_component(mesh.bounds().extent()));
  const auto pts = test::random_points(box, 100000, 2024);

  // Pivot: K = 4, SAH; checked against brute force on a subset.
  const auto pivot_sdf = MeshSdf<T>::make(mesh).value();
  const auto pivot = evaluate_all(pivot_sdf, pts, 2);
  EXPECT_EQ(evaluate_all(pivot_sdf, pts, 1), pivot) << "thread count changed results";
  const std::size_t n_ref =
      std::min<std::size_t>(pts.size(), std::max<std::size_t>(300, 120000000 / nt));
  const std::vector<Vec3<T>> sub(pts.begin(), pts.begin() + std::ptrdiff_t(n_ref));
  const BruteForceMeshSdf<T> brute(mesh);
  const auto ref = evaluate_all(brute, sub, 2);
  std::size_t bad = 0;
  for (std::size_t i = 0; i < n_ref; ++i)
    if (!same_bits(pivot[i], ref[i]) && bad++ < 5)
      ADD_FAILURE() << name << ": point " << sub[i] << ": bvh " << pivot[i] << " brute " << ref[i];
  EXPECT_EQ(bad, 0u) << name << ": BVH differs from the brute force";
  std::printf("%s (%zu triangles, %s): brute force checked on %zu points, every configuration on "
              "%zu\n",
              name.c_str(), nt, sizeof(T) == 4 ? "float" : "double", n_ref, pts.size());

  for (auto m :
       {bvh::BuildMethod::sah_binned, bvh::BuildMethod::median, bvh::BuildMethod::morton}) {
    check_config<T, 2>(mesh, m, pts, pivot, name);
    check_config<T, 4>(mesh, m, pts, pivot, name);
    check_config<T, 8>(mesh, m, pts, pivot, name);
  }
}

class BvhRealMesh : public ::testing::TestWithParam<const char*> {};

TEST_P(BvhRealMesh, EqualsBruteForceForEveryConfigurationFloat) {
  EBGEOM_REQUIRE_MESH(GetParam());
  check_mesh<float>(GetParam());
}
TEST_P(BvhRealMesh, EqualsBruteForceForEveryConfigurationDouble) {
  EBGEOM_REQUIRE_MESH(GetParam());
  check_mesh<double>(GetParam());
}

INSTANTIATE_TEST_SUITE_P(SharedMeshes, BvhRealMesh,
                         ::testing::Values("stanford-bunny.obj", "ogre.obj", "nefertiti.obj",
                                           "spot.obj", "fandisk.obj", "cow.obj", "teapot.obj",
                                           "suzanne.obj", "igea.ply"),
                         [](const auto& param_info) {
                           std::string s = param_info.param;
                           for (char& c : s)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return s;
                         });

} // namespace
