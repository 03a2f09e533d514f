// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// The grid-job rules of the jobs component (what `ebgeom sdf`, `ebgeom-mpi sdf` and the Python
// package share): command-line options parsed into `SdfOptions`, the grid `make_spec` derives from
// them against hand-computed boxes and counts, its errors and exit codes, the input loader on a
// scene and on a mesh file, the mesh report of a closed cube, and the .vdb switch of this build.
#include <gtest/gtest.h>
#include <unistd.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "ebgeom/eval/sparse_grid.hpp"
#include "ebgeom/io/write_mesh.hpp"
#include "ebgeom/jobs/mesh_report.hpp"
#include "ebgeom/jobs/sdf_job.hpp"
#include "ebgeom/jobs/vdb_output.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/mesh/validate.hpp"
#include "ebgeom/sdf/shapes.hpp"

using namespace ebgeom;
using jobs::SdfOptions;

namespace {

std::string test_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path d =
      std::filesystem::temp_directory_path() /
      ("ebgeom-jobs-" + std::string(info->name()) + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d.string();
}

/// `args` parsed as `sdf ARGS` by the options of `ebgeom sdf`.
std::shared_ptr<SdfOptions> parse(std::vector<std::string> args) {
  CLI::App app("test");
  auto* sub = app.add_subcommand("sdf");
  auto o = std::make_shared<SdfOptions>();
  jobs::add_sdf_options(sub, o);
  args.insert(args.begin(), "sdf");
  std::reverse(args.begin(), args.end()); // CLI11 takes the arguments last first
  app.parse(args);
  return o;
}

/// The exit code of the `scene::ToolError` that `f` throws (-1 when it does not throw).
template <class F> int exit_code_of(F&& f, std::string* what = nullptr) {
  try {
    f();
  } catch (const scene::ToolError& e) {
    if (what) *what = e.what();
    return e.code;
  }
  return -1;
}

const Aabb<double> unit_box({0, 0, 0}, {1, 2, 4});

} // namespace

TEST(SdfOptions, ParsedAndValidated) {
  auto o = parse({"in.obj", "-o", "out.npz", "--res", "8", "16", "32", "--band", "2", "--nodes",
                  "--precision", "double"});
  EXPECT_EQ(o->input, "in.obj");
  EXPECT_EQ(o->output, "out.npz");
  EXPECT_EQ(o->res, (std::vector<std::size_t>{8, 16, 32}));
  EXPECT_EQ(o->band, 2.0);
  EXPECT_TRUE(o->nodes);
  EXPECT_EQ(o->precision, "double");
  EXPECT_EQ(o->sign, "auto");
  EXPECT_THROW(parse({"in.obj", "-o", "o.npy", "--res", "8", "16"}), CLI::ValidationError);
  EXPECT_THROW(parse({"in.obj", "-o", "o.npy", "--res", "0"}), CLI::ValidationError);
  EXPECT_THROW(parse({"in.obj", "-o", "o.npy", "--dx", "nan"}), CLI::ValidationError);
  EXPECT_THROW(parse({"in.obj", "-o", "o.npy", "--cubic", "--res", "4", "4", "4"}),
               CLI::ValidationError);
  EXPECT_THROW(parse({"in.obj", "-o", "o.npy", "--res", "8", "--dx", "0.5"}), CLI::ParseError);
}

TEST(MakeSpec, DefaultsPadTheBoundsWith64Cells) {
  SdfOptions o;
  const GridSpec<double> s = jobs::make_spec<double>(o, unit_box);
  EXPECT_EQ(s.centering, Centering::cell);
  EXPECT_EQ(s.dims, (std::array<std::size_t, 3>{{64, 64, 64}}));
  // 10% of each axis's extent on each side
  EXPECT_DOUBLE_EQ(s.box.lo.x, -0.1);
  EXPECT_DOUBLE_EQ(s.box.hi.y, 2.2);
  EXPECT_DOUBLE_EQ(s.box.lo.z, -0.4);
  o.res = {3, 5, 7};
  o.nodes = true;
  const GridSpec<float> f = jobs::make_spec<float>(o, Aabb<float>({0, 0, 0}, {1, 2, 4}));
  EXPECT_EQ(f.centering, Centering::node);
  EXPECT_EQ(f.dims, (std::array<std::size_t, 3>{{3, 5, 7}}));
}

