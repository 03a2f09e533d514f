// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Grid outputs that carry their geometry: the dense .npz (read with the tests' ZIP reader and,
// when Debian's python3 has numpy, with numpy.load), --cubic cells, and the OpenVDB level set
// (read back with OpenVDB and compared voxel by voxel with the dense .npy of the same command).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>

#include "cli_support.hpp"
#include "zip_reader.hpp"

#if EBGEOM_TEST_OPENVDB
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#endif

using namespace ebgeom::clitest;

namespace {

/// A box of extent 2 x 1 x 0.5 minus nothing: a non-cubic input, so that --cubic matters.
std::string slab_scene(const std::string& dir) {
  const std::string p = dir + "/slab.json";
  std::ofstream(p)
      << R"({"type": "box", "center": [0.5, 0.25, 0.125], "half_size": [1, 0.5, 0.25]})";
  return p;
}

/// An L-shaped prism, as OBJ, for the OpenVDB tests (a closed non-convex mesh).
std::string l_prism(const std::string& dir) {
  const std::string p = dir + "/l.obj";
  std::ofstream(p) << "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nv 0 0 1\nv 2 0 1\n"
                      "v 2 1 1\nv 1 1 1\nv 1 2 1\nv 0 2 1\nf 1 6 5 4 3 2\nf 7 8 9 10 11 12\n"
                      "f 1 2 8 7\nf 2 3 9 8\nf 3 4 10 9\nf 4 5 11 10\nf 5 6 12 11\nf 6 1 7 12\n";
  return p;
}

std::map<std::string, NpyArray> read_npz_members(const std::string& path) {
  return read_npz_bytes(slurp(path), path);
}

} // namespace

// Without --band, .npz is the dense grid with its geometry: `sdf` holds exactly the .npy's
// values and `origin`, `spacing`, `box`, `centering` what --json reports.
TEST(DenseNpz, CarriesTheGridAndItsGeometry) {
  const std::string dir = test_dir();
  const std::string in = slab_scene(dir);
  for (const char* opts : {" --res 12 10 8", " --res 9 --nodes --precision double"}) {
    RunResult r = run("sdf '" + in + "' -o '" + dir + "/g.npy' -q" + opts);
    ASSERT_EQ(r.code, 0) << r.err;
    r = run("sdf '" + in + "' -o '" + dir + "/g.npz' --json" + opts);
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["format"], "dense");
    const std::string npy = slurp(dir + "/g.npy");
    auto m = read_npz_members(dir + "/g.npz");
    ASSERT_EQ(m.size(), 5u) << opts;
    const NpyArray dense = parse_npy(npy, "g.npy");
    EXPECT_EQ(m["sdf"].descr, dense.descr);
    EXPECT_EQ(m["sdf"].shape, dense.shape);
    EXPECT_EQ(m["sdf"].data, dense.data) << opts; // bit for bit
    ASSERT_EQ(m["origin"].count(), 3u);
    ASSERT_EQ(m["spacing"].count(), 3u);
    ASSERT_EQ(m["box"].shape, (std::vector<std::size_t>{2, 3}));
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(m["origin"].at<double>(a), j["origin"][a].get<double>());
      EXPECT_EQ(m["spacing"].at<double>(a), j["spacing"][a].get<double>());
      EXPECT_EQ(m["box"].at<double>(a), j["box"]["lo"][a].get<double>());
      EXPECT_EQ(m["box"].at<double>(3 + a), j["box"]["hi"][a].get<double>());
    }
    const std::string c = j["centering"];
    EXPECT_EQ(m["centering"].descr, "<U" + std::to_string(c.size()));
    std::string text;
    for (std::size_t i = 0; i < m["centering"].data.size(); i += 4) text += m["centering"].data[i];
    EXPECT_EQ(text, c);
  }
}

