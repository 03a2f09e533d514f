// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// The .npz writers of the jobs component, read back with the tests' own ZIP and .npy reader
// (zip_reader.hpp, written from the ZIP specification, CRCs recomputed with zlib): the archive
// writer with and without ZIP64 records, the dense grid against the library's `sample_grid` bit for
// bit, and the sparse band against the dense band-clamped grid sample for sample.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "ebgeom/eval/grid.hpp"
#include "ebgeom/eval/sparse_grid.hpp"
#include "ebgeom/jobs/npz.hpp"
#include "ebgeom/sdf/shapes.hpp"
#include "zip_reader.hpp"

using namespace ebgeom;
using namespace ebgeom::clitest;

namespace {

/// A fresh folder for this test's files (named by test and process).
std::string test_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path d =
      std::filesystem::temp_directory_path() /
      ("ebgeom-jobs-" + std::string(info->name()) + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d.string();
}

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

std::map<std::string, NpyArray> read_npz(const std::string& path) {
  return read_npz_bytes(slurp(path), path);
}

/// numpy's 'U' text of the host's byte order, back to ASCII.
std::string unicode_text(const NpyArray& a) {
  std::string s;
  for (std::size_t i = 0; i + 4 <= a.data.size(); i += 4) {
    std::uint32_t c;
    std::memcpy(&c, a.data.data() + i, 4);
    s += char(c);
  }
  return s;
}

template <class T> GridSpec<T> test_spec(Centering c) {
  GridSpec<T> s;
  s.box = Aabb<T>({T(-1.1), T(-0.9), T(-1.3)}, {T(1.2), T(1.0), T(0.8)});
  s.dims = {{19, 13, 21}}; // partial tiles on every axis
  s.centering = c;
  return s;
}

} // namespace

TEST(NpzWriter, Zip64RecordsAreReadBack) {
  const std::string dir = test_dir();
  const std::vector<float> a = {1.5f, -2.f, 3.25f, 0.f, 7.f, -9.5f};
  const std::vector<std::int32_t> b = {-1, 0, 5};
  const std::vector<jobs::NpzMember> members = {
      {"a", npy_header("<f4", {2, 3}), a.data(), a.size() * 4},
      {"b", npy_header("<i4", {3}), b.data(), b.size() * 4},
      {"empty", npy_header("<f8", {0}), nullptr, 0},
  };
  for (jobs::Zip64 mode : {jobs::Zip64::as_needed, jobs::Zip64::always}) {
    const std::string path = dir + "/t.npz";
    jobs::NpzOptions opt;
    opt.zip64 = mode;
    auto ok = jobs::write_npz(path, members, opt);
    ASSERT_TRUE(ok) << ok.error().what();
    const std::string bytes = slurp(path);
    EXPECT_EQ(*ok, bytes.size());
    const Zip z = read_zip(bytes);
    ASSERT_TRUE(z.ok);
    EXPECT_EQ(z.order, (std::vector<std::string>{"a.npy", "b.npy", "empty.npy"}));
    EXPECT_EQ(z.zip64_end, mode == jobs::Zip64::always);
    for (const auto& [name, e] : z.entries) EXPECT_EQ(e.zip64, mode == jobs::Zip64::always) << name;
    const NpyArray pa = parse_npy(z.entries.at("a.npy").data, "a");
    EXPECT_EQ(pa.shape, (std::vector<std::size_t>{2, 3}));
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(pa.at<float>(i), a[i]);
    const NpyArray pb = parse_npy(z.entries.at("b.npy").data, "b");
    for (std::size_t i = 0; i < b.size(); ++i) EXPECT_EQ(pb.at<std::int32_t>(i), b[i]);
    EXPECT_TRUE(parse_npy(z.entries.at("empty.npy").data, "empty").data.empty());
  }
  auto bad = jobs::write_npz(dir + "/missing/t.npz", members);
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().code, ErrorCode::io);
}

