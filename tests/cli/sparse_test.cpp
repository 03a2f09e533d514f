// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// `ebgeom sdf ... -o OUT.npz --band W`: the sparse narrow-band output, read back with the tests'
// own ZIP and .npy readers (zip_reader.hpp, CRCs recomputed with zlib), against the dense .npy of
// the same command sample for sample; a grid too large for a dense array; error paths. The archive
// writer itself is tested in jobs/tests/npz_test.cpp.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

#include "cli_support.hpp"
#include "zip_reader.hpp"

using namespace ebgeom;
using namespace ebgeom::clitest;

namespace {

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

std::map<std::string, NpyArray> read_npz(const std::string& path) {
  std::map<std::string, NpyArray> m;
  const Zip z = read_zip(slurp(path));
  EXPECT_TRUE(z.ok) << path;
  for (const auto& [name, e] : z.entries) {
    EXPECT_EQ(name.substr(name.size() - 4), ".npy") << name;
    m[name.substr(0, name.size() - 4)] = parse_npy(e.data, path + ":" + name);
  }
  return m;
}

/// Bytes of memory in the machine (MemTotal), 0 if unknown.
std::uint64_t total_memory_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string key, unit;
  std::uint64_t kib = 0;
  while (in >> key >> kib) {
    std::getline(in, unit);
    if (key == "MemTotal:") return kib * 1024;
  }
  return 0;
}

