// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "ebgeom/eval/grid.hpp"
#include "ebgeom/eval/write_grid.hpp"
#include "test_shapes.hpp"
#include "test_support.hpp"

using namespace ebgeom;

namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::string temp_path(const std::string& name) {
  // The process id keeps concurrent runs (ctest -j, several build trees) apart.
  return ::testing::TempDir() + "ebgeom_wg_" + std::to_string(::getpid()) + "_" + name;
}

template <class T> struct Fixture {
  GridSpec<T> spec{Aabb<T>({T(-1), T(-2), T(0)}, {T(1), T(2), T(1)}), {{5, 7, 3}}, Centering::cell};
  std::vector<T> values;
  Fixture() {
    const test::Ball<T> b{{T(0), T(0), T(0.5)}, T(0.8)};
    values.resize(spec.size());
    for (std::size_t k = 0; k < spec.nz(); ++k)
      for (std::size_t j = 0; j < spec.ny(); ++j)
        for (std::size_t i = 0; i < spec.nx(); ++i)
          values[spec.index(i, j, k)] = b(spec.point(i, j, k));
  }
};

template <class D> std::vector<double> decode(const char* p, std::size_t n) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) {
    D d;
    std::memcpy(&d, p + i * sizeof(D), sizeof(D));
    v[i] = d;
  }
  return v;
}

} // namespace

template <class T> class WriteGridTest : public ::testing::Test {};
TYPED_TEST_SUITE(WriteGridTest, test::FloatTypes);

TYPED_TEST(WriteGridTest, NpyHeaderShapeAndValues) {
  using T = TypeParam;
  Fixture<T> f;
  for (DType dt : {DType::float32, DType::float64}) {
    const std::string path = temp_path("a.npy");
    WriteGridOptions opt;
    opt.dtype = dt;
    ASSERT_TRUE(write_npy(path, f.spec, Span<const T>(f.values), opt));
    const std::string bytes = slurp(path);
    ASSERT_GE(bytes.size(), 10u);
    EXPECT_EQ(bytes.substr(0, 6), std::string("\x93NUMPY"));
    EXPECT_EQ(bytes[6], 1);
    const std::size_t hlen =
        std::size_t(static_cast<unsigned char>(bytes[8])) | std::size_t(bytes[9]) << 8;
    EXPECT_EQ((10 + hlen) % 64, 0u);
    const std::string header = bytes.substr(10, hlen);
    EXPECT_NE(header.find(dt == DType::float32 ? "'descr': '<f4'" : "'descr': '<f8'"),
              std::string::npos)
        << header;
    EXPECT_NE(header.find("'fortran_order': False"), std::string::npos);
    EXPECT_NE(header.find("'shape': (3, 7, 5)"), std::string::npos) << header;
    EXPECT_EQ(header.back(), '\n');
    const std::size_t w = dt == DType::float32 ? 4 : 8;
    ASSERT_EQ(bytes.size(), 10 + hlen + f.values.size() * w);
    const auto v = dt == DType::float32 ? decode<float>(bytes.data() + 10 + hlen, f.values.size())
                                        : decode<double>(bytes.data() + 10 + hlen, f.values.size());
    for (std::size_t n = 0; n < v.size(); ++n) {
      if (dt == DType::float32)
        ASSERT_EQ(float(v[n]), float(f.values[n]));
      else
        ASSERT_EQ(v[n], double(f.values[n]));
    }
    std::remove(path.c_str());
  }
}

TEST(WriteNpy, OneDimensionalShapeHasTrailingComma) {
  const std::vector<double> v{1, 2, 3};
  const std::string path = temp_path("b.npy");
  ASSERT_TRUE(write_npy(path, Span<const double>(v), {3}, DType::float64));
  EXPECT_NE(slurp(path).find("'shape': (3,)"), std::string::npos);
  EXPECT_EQ(write_npy(path, Span<const double>(v), {2, 2}).error().code,
            ErrorCode::invalid_argument);
  std::remove(path.c_str());
}

