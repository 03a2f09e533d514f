// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Fast winding number (beta = 2) against the exact winding number on the open shared meshes, at
// random points in each mesh's box grown by 10% per side. The exact sum is O(n) per point, so
// the bunny (69k triangles) gets 20,000 points and the smaller teapot and suzanne 100,000.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "ebgeom/core/parallel.hpp"
#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"
#include "ebgeom/sdf/signed_mesh_sdf.hpp"
#include "ebgeom/sdf/winding.hpp"
#include "test_support.hpp"

namespace ebgeom {
namespace {

struct OpenMesh {
  const char* name;
  std::size_t points;
};

class FastWindingOnOpenMeshes : public ::testing::TestWithParam<OpenMesh> {};

TEST_P(FastWindingOnOpenMeshes, AgreesWithExactOutsideTheBand) {
  const OpenMesh om = GetParam();
  EBGEOM_REQUIRE_MESH(om.name);
  auto soup = io::read_mesh<double>(test::mesh_path(om.name));
  ASSERT_TRUE(soup.has_value()) << soup.error().what();
  const TriangleMesh<double> mesh = make_triangle_mesh(*soup).value();
  const auto fw = FastWindingNumber<double>::make(mesh).value();
  const SignChoice auto_choice = choose_sign_mode(validate(*soup));
  EXPECT_EQ(auto_choice.mode, SignMode::fast_winding) << om.name << " is open";

  const Aabb<double> box = mesh.bounds();
  const auto pts =
      test::random_points(box.grown(0.1 * max_component(box.extent())), om.points, 2024);
  std::vector<double> diff(pts.size()), exact(pts.size());
  ExecOptions ex;
  parallel_for(
      0, pts.size(), 64,
      [&](std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i) {
          exact[i] = winding_number(mesh, pts[i]);
          diff[i] = double(fw(pts[i])) - exact[i];
        }
      },
      ex);
  double worst = 0, mean = 0;
  std::size_t in_band = 0, flips = 0, flips_in_band = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    ASSERT_TRUE(std::isfinite(diff[i]));
    worst = std::max(worst, std::abs(diff[i]));
    mean += std::abs(diff[i]);
    const bool band = std::abs(exact[i] - 0.5) <= 0.1;
    const bool flip = (exact[i] > 0.5) != (exact[i] + diff[i] > 0.5);
    in_band += band;
    if (flip) (band ? flips_in_band : flips)++;
  }
  mean /= double(pts.size());
  std::printf("%s: %zu points, |fast - exact| mean %.2e max %.2e; %zu points with |w - 1/2| <= "
              "0.1, %zu side changes there, %zu outside it\n",
              om.name, pts.size(), mean, worst, in_band, flips_in_band, flips);
  EXPECT_EQ(flips, 0u) << "fast winding changed side outside the documented band";
  EXPECT_LT(worst, 0.1);
  EXPECT_LT(mean, 0.01);
}

INSTANTIATE_TEST_SUITE_P(Shared, FastWindingOnOpenMeshes,
                         ::testing::Values(OpenMesh{"stanford-bunny.obj", 20000},
                                           OpenMesh{"teapot.obj", 100000},
                                           OpenMesh{"suzanne.obj", 100000}),
                         [](const auto& param_info) {
                           std::string n = param_info.param.name;
                           return n.substr(0, n.find_first_of("-."));
                         });

/// Packets of fast winding numbers are the per-point values bit for bit on a real open mesh, at
/// the samples of a 192³ grid's tiles next to the surface (in 4x2x2 groups, two to a packet)
/// and at random points.
TEST(FastWindingPacketsOnOpenMeshes, EqualThePerPointValuesOnTheBunny) {
  EBGEOM_REQUIRE_MESH("stanford-bunny.obj");
  auto soup = io::read_mesh<float>(test::mesh_path("stanford-bunny.obj"));
  ASSERT_TRUE(soup.has_value()) << soup.error().what();
  const TriangleMesh<float> mesh = make_triangle_mesh(*soup).value();
  const auto fw = FastWindingNumber<float>::make(mesh).value();
  const auto sdf = MeshSdf<float>::make(mesh).value();
  const Aabb<float> box = mesh.bounds().grown(0.1f * max_component(mesh.bounds().extent()));
  const float h = max_component(box.extent()) / 192;
  std::vector<Vec3<float>> pts = test::random_points(box, 20000, 7);
  for (int g = 0; g < 4000; ++g) { // 4x2x2 groups around vertices, 0 to 3 cells off the surface
    const Vec3<float>& v = mesh.vertices[std::size_t(g) * 17 % mesh.vertices.size()];
    const Vec3<float> o{box.lo.x + h * std::floor((v.x - box.lo.x) / h + float(g % 3)),
                        box.lo.y + h * std::floor((v.y - box.lo.y) / h),
                        box.lo.z + h * std::floor((v.z - box.lo.z) / h - float(g % 2))};
    for (int z = 0; z < 2; ++z)
      for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x)
          pts.push_back(o + Vec3<float>{float(x), float(y), float(z)} * h);
  }
  std::vector<float> packed(pts.size());
  fw.eval(Span<const Vec3<float>>(pts), Span<float>(packed));
  std::size_t near = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const float w = fw(pts[i]);
    ASSERT_EQ(std::memcmp(&w, &packed[i], sizeof w), 0)
        << pts[i] << ": " << packed[i] << " vs " << w;
    near += std::abs(sdf(pts[i])) <= 3 * h;
  }
  EXPECT_GT(near, pts.size() / 3); // most lattice samples are within a band of 3 cells
}

} // namespace
} // namespace ebgeom