/// Runs the same job as .npy and as .npz and checks the .npz sample by sample: kept tiles equal
/// the dense band bit for bit, skipped tiles hold the dense grid's value (±band, its sign), the
/// padding of partial tiles is +band; the metadata and the JSON statistics agree.
template <class T>
void check_sparse_equals_dense(const std::string& dir, const std::string& input,
                               const std::string& opts) {
  RunResult r = run("sdf '" + input + "' -o '" + dir + "/d.npy' --json" + opts);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto jd = nlohmann::json::parse(r.out);
  r = run("sdf '" + input + "' -o '" + dir + "/s.npz' --json" + opts);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto js = nlohmann::json::parse(r.out);
  const Npy dense = read_npy(dir + "/d.npy");
  const std::string dense_bytes = slurp(dir + "/d.npy");
  auto z = read_npz(dir + "/s.npz");
  const char* vt = sizeof(T) == 4 ? "<f4" : "<f8";
  for (const char* k : {"dims", "tile", "origin", "spacing", "box", "band", "centering", "tiles",
                        "tile_code", "values"})
    ASSERT_TRUE(z.count(k)) << k;
  ASSERT_EQ(z["dims"].descr, "<u8");
  ASSERT_EQ(z["dims"].shape, std::vector<std::size_t>{3});
  const std::size_t nx = z["dims"].at<std::uint64_t>(0), ny = z["dims"].at<std::uint64_t>(1),
                    nz = z["dims"].at<std::uint64_t>(2);
  EXPECT_EQ(jd["dims"], nlohmann::json::array({nx, ny, nz}));
  ASSERT_EQ(dense.shape, (std::vector<std::size_t>{nz, ny, nx}));
  EXPECT_EQ(z["tile"].descr, "<i8");
  EXPECT_TRUE(z["tile"].shape.empty());
  EXPECT_EQ(z["tile"].at<std::int64_t>(0), 8);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(z["origin"].at<double>(a), jd["origin"][a].get<double>());
    EXPECT_EQ(z["spacing"].at<double>(a), jd["spacing"][a].get<double>());
    EXPECT_EQ(z["box"].at<double>(a), jd["box"]["lo"][a].get<double>());
    EXPECT_EQ(z["box"].at<double>(3 + a), jd["box"]["hi"][a].get<double>());
  }
  EXPECT_EQ(z["box"].shape, (std::vector<std::size_t>{2, 3}));
  ASSERT_EQ(z["band"].descr, vt);
  const T band = z["band"].at<T>(0);
  EXPECT_EQ(band, T(jd["band"].get<double>()));
  const std::string centring = jd["centering"].get<std::string>();
  EXPECT_EQ(z["centering"].descr, "<U" + std::to_string(centring.size()));
  std::string text;
  for (std::size_t i = 0; i < z["centering"].data.size(); i += 4) text += z["centering"].data[i];
  EXPECT_EQ(text, centring);

  const std::size_t tx = (nx + 7) / 8, ty = (ny + 7) / 8, tz = (nz + 7) / 8;
  const NpyArray& code = z["tile_code"];
  EXPECT_FALSE(z.count("blocks")) << "the kept tiles' member is named tiles (blocks in 0.1)";
  const NpyArray& kept = z["tiles"];
  const NpyArray& values = z["values"];
  ASSERT_EQ(code.descr, "<i4");
  ASSERT_EQ(code.shape, (std::vector<std::size_t>{tz, ty, tx}));
  ASSERT_EQ(kept.descr, "<u4");
  const std::size_t m = kept.shape.at(0);
  ASSERT_EQ(kept.shape, (std::vector<std::size_t>{m, 3}));
  ASSERT_EQ(values.descr, vt);
  ASSERT_EQ(values.shape, (std::vector<std::size_t>{m, 8, 8, 8}));
  ASSERT_EQ(values.data.size(), m * 512 * sizeof(T));
  EXPECT_EQ(js["kept_tiles"].get<std::size_t>(), m);
  EXPECT_EQ(js["blocks"].get<std::size_t>(), m); // its 0.1 name, kept for one release
  EXPECT_EQ(js["tiles"], nlohmann::json::array({tx, ty, tz}));
  EXPECT_EQ(js["format"], "sparse");
  EXPECT_EQ(js["output_bytes"].get<std::size_t>(), slurp(dir + "/s.npz").size());
  EXPECT_GT(m, 0u);
  EXPECT_LT(m, tx * ty * tz) << "nothing was skipped: the test would not test skipping";
  // Each kept tile sits where tile_code points to it, once.
  std::vector<int> seen(m, 0);
  for (std::size_t b = 0; b < m; ++b) {
    const std::size_t bx = kept.at<std::uint32_t>(3 * b), by = kept.at<std::uint32_t>(3 * b + 1),
                      bz = kept.at<std::uint32_t>(3 * b + 2);
    ASSERT_TRUE(bx < tx && by < ty && bz < tz);
    EXPECT_EQ(code.at<std::int32_t>(bx + tx * (by + ty * bz)), std::int32_t(b));
  }
  const std::size_t w = sizeof(T);
  const std::size_t head = dense_bytes.size() - nx * ny * nz * w;
  std::size_t skipped = 0, padding = 0;
  for (std::size_t k = 0; k < tz * 8; ++k)
    for (std::size_t j = 0; j < ty * 8; ++j)
      for (std::size_t i = 0; i < tx * 8; ++i) {
        const std::int32_t c = code.at<std::int32_t>(i / 8 + tx * (j / 8 + ty * (k / 8)));
        ASSERT_TRUE(c >= -2 && c < std::int32_t(m)) << c;
        // values[b, z, y, x] is sample tiles[b] * 8 + (x, y, z).
        const std::size_t at =
            c >= 0 ? (std::size_t(c) * 512 + i % 8 + 8 * (j % 8 + 8 * (k % 8))) : 0;
        if (c >= 0) ++seen[std::size_t(c)];
        if (i >= nx || j >= ny || k >= nz) {
          if (c >= 0) {
            ASSERT_EQ(values.at<T>(at), band) << "padding";
          }
          ++padding;
          continue;
        }
        const char* d = dense_bytes.data() + head + (i + nx * (j + ny * k)) * w;
        if (c >= 0) {
          ASSERT_EQ(std::memcmp(values.data.data() + at * w, d, w), 0)
              << "sample " << i << " " << j << " " << k << ": " << values.at<T>(at) << " vs "
              << dense.data[i + nx * (j + ny * k)];
        } else {
          T v;
          std::memcpy(&v, d, w);
          ASSERT_EQ(v, c == -1 ? -band : band) << "skipped sample " << i << " " << j << " " << k;
          ++skipped;
        }
      }
  for (int s : seen) EXPECT_EQ(s, 512);
  EXPECT_GT(skipped, 0u);
  // The statistics are those of the dense grid (skipped inside tiles count as inside).
  for (const char* k : {"min", "max", "inside_fraction"})
    EXPECT_EQ(js[k].get<double>(), jd[k].get<double>()) << k;
  (void)padding;
}

std::string sphere_scene(const std::string& dir) {
  write_text(dir + "/s.json", R"({"type": "union", "children": [
      {"type": "sphere", "radius": 1},
      {"type": "box", "center": [1.2, 0.6, 0], "half_size": [0.3, 0.5, 0.4]}]})");
  return dir + "/s.json";
}

} // namespace