TEST(MakeSpec, DxAndCubicGrowTheBoxToWholeCells) {
  SdfOptions o;
  o.box = {0, 0, 0, 1, 1, 0.9};
  o.dx = 0.25;
  GridSpec<double> s = jobs::make_spec<double>(o, unit_box);
  EXPECT_EQ(s.dims, (std::array<std::size_t, 3>{{4, 4, 4}}));
  EXPECT_DOUBLE_EQ(s.box.hi.z, 1.0); // 0.9 / 0.25 = 3.6 cells: 4
  o.nodes = true;
  s = jobs::make_spec<double>(o, unit_box);
  EXPECT_EQ(s.dims, (std::array<std::size_t, 3>{{5, 5, 5}})); // 4 cells, 5 nodes
  SdfOptions c;
  c.box = {0, 0, 0, 2, 1, 0.5};
  c.cubic = true;
  c.res = {10}; // cells of 0.2 on the longest axis
  s = jobs::make_spec<double>(c, unit_box);
  EXPECT_EQ(s.dims, (std::array<std::size_t, 3>{{10, 5, 3}}));
  EXPECT_NEAR(s.box.hi.z, 0.6, 1e-12);
  const Vec3<double> h = s.spacing();
  EXPECT_NEAR(h.x, 0.2, 1e-12);
  EXPECT_NEAR(h.y, 0.2, 1e-12);
  EXPECT_NEAR(h.z, 0.2, 1e-12);
}

TEST(MakeSpec, BadGridsAreRefusedWithTheirExitCodes) {
  std::string what;
  SdfOptions o;
  o.input = "plane.json";
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(exit_code_of(
                [&] {
                  jobs::make_spec<double>(o, Aabb<double>({-inf, 0, 0}, {inf, 1, 1}));
                },
                &what),
            scene::exit_usage);
  EXPECT_NE(what.find("unbounded"), std::string::npos) << what;
  EXPECT_EQ(exit_code_of([&] {
              jobs::make_spec<double>(o, Aabb<double>({1, 1, 1}, {0, 0, 0}));
            }),
            scene::exit_input); // finite but empty
  o.box = {0, 0, 0, 1, -1, 1};
  EXPECT_EQ(exit_code_of([&] { jobs::make_spec<double>(o, unit_box); }, &what), scene::exit_usage);
  EXPECT_NE(what.find("axis y"), std::string::npos) << what;
  o.box = {0, 0, 0, 1e39, 1, 1}; // beyond float
  EXPECT_EQ(exit_code_of([&] {
              jobs::make_spec<float>(o, Aabb<float>({0, 0, 0}, {1, 1, 1}));
            }),
            scene::exit_usage);
  EXPECT_EQ(exit_code_of([&] { jobs::make_spec<double>(o, unit_box); }), -1); // fine in double
  SdfOptions d;
  d.box = {0, 0, 0, 1, 1, 1};
  d.dx = 1e-7; // over 2^21 cells per axis
  EXPECT_EQ(exit_code_of([&] { jobs::make_spec<double>(d, unit_box); }), scene::exit_usage);
}

TEST(RequireFiniteGrid, CountsTheNonFiniteSamples) {
  EXPECT_EQ(exit_code_of([] { jobs::require_finite_grid(0, 10, "in.json"); }), -1);
  std::string what;
  EXPECT_EQ(exit_code_of([] { jobs::require_finite_grid(3, 10, "in.json"); }, &what),
            scene::exit_input);
  EXPECT_NE(what.find("in.json: 3 of 10 samples"), std::string::npos) << what;
}