TYPED_TEST(WriteGridTest, VtiHeaderAndAppendedData) {
  using T = TypeParam;
  Fixture<T> f;
  const std::string path = temp_path("a.vti");
  ASSERT_TRUE(write_grid(path, f.spec, Span<const T>(f.values)));
  const std::string bytes = slurp(path);
  EXPECT_NE(bytes.find("type=\"ImageData\""), std::string::npos);
  EXPECT_NE(bytes.find("WholeExtent=\"0 4 0 6 0 2\""), std::string::npos);
  // Origin = first cell centre, spacing = cell size.
  std::istringstream origin(bytes.substr(bytes.find("Origin=\"") + 8));
  double ox, oy, oz;
  origin >> ox >> oy >> oz;
  EXPECT_NEAR(ox, -0.8, 1e-6);
  EXPECT_NEAR(oy, -2 + 2.0 / 7, 1e-6);
  EXPECT_NEAR(oz, 1.0 / 6, 1e-6);
  std::istringstream spacing(bytes.substr(bytes.find("Spacing=\"") + 9));
  double hx, hy, hz;
  spacing >> hx >> hy >> hz;
  EXPECT_NEAR(hx, 0.4, 1e-6);
  EXPECT_NEAR(hy, 4.0 / 7, 1e-6);
  EXPECT_NEAR(hz, 1.0 / 3, 1e-6);
  EXPECT_NE(bytes.find("type=\"Float32\""), std::string::npos);
  const std::size_t us = bytes.find('_', bytes.find("<AppendedData"));
  ASSERT_NE(us, std::string::npos);
  std::uint64_t nbytes = 0;
  std::memcpy(&nbytes, bytes.data() + us + 1, 8);
  ASSERT_EQ(nbytes, f.values.size() * 4);
  const auto v = decode<float>(bytes.data() + us + 9, f.values.size());
  for (std::size_t n = 0; n < v.size(); ++n) ASSERT_EQ(float(v[n]), float(f.values[n]));
  EXPECT_NE(bytes.find("</VTKFile>", us + 9 + nbytes), std::string::npos);
  std::remove(path.c_str());
}

TYPED_TEST(WriteGridTest, RawWithJsonSidecar) {
  using T = TypeParam;
  Fixture<T> f;
  const std::string path = temp_path("grid.raw");
  WriteGridOptions opt;
  opt.dtype = DType::float64;
  ASSERT_TRUE(write_grid(path, f.spec, Span<const T>(f.values), opt));
  const std::string raw = slurp(path);
  ASSERT_EQ(raw.size(), f.values.size() * 8);
  const auto v = decode<double>(raw.data(), f.values.size());
  for (std::size_t n = 0; n < v.size(); ++n) ASSERT_EQ(v[n], double(f.values[n]));
  EXPECT_EQ(raw_sidecar_path(path), temp_path("grid.json"));
  const std::string raw_name = path.substr(path.find_last_of('/') + 1);
  const std::string js = slurp(temp_path("grid.json"));
  EXPECT_NE(js.find("\"dims\": [5, 7, 3]"), std::string::npos) << js;
  EXPECT_NE(js.find("\"dtype\": \"float64\""), std::string::npos);
  EXPECT_NE(js.find("\"file\": \"" + raw_name + "\""), std::string::npos) << js;
  EXPECT_NE(js.find("\"centering\": \"cell\""), std::string::npos);
  std::remove(path.c_str());
  std::remove(temp_path("grid.json").c_str());
}

TEST(WriteGrid, ErrorsLeaveNoFileBehind) {
  Fixture<double> f;
  EXPECT_EQ(write_grid("/nonexistent-dir/x.vti", f.spec, Span<const double>(f.values)).error().code,
            ErrorCode::io);
  EXPECT_EQ(write_grid(temp_path("x.txt"), f.spec, Span<const double>(f.values)).error().code,
            ErrorCode::unsupported);
  const std::string path = temp_path("short.npy");
  std::vector<double> few(3);
  EXPECT_EQ(write_grid(path, f.spec, Span<const double>(few)).error().code,
            ErrorCode::invalid_argument);
  EXPECT_FALSE(test::file_exists(path));
  EXPECT_FALSE(test::file_exists(path + ".ebgeom-tmp"));
  EXPECT_EQ(raw_sidecar_path("dir.v2/out"), "dir.v2/out.json");
}

