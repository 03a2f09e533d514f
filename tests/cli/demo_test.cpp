// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// `ebgeom demo`: outputs exist, agree with each other and with the library's own evaluation.
#include <gtest/gtest.h>

#include "cli_support.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/sdf/brute_force_mesh_sdf.hpp"

using namespace ebgeom;
using namespace ebgeom::clitest;

TEST(Demo, WritesVtiNpyPngThatAgreeWithTheLibrary) {
  const std::string dir = test_dir();
  const RunResult r = run("demo --quiet --res 24 -o '" + dir + "'");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err; // no progress bar when stderr is not a terminal
  EXPECT_NE(r.out.find("ebgeom demo:"), std::string::npos);
  EXPECT_NE(r.out.find("inside fraction"), std::string::npos);

  const Npy npy = read_npy(dir + "/demo.npy");
  const Vti vti = read_vti(dir + "/demo.vti");
  ASSERT_EQ(npy.shape.size(), 3u);
  EXPECT_EQ(npy.descr, "<f4");
  EXPECT_FALSE(npy.fortran);
  EXPECT_EQ(*std::max_element(npy.shape.begin(), npy.shape.end()), 24u); // --res: longest axis
  EXPECT_EQ(std::size_t(vti.extent[1] + 1), npy.shape[2]);
  EXPECT_EQ(std::size_t(vti.extent[3] + 1), npy.shape[1]);
  EXPECT_EQ(std::size_t(vti.extent[5] + 1), npy.shape[0]);
  ASSERT_EQ(vti.data, npy.data);

  // Every sample equals the demo scene (tools/ebgeom/demo_scene.hpp) rebuilt here from closed
  // forms and the library's mesh SDF of the same generated icosphere.
  const auto ico = BruteForceMeshSdf<double>::build(make_icosphere<double>(2, 1.0).value()).value();
  auto scene = [&](const Vec3<double>& p) {
    const Vec3<double> q = abs(p - Vec3<double>{0.6, 0.6, 0.6}) - Vec3<double>::constant(0.5);
    const double box = norm(max(q, Vec3<double>::zero())) + std::min(max_component(q), 0.0);
    const double body = std::max(ico(p), -box);
    const double c = std::cos(20 * M_PI / 180), s = std::sin(20 * M_PI / 180);
    const Vec3<double> t{p.x, c * p.y + s * p.z, -s * p.y + c * p.z};
    const double torus = std::hypot(std::hypot(t.x, t.y) - 1.5, t.z) - 0.2;
    const Vec3<double> a{0, 0, 0.9}, ab{0, 0, 0.8};
    const double h = std::clamp(dot(p - a, ab) / dot(ab, ab), 0.0, 1.0);
    const double capsule = norm(p - (a + ab * h)) - 0.12;
    const double ball = norm(p - Vec3<double>{0, 0, 1.9}) - 0.3;
    const double k = 0.25, w = std::max(k - std::abs(capsule - ball), 0.0) / k;
    const double mast = std::min(capsule, ball) - w * w * k / 4;
    return std::min({body, torus, mast});
  };
  const std::size_t nx = npy.shape[2], ny = npy.shape[1], nz = npy.shape[0];
  std::size_t inside = 0;
  for (std::size_t k = 0; k < nz; ++k)
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i) {
        const Vec3<double> p{vti.origin[0] + double(i) * vti.spacing[0],
                             vti.origin[1] + double(j) * vti.spacing[1],
                             vti.origin[2] + double(k) * vti.spacing[2]};
        const double got = npy.data[i + nx * (j + ny * k)];
        ASSERT_NEAR(got, scene(p), 2e-5) << i << " " << j << " " << k;
        inside += got < 0;
      }
  EXPECT_GT(inside, 0u);
  EXPECT_LT(inside, nx * ny * nz);

  const Png png = read_png(dir + "/demo.png");
  EXPECT_GE(png.width, 256u);
  EXPECT_GE(png.height, 256u);
  // Inside (blue-dominant), outside (red-dominant) and the zero level set (black) all appear.
  std::size_t blue = 0, red = 0, black = 0;
  for (std::size_t q = 0; q + 2 < png.rgb.size(); q += 3) {
    const int R = png.rgb[q], G = png.rgb[q + 1], B = png.rgb[q + 2];
    blue += B > R + 30;
    red += R > B + 30;
    black += R + G + B == 0;
  }
  EXPECT_GT(blue, 1000u);
  EXPECT_GT(red, 1000u);
  EXPECT_GT(black, 100u);
  // No temporary files left behind.
  for (const auto& name : list_dir(dir)) EXPECT_EQ(name.find("tmp"), std::string::npos) << name;
}

TEST(Demo, UnwritableDirectoryIsAnOutputError) {
  const std::string dir = test_dir();
  const std::string file = dir + "/plainfile";
  std::ofstream(file) << "x";
  const RunResult r = run("demo --quiet --res 8 -o '" + file + "/sub'");
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_EQ(r.err.rfind("ebgeom: error: ", 0), 0u) << r.err;
}

TEST(Cli, UsageErrorsExitWith2) {
  RunResult r = run("");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("ebgeom: error:"), std::string::npos) << r.err;
  r = run("demo --res 0");
  EXPECT_EQ(r.code, 2) << r.err;
  r = run("no-such-command");
  EXPECT_EQ(r.code, 2) << r.err;
  r = run("--help");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("demo"), std::string::npos);
  r = run("--version");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("ebgeom "), std::string::npos);
}