template <class T> void dense_round_trip(Centering c) {
  const std::string dir = test_dir();
  const Sphere<T> sphere{{T(0.1), T(-0.05), T(0.02)}, T(0.7)};
  const GridSpec<T> spec = test_spec<T>(c);
  std::vector<T> values(spec.size());
  ASSERT_TRUE(sample_grid(sphere, spec, Span<T>(values)));
  const std::string path = dir + "/dense.npz";
  auto ok = jobs::write_dense_npz(path, spec, Span<const T>(values));
  ASSERT_TRUE(ok) << ok.error().what();
  EXPECT_EQ(*ok, std::filesystem::file_size(path));
  auto m = read_npz(path);
  ASSERT_EQ(m.size(), 5u);
  const NpyArray& sdf = m["sdf"];
  EXPECT_EQ(sdf.descr, sizeof(T) == 4 ? "<f4" : "<f8");
  EXPECT_EQ(sdf.shape, (std::vector<std::size_t>{spec.nz(), spec.ny(), spec.nx()}));
  ASSERT_EQ(sdf.count(), values.size());
  for (std::size_t i = 0; i < values.size(); ++i) ASSERT_EQ(sdf.at<T>(i), values[i]) << i;
  const Vec3<T> o = spec.origin(), h = spec.spacing();
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(m["origin"].at<double>(a), double(o[a]));
    EXPECT_EQ(m["spacing"].at<double>(a), double(h[a]));
    EXPECT_EQ(m["box"].at<double>(a), double(spec.box.lo[a]));
    EXPECT_EQ(m["box"].at<double>(3 + a), double(spec.box.hi[a]));
  }
  EXPECT_EQ(unicode_text(m["centering"]), c == Centering::cell ? "cell" : "node");
  // equal grids give equal files (fixed timestamps)
  ASSERT_TRUE(jobs::write_dense_npz(dir + "/again.npz", spec, Span<const T>(values)));
  EXPECT_EQ(slurp(dir + "/again.npz"), slurp(path));
}

TEST(NpzWriter, DenseGridIsTheSampledGrid) {
  dense_round_trip<float>(Centering::cell);
  dense_round_trip<double>(Centering::node);
}

template <class T> void sparse_round_trip(Centering c) {
  const std::string dir = test_dir();
  const Sphere<T> sphere{{T(0.1), T(-0.05), T(0.02)}, T(0.7)};
  const GridSpec<T> spec = test_spec<T>(c);
  GridOptions opt;
  opt.band = 2 * double(max_component(spec.spacing()));
  auto g = sample_grid_sparse(sphere, spec, opt);
  ASSERT_TRUE(g) << g.error().what();
  // the reference: the dense grid clamped to the band
  opt.outside = BandFill::clamp;
  std::vector<T> dense(spec.size());
  ASSERT_TRUE(sample_grid(sphere, spec, Span<T>(dense), opt));
  const std::string path = dir + "/band.npz";
  auto ok = jobs::write_sparse_npz(path, *g);
  ASSERT_TRUE(ok) << ok.error().what();
  auto m = read_npz(path);
  const std::size_t W = grid_tile;
  const std::size_t tx = (spec.nx() + W - 1) / W, ty = (spec.ny() + W - 1) / W,
                    tz = (spec.nz() + W - 1) / W;
  const NpyArray& code = m["tile_code"];
  EXPECT_EQ(code.shape, (std::vector<std::size_t>{tz, ty, tx}));
  const NpyArray& vals = m["values"];
  const T band = m["band"].at<T>(0);
  EXPECT_EQ(double(band), double(g->band));
  EXPECT_EQ(m["tile"].at<std::int64_t>(0), std::int64_t(W));
  for (int a = 0; a < 3; ++a) EXPECT_EQ(m["dims"].at<std::uint64_t>(a), spec.dims[a]);
  // The kept tiles' coordinates: member `tiles` (it was named `blocks` in 0.1).
  EXPECT_EQ(m.count("blocks"), 0u);
  ASSERT_EQ(m.count("tiles"), 1u);
  const NpyArray& tiles = m["tiles"];
  ASSERT_EQ(tiles.shape, (std::vector<std::size_t>{g->kept_tile_count(), 3}));
  for (std::size_t b = 0; b < g->kept_tile_count(); ++b)
    for (std::size_t a = 0; a < 3; ++a)
      ASSERT_EQ(tiles.at<std::uint32_t>(3 * b + a), g->kept_tiles[b][a]) << b;
  std::size_t kept = 0, skipped = 0;
  for (std::size_t k = 0; k < spec.nz(); ++k)
    for (std::size_t j = 0; j < spec.ny(); ++j)
      for (std::size_t i = 0; i < spec.nx(); ++i) {
        const std::int32_t t = code.at<std::int32_t>(i / W + tx * (j / W + ty * (k / W)));
        T v;
        if (t >= 0) {
          v = vals.at<T>(std::size_t(t) * W * W * W + i % W + W * (j % W + W * (k % W)));
          ++kept;
        } else {
          ASSERT_TRUE(t == -1 || t == -2) << t;
          v = t == -1 ? -band : band;
          ++skipped;
        }
        ASSERT_EQ(v, dense[i + spec.nx() * (j + spec.ny() * k)]) << i << " " << j << " " << k;
      }
  EXPECT_GT(kept, 0u);
  EXPECT_GT(skipped, 0u); // the band is narrow: some tiles are skipped
}

TEST(NpzWriter, SparseBandIsTheDenseBand) {
  sparse_round_trip<float>(Centering::cell);
  sparse_round_trip<double>(Centering::node);
}