TYPED_TEST(WriteGridTest, VtiPieceAndPvtiDescribeTheirPartOfTheGrid) {
  using T = TypeParam;
  Fixture<T> f;
  // The whole grid as one piece is the .vti byte for byte.
  const GridRange all = GridRange::all(f.spec);
  const std::string whole = temp_path("whole.vti"), piece = temp_path("piece.vti");
  ASSERT_TRUE(write_vti(whole, f.spec, Span<const T>(f.values)));
  ASSERT_TRUE(write_vti_piece(piece, f.spec, all, all, Span<const T>(f.values)));
  EXPECT_EQ(slurp(whole), slurp(piece));
  // Samples [1, 4) x [2, 7) x [0, 2), declared inside the whole grid.
  const GridRange r{{{1, 2, 0}}, {{4, 7, 2}}};
  std::vector<T> sub;
  for (std::size_t k = r.lo[2]; k < r.hi[2]; ++k)
    for (std::size_t j = r.lo[1]; j < r.hi[1]; ++j)
      for (std::size_t i = r.lo[0]; i < r.hi[0]; ++i)
        sub.push_back(f.values[f.spec.index(i, j, k)]);
  WriteGridOptions opt;
  opt.dtype = DType::float64;
  ASSERT_TRUE(write_vti_piece(piece, f.spec, all, r, Span<const T>(sub), opt));
  const std::string bytes = slurp(piece);
  EXPECT_NE(bytes.find("WholeExtent=\"0 4 0 6 0 2\""), std::string::npos) << bytes;
  EXPECT_NE(bytes.find("<Piece Extent=\"1 3 2 6 0 1\">"), std::string::npos) << bytes;
  EXPECT_EQ(bytes.substr(0, bytes.find("WholeExtent")),
            slurp(whole).substr(0, slurp(whole).find("WholeExtent")));
  const std::size_t us = bytes.find('_', bytes.find("<AppendedData"));
  const auto v = decode<double>(bytes.data() + us + 9, sub.size());
  for (std::size_t n = 0; n < v.size(); ++n) ASSERT_EQ(v[n], double(sub[n]));
  // A piece outside its whole extent, or with the wrong count, is refused and leaves nothing.
  std::remove(piece.c_str());
  EXPECT_EQ(write_vti_piece(piece, f.spec, r, all, Span<const T>(f.values)).error().code,
            ErrorCode::invalid_argument);
  EXPECT_EQ(write_vti_piece(piece, f.spec, all, r, Span<const T>(f.values)).error().code,
            ErrorCode::invalid_argument);
  EXPECT_FALSE(test::file_exists(piece));

  const std::string pvti = temp_path("all.pvti");
  ASSERT_TRUE(write_pvti(pvti, f.spec, {{r, "a_0.vti"}, {all, "a&1.vti"}}, opt));
  const std::string p = slurp(pvti);
  EXPECT_NE(p.find("<VTKFile type=\"PImageData\""), std::string::npos) << p;
  EXPECT_NE(p.find("<PImageData WholeExtent=\"0 4 0 6 0 2\" GhostLevel=\"0\" Origin=\""),
            std::string::npos)
      << p;
  EXPECT_NE(p.find("<PDataArray type=\"Float64\" Name=\"sdf\""), std::string::npos) << p;
  EXPECT_NE(p.find("<Piece Extent=\"1 3 2 6 0 1\" Source=\"a_0.vti\"/>"), std::string::npos) << p;
  EXPECT_NE(p.find("Source=\"a&amp;1.vti\"/>"), std::string::npos) << p;
  // Same origin and spacing text as the pieces.
  const auto attr = [](const std::string& s, const char* name) {
    const std::size_t a = s.find(name);
    return s.substr(a, s.find('"', s.find('"', a) + 1) - a);
  };
  EXPECT_EQ(attr(p, "Origin="), attr(bytes, "Origin="));
  EXPECT_EQ(attr(p, "Spacing="), attr(bytes, "Spacing="));
  for (const std::string& s : {whole, piece, pvti}) std::remove(s.c_str());
}

TEST(WriteNpy, HeaderForAnyDescrIsPaddedTo64Bytes) {
  const std::string h = npy_header("<u4", {7, 3});
  EXPECT_EQ(h.size() % 64, 0u);
  EXPECT_EQ(h.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
  EXPECT_NE(h.find("{'descr': '<u4', 'fortran_order': False, 'shape': (7, 3), }"),
            std::string::npos)
      << h;
  EXPECT_NE(npy_header("<f8", {}).find("'shape': ()"), std::string::npos);
  EXPECT_EQ(npy_descr(DType::float32), "<f4");
}