// numpy.load reads the dense .npz; its members give the sample positions. Skipped without
// Debian's python3 + numpy.
TEST(DenseNpz, NumpyLoadsIt) {
  const std::string py = EBGEOM_SYSTEM_PYTHON;
  if (py.empty() || std::system(("'" + py + "' -c 'import numpy' 2>/dev/null").c_str()) != 0)
    GTEST_SKIP() << "no python3 with numpy";
  const std::string dir = test_dir();
  const std::string in = slab_scene(dir);
  RunResult r = run("sdf '" + in + "' -o '" + dir + "/g.npz' -q --res 10 7 5");
  ASSERT_EQ(r.code, 0) << r.err;
  r = run("sdf '" + in + "' -o '" + dir + "/g.npy' -q --res 10 7 5");
  ASSERT_EQ(r.code, 0) << r.err;
  // The box SDF at the sample positions the .npz describes, in numpy (float64), against the
  // stored float32 values.
  const std::string script =
      "import numpy as np, sys\n"
      "z = np.load(sys.argv[1])\n"
      "assert sorted(z.files) == ['box', 'centering', 'origin', 'sdf', 'spacing'], z.files\n"
      "s = z['sdf']\n"
      "assert s.shape == (5, 7, 10) and s.dtype == np.float32, (s.shape, s.dtype)\n"
      "assert str(z['centering']) == 'cell'\n"
      "assert np.array_equal(s, np.load(sys.argv[2]))\n"
      "o, h = z['origin'], z['spacing']\n"
      "k, j, i = np.indices(s.shape)\n"
      "p = np.stack([o[0] + i * h[0], o[1] + j * h[1], o[2] + k * h[2]], -1)\n"
      "q = np.abs(p - [0.5, 0.25, 0.125]) - [1, 0.5, 0.25]\n"
      "ref = np.linalg.norm(np.maximum(q, 0), axis=-1) + np.minimum(q.max(-1), 0)\n"
      "assert np.allclose(s, ref, atol=1e-5), np.abs(s - ref).max()\n"
      "b = z['box']\n"
      "assert np.allclose(b[0] + h / 2, o) and np.allclose(b[0] + h * [10, 7, 5], b[1])\n";
  std::ofstream(dir + "/check.py") << script;
  const int st = std::system(("'" + py + "' '" + dir + "/check.py' '" + dir + "/g.npz' '" + dir +
                              "/g.npy' > '" + dir + "/py.log' 2>&1")
                                 .c_str());
  EXPECT_EQ(st, 0) << slurp(dir + "/py.log");
}