TEST(SparseNpz, EqualsTheDenseBandSampleForSample) {
  const std::string dir = test_dir();
  const std::string in = sphere_scene(dir);
  // Partial tiles on every axis, float and double, cell and node centring, a mesh input.
  check_sparse_equals_dense<float>(dir, in, " --res 37 29 21 --band 2");
  check_sparse_equals_dense<double>(dir, in,
                                    " --res 40 17 33 --band 1.5 --precision double --nodes");
  check_sparse_equals_dense<float>(
      dir, std::string(EBGEOM_SOURCE_DIR) + "/examples/scenes/csg.json", " --res 48 --band 3");
  write_text(dir + "/m.json", R"({"type": "mesh", "generate": "icosphere", "subdivisions": 2})");
  check_sparse_equals_dense<float>(dir, dir + "/m.json", " --res 30 --band 2");
}

TEST(SparseNpz, EqualInputsGiveEqualFilesWhateverTheThreads) {
  const std::string dir = test_dir();
  const std::string in = sphere_scene(dir);
  RunResult r = run("sdf '" + in + "' -o '" + dir + "/a.npz' --res 40 --band 2 -q --threads 1");
  ASSERT_EQ(r.code, 0) << r.err;
  r = run("sdf '" + in + "' -o '" + dir + "/b.npz' --res 40 --band 2 -q --threads 2");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(dir + "/a.npz"), slurp(dir + "/b.npz"));
  const Zip z = read_zip(slurp(dir + "/a.npz"));
  EXPECT_FALSE(z.zip64_end);
  for (const auto& [name, e] : z.entries) EXPECT_FALSE(e.zip64) << name;
}

TEST(SparseNpz, PngSliceEqualsTheDenseOne) {
  const std::string dir = test_dir();
  const std::string in = sphere_scene(dir);
  const std::string opts = " --res 45 31 27 --band 2 -q --slice y=0.4 --png ";
  RunResult r = run("sdf '" + in + "' -o '" + dir + "/d.npy'" + opts + "'" + dir + "/d.png'");
  ASSERT_EQ(r.code, 0) << r.err;
  r = run("sdf '" + in + "' -o '" + dir + "/s.npz'" + opts + "'" + dir + "/s.png'");
  ASSERT_EQ(r.code, 0) << r.err;
  const Png d = read_png(dir + "/d.png"), s = read_png(dir + "/s.png");
  EXPECT_EQ(d.width, s.width);
  EXPECT_EQ(d.height, s.height);
  EXPECT_TRUE(d.rgb == s.rgb);
}

TEST(SparseNpz, TextSummaryNamesTheKeptTiles) {
  const std::string dir = test_dir();
  const std::string in = sphere_scene(dir);
  const RunResult r = run("sdf '" + in + "' -o '" + dir + "/s.npz' --res 64 --band 2");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("tiles of 8^3 kept"), std::string::npos) << r.out;
}

