// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Fast winding number (beta = 2) against the exact winding number on the open shared meshes, at
// random points in each mesh's box grown by 10% per side. The exact sum is O(n) per point, so
// the bunny (69k triangles) gets 20,000 points and the smaller teapot and suzanne 100,000.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <vector>

#include "ebgeom/core/parallel.hpp"
#include "ebgeom/io/read_mesh.hpp"
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

} // namespace
} // namespace ebgeom
