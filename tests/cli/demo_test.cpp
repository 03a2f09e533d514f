// `ebgeom demo`: outputs exist, agree with each other and with the library's own evaluation.
#include <gtest/gtest.h>

#include "cli_support.hpp"
#include "demo_scene.hpp"

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
  EXPECT_EQ(npy.shape[2], 24u); // x is the longest axis of the demo scene
  EXPECT_EQ(std::size_t(vti.extent[1] + 1), npy.shape[2]);
  EXPECT_EQ(std::size_t(vti.extent[3] + 1), npy.shape[1]);
  EXPECT_EQ(std::size_t(vti.extent[5] + 1), npy.shape[0]);
  ASSERT_EQ(vti.data, npy.data);

  // Every sample equals the scene evaluated at origin + (i, j, k) * spacing.
  const auto scene = cli::make_demo_scene();
  const std::size_t nx = npy.shape[2], ny = npy.shape[1], nz = npy.shape[0];
  std::size_t inside = 0;
  for (std::size_t k = 0; k < nz; ++k)
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i) {
        const Vec3<float> p{float(vti.origin[0] + double(i) * vti.spacing[0]),
                            float(vti.origin[1] + double(j) * vti.spacing[1]),
                            float(vti.origin[2] + double(k) * vti.spacing[2])};
        const double got = npy.data[i + nx * (j + ny * k)];
        ASSERT_NEAR(got, double(scene(p)), 1e-5) << i << " " << j << " " << k;
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