// --cubic: N cells on the longest axis, cubic cells, the box grown to a whole number of them;
// plain --res N keeps the input box and gives each axis N cells (not cubic).
TEST(Cubic, CellsAreCubicAndCoverTheBox) {
  const std::string dir = test_dir();
  const std::string in = slab_scene(dir);
  RunResult r = run("sdf '" + in + "' -o '" + dir + "/c.npy' --res 40 --cubic --pad 0.1 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  const double h = j["spacing"][0];
  EXPECT_EQ(j["spacing"][1].get<double>(), h);
  EXPECT_EQ(j["spacing"][2].get<double>(), h);
  EXPECT_EQ(j["dims"][0], 40);
  // extent with 10% padding per side: 2.4 x 1.2 x 0.6 -> 40 x 20 x 10 cells of 0.06
  EXPECT_NEAR(h, 2.4 / 40, 1e-6);
  EXPECT_EQ(j["dims"][1], 20);
  EXPECT_EQ(j["dims"][2], 10);
  for (int a = 0; a < 3; ++a) {
    const double lo = j["box"]["lo"][a], hi = j["box"]["hi"][a];
    EXPECT_NEAR(hi - lo, h * j["dims"][a].get<double>(), 1e-5) << a;
  }
  EXPECT_EQ(read_npy(dir + "/c.npy").shape, (std::vector<std::size_t>{10, 20, 40}));
  // nodes: N samples on the longest axis, N - 1 cells
  r = run("sdf '" + in + "' -o '" + dir + "/n.npy' --res 41 --cubic --nodes --json");
  ASSERT_EQ(r.code, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["dims"][0], 41);
  EXPECT_EQ(j["spacing"][0].get<double>(), j["spacing"][2].get<double>());
  // without --cubic: N cells per axis, spacing differs
  r = run("sdf '" + in + "' -o '" + dir + "/p.npy' --res 40 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["dims"][1], 40);
  EXPECT_NE(j["spacing"][0].get<double>(), j["spacing"][1].get<double>());
  // --cubic takes one N, and not --dx (already cubic)
  EXPECT_EQ(run("sdf '" + in + "' -o '" + dir + "/x.npy' --res 4 5 6 --cubic").code, 2);
  EXPECT_EQ(run("sdf '" + in + "' -o '" + dir + "/x.npy' --dx 0.1 --cubic").code, 2);
}

#if EBGEOM_TEST_OPENVDB

namespace {

/// Reads the one grid of `path`, checks it is a level set named "sdf" of type `Grid` and that
/// every voxel the dense `.npy` of the same command covers holds the dense value: active where
/// |S| < band, inactive ±band (the dense value) elsewhere; nothing active outside the grid.
template <class Grid>
void check_vdb_equals_dense(const std::string& vdb, const std::string& npy,
                            const nlohmann::json& j) {
  openvdb::initialize();
  openvdb::io::File f(vdb);
  f.open();
  openvdb::GridPtrVecPtr grids = f.getGrids();
  f.close();
  ASSERT_EQ(grids->size(), 1u);
  auto grid = openvdb::gridPtrCast<Grid>((*grids)[0]);
  ASSERT_TRUE(grid) << "grid type " << (*grids)[0]->type();
  EXPECT_EQ(grid->getName(), "sdf");
  EXPECT_EQ(grid->getGridClass(), openvdb::GRID_LEVEL_SET);
  // the band in the grid's precision (the JSON reports it in double)
  const double band = double(typename Grid::ValueType(j["band"].get<double>()));
  EXPECT_EQ(double(grid->background()), band);
  const Npy d = read_npy(npy);
  const std::size_t nx = d.shape[2], ny = d.shape[1], nz = d.shape[0];
  // the transform puts index (i, j, k) on the sample position origin + (i, j, k) * spacing
  for (const auto& ijk : {openvdb::Coord(0, 0, 0), openvdb::Coord(int(nx) - 1, 3, int(nz) - 1)}) {
    const openvdb::Vec3d w = grid->transform().indexToWorld(ijk);
    for (int a = 0; a < 3; ++a)
      EXPECT_NEAR(w[a], j["origin"][a].get<double>() + ijk[a] * j["spacing"][a].get<double>(),
                  1e-12);
  }
  auto acc = grid->getConstAccessor();
  std::size_t active = 0;
  for (std::size_t k = 0; k < nz; ++k)
    for (std::size_t jj = 0; jj < ny; ++jj)
      for (std::size_t i = 0; i < nx; ++i) {
        const double v = d.data[i + nx * (jj + ny * k)];
        const openvdb::Coord c{int(i), int(jj), int(k)};
        const bool on = std::abs(v) < band;
        active += on;
        ASSERT_EQ(acc.isValueOn(c), on) << c << " dense " << v;
        ASSERT_EQ(double(acc.getValue(c)), on ? v : (v < 0 ? -band : band)) << c << " dense " << v;
      }
  EXPECT_EQ(grid->activeVoxelCount(), active);
  EXPECT_GT(active, 0u);
  // leaves are ebgeom's 8^3 tiles: every leaf origin is a multiple of 8
  for (auto leaf = grid->tree().cbeginLeaf(); leaf; ++leaf)
    for (int a = 0; a < 3; ++a) EXPECT_EQ(leaf->origin()[a] % 8, 0);
}

} // namespace

TEST(OpenVdb, LevelSetEqualsTheDenseBand) {
  const std::string dir = test_dir();
  const std::string in = l_prism(dir);
  for (const char* opts : {" --res 37 --cubic --band 2.5", " --res 20 --band 3 --nodes",
                           " --res 30 --band 2 --precision double"}) {
    const bool dbl = std::string(opts).find("double") != std::string::npos;
    RunResult r = run("sdf '" + in + "' -o '" + dir + "/d.npy' -q" + opts);
    ASSERT_EQ(r.code, 0) << r.err;
    r = run("sdf '" + in + "' -o '" + dir + "/s.vdb' --json" + opts);
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["format"], "openvdb");
    EXPECT_EQ(j["output_bytes"].get<std::size_t>(), slurp(dir + "/s.vdb").size());
    if (dbl)
      check_vdb_equals_dense<openvdb::DoubleGrid>(dir + "/s.vdb", dir + "/d.npy", j);
    else
      check_vdb_equals_dense<openvdb::FloatGrid>(dir + "/s.vdb", dir + "/d.npy", j);
  }
}

// OpenVDB's own vdb_print opens the file (skipped when openvdb-tools is not installed).
TEST(OpenVdb, VdbPrintReadsIt) {
  const std::string vdb_print = EBGEOM_VDB_PRINT;
  if (vdb_print.empty()) GTEST_SKIP() << "vdb_print not found (Debian package openvdb-tools)";
  const std::string dir = test_dir();
  RunResult r = run("sdf '" + l_prism(dir) + "' -o '" + dir + "/s.vdb' -q --res 24 --band 3");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string log = dir + "/print.log";
  const int st =
      std::system(("'" + vdb_print + "' -l '" + dir + "/s.vdb' > '" + log + "' 2>&1").c_str());
  EXPECT_EQ(st, 0) << slurp(log);
  EXPECT_NE(slurp(log).find("level set"), std::string::npos) << slurp(log);
}

#endif

TEST(OpenVdb, NeedsABand) {
  const std::string dir = test_dir();
  const RunResult r = run("sdf '" + l_prism(dir) + "' -o '" + dir + "/s.vdb' --res 8");
  EXPECT_EQ(r.code, 2) << r.err;
#if EBGEOM_TEST_OPENVDB
  EXPECT_NE(r.err.find("needs --band"), std::string::npos) << r.err;
#else
  EXPECT_TRUE(r.err.find("needs --band") != std::string::npos ||
              r.err.find("libopenvdb-dev") != std::string::npos)
      << r.err;
#endif
  EXPECT_FALSE(exists(dir + "/s.vdb"));
}