TEST(SparseNpz, GridTooLargeForADenseArrayIsWrittenSparse) {
  const std::uint64_t mem = total_memory_bytes();
  if (mem == 0) GTEST_SKIP() << "no /proc/meminfo";
  // A double grid of twice the machine's memory around a small sphere: refused as .npy, written
  // as .npz without ever allocating the dense array (which could not succeed).
  const std::uint64_t samples = mem / 8 * 2;
  std::size_t n = std::size_t(std::cbrt(double(samples))) + 1;
  n = (n + 7) / 8 * 8;
  const std::uint64_t dense = std::uint64_t(n) * n * n * 8;
  ASSERT_GT(dense, mem);
  const std::string dir = test_dir();
  write_text(dir + "/s.json", R"({"type": "sphere", "center": [0.1, 0, 0], "radius": 0.02})");
  const std::string opts =
      " --res " + std::to_string(n) + " --box -1 -1 -1 1 1 1 --band 2 --precision double";
  RunResult r = run("sdf '" + dir + "/s.json' -o '" + dir + "/x.npy' -q" + opts);
  EXPECT_EQ(r.code, 5) << r.err;
  char need[64];
  std::snprintf(need, sizeof need, "needs %.1f GiB", double(dense) / double(1u << 30));
  EXPECT_NE(r.err.find(need), std::string::npos) << need << "\n" << r.err;
  EXPECT_NE(r.err.find(".npz --band"), std::string::npos) << r.err;
  EXPECT_FALSE(exists(dir + "/x.npy"));

  r = run("sdf '" + dir + "/s.json' -o '" + dir + "/x.npz' --json" + opts);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["dense_bytes"].get<std::uint64_t>(), dense);
  EXPECT_LT(j["sparse_bytes"].get<std::uint64_t>(), dense / 512);
  auto z = read_npz(dir + "/x.npz");
  EXPECT_EQ(z["dims"].at<std::uint64_t>(2), n);
  const NpyArray& code = z["tile_code"];
  const std::size_t t = n / 8, m = z["tiles"].shape.at(0);
  ASSERT_EQ(code.shape, (std::vector<std::size_t>{t, t, t}));
  EXPECT_EQ(j["kept_tiles"].get<std::size_t>(), m);
  // Kept samples are the sphere's distance (clamped to the band); skipped tiles have its sign.
  const double h = 2.0 / double(n), band = z["band"].at<double>(0);
  EXPECT_DOUBLE_EQ(band, 2 * h);
  for (std::size_t b = 0; b < m; ++b)
    for (int s = 0; s < 512; s += 37) {
      const std::size_t i = z["tiles"].at<std::uint32_t>(3 * b) * 8 + std::size_t(s % 8);
      const std::size_t jj = z["tiles"].at<std::uint32_t>(3 * b + 1) * 8 + std::size_t(s / 8 % 8);
      const std::size_t k = z["tiles"].at<std::uint32_t>(3 * b + 2) * 8 + std::size_t(s / 64);
      const double x = -1 + (double(i) + 0.5) * h - 0.1, y = -1 + (double(jj) + 0.5) * h,
                   zc = -1 + (double(k) + 0.5) * h;
      const double d = std::sqrt(x * x + y * y + zc * zc) - 0.02;
      const double expect = std::abs(d) <= band ? d : std::copysign(band, d);
      ASSERT_NEAR(z["values"].at<double>(b * 512 + std::size_t(s)), expect, 1e-12);
    }
  std::size_t inside = 0;
  for (std::size_t c = 0; c < code.count(); ++c) inside += code.at<std::int32_t>(c) == -1;
  EXPECT_GT(inside, 0u); // the sphere is bigger than a tile
}

TEST(SparseNpz, Errors) {
  const std::string dir = test_dir();
  const std::string in = sphere_scene(dir);
  // .npz is the sparse band only with --band W > 0: without it (or with 0) it is the dense grid
  // (formats_test.cpp checks its content).
  for (const char* opts : {" --res 16", " --res 16 --band 0"}) {
    const RunResult r = run("sdf '" + in + "' -o '" + dir + "/x.npz' -q" + opts);
    EXPECT_EQ(r.code, 0) << opts << r.err;
    const auto z = read_npz(dir + "/x.npz");
    EXPECT_EQ(z.count("sdf"), 1u) << opts;
    EXPECT_EQ(z.count("values"), 0u) << opts;
  }
  RunResult r = run("sdf '" + in + "' -o '" + dir + "/x.txt' --band 2");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(".npz"), std::string::npos) << r.err;
  r = run("sdf '" + in + "' -o '" + dir + "/no/such/dir/x.npz' --res 16 --band 2 -q");
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_NE(r.err.find("no/such/dir/x.npz: cannot open for writing"), std::string::npos) << r.err;
  // An unwritable PNG after the .npz: an output error too.
  r = run("sdf '" + in + "' -o '" + dir + "/x.npz' --res 16 --band 2 -q --png '" + dir +
          "/no/p.png'");
  EXPECT_EQ(r.code, 4) << r.err;
  for (const auto& name : list_dir(dir)) EXPECT_EQ(name.find("tmp"), std::string::npos) << name;
  // A scene of implicit kind keeps every tile: refused up front when they cannot fit, naming the
  // remedy. (A mesh file with a winding sign signs far tiles by proof and skips them.)
  write_text(dir + "/open.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n");
  write_text(dir + "/open.json", R"({"type": "mesh", "path": "open.obj", "sign": "fast-winding"})");
  r = run("sdf '" + dir + "/open.json' -o '" + dir + "/o.npz' --res 20000 20000 100 --band 2");
  EXPECT_EQ(r.code, 5) << r.err;
  EXPECT_NE(r.err.find("implicit SDF (it keeps every tile)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("\"sign\": \"pseudonormal\""), std::string::npos) << r.err;
}