TEST(LoadSdfInput, SceneAndMeshFiles) {
  const std::string dir = test_dir();
  SdfOptions o;
  o.input = dir + "/ball.json";
  std::ofstream(o.input) << R"({"type": "sphere", "center": [0.5, 0, 0], "radius": 2})";
  auto s = jobs::load_sdf_input<double>(o, SignMode::automatic);
  EXPECT_TRUE(s.scene);
  EXPECT_EQ(s.prog.triangle_count(), 0u);
  EXPECT_EQ(s.prog({0.5, 0, 3}), 1.0);
  EXPECT_EQ(s.prog({0.5, 0, 0}), -2.0);

  o.input = dir + "/cube.obj";
  ASSERT_TRUE(io::write_mesh(o.input, *make_cube<double>(1.0)));
  auto m = jobs::load_sdf_input<double>(o, SignMode::automatic);
  EXPECT_FALSE(m.scene);
  ASSERT_NE(m.prog.mesh(), nullptr);
  EXPECT_EQ(m.prog.triangle_count(), 12u);
  EXPECT_EQ(m.prog({0, 0, 0}), -1.0);
  EXPECT_EQ(m.prog({3, 0, 0}), 2.0);
  const GridSpec<double> spec = jobs::make_spec<double>(o, m.prog.bounds());
  const auto j = jobs::grid_job_json(o, m, spec, 0.0);
  EXPECT_EQ(j["input_kind"], "mesh");
  EXPECT_EQ(j["triangles"], 12);
  EXPECT_EQ(j["dims"], (std::vector<std::size_t>{64, 64, 64}));
  EXPECT_EQ(j["centering"], "cell");
  EXPECT_EQ(j["precision"], "double");

  o.input = dir + "/missing.obj";
  EXPECT_EQ(exit_code_of([&] { jobs::load_sdf_input<double>(o, SignMode::automatic); }),
            scene::exit_input);
}

TEST(MeshReport, ClosedCube) {
  const PolygonSoup<double> cube = *make_cube<double>(1.0);
  const auto j = jobs::mesh_report_json(validate(cube), cube.triangle_count());
  EXPECT_EQ(j["vertices"], 8);
  EXPECT_EQ(j["triangles"], 12);
  EXPECT_EQ(j["boundary_edges"], 0);
  EXPECT_EQ(j["watertight"], true);
  EXPECT_EQ(j["outward"], true);
  EXPECT_DOUBLE_EQ(j["volume"].get<double>(), 8.0);
  EXPECT_DOUBLE_EQ(j["area"].get<double>(), 24.0);
  EXPECT_EQ(j["auto_sign"]["mode"], "pseudonormal");
  EXPECT_EQ(j["bbox"]["lo"], (std::vector<double>{-1, -1, -1}));
}

TEST(VdbOutput, FollowsTheBuildsSwitch) {
  const std::string dir = test_dir();
  EXPECT_TRUE(jobs::is_vdb_path("a.vdb"));
  EXPECT_FALSE(jobs::is_vdb_path("vdb"));
  GridSpec<float> spec;
  spec.box = Aabb<float>({-1, -1, -1}, {1, 1, 1});
  spec.dims = {{16, 16, 16}};
  GridOptions opt;
  opt.band = 0.3;
  auto g = sample_grid_sparse(Sphere<float>{{0, 0, 0}, 0.6f}, spec, opt);
  ASSERT_TRUE(g);
  const std::string path = dir + "/s.vdb";
  auto ok = jobs::write_vdb(path, *g);
#ifdef EBGEOM_TEST_OPENVDB
  EXPECT_TRUE(jobs::vdb_available());
  ASSERT_TRUE(ok) << ok.error().what();
  EXPECT_EQ(*ok, std::filesystem::file_size(path));
#else
  EXPECT_FALSE(jobs::vdb_available());
  ASSERT_FALSE(ok);
  EXPECT_EQ(ok.error().code, ErrorCode::unsupported);
  EXPECT_NE(std::string(ok.error().what()).find("libopenvdb-dev"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(path));
#endif
}
