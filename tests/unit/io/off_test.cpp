// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>

#include "ebgeom/io/off.hpp"
#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/io/write_mesh.hpp"
#include "io_test_util.hpp"
#include "test_support.hpp"

using namespace ebgeom;

namespace {
template <class T> class OffTest : public ::testing::Test {};
TYPED_TEST_SUITE(OffTest, test::FloatTypes);

const char* const tet_off =
    "OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n";

/// Binary OFF built by hand (big-endian), independent of the reader.
std::string binary_off(const std::vector<std::array<float, 3>>& v,
                       const std::vector<std::vector<std::int32_t>>& f) {
  std::string out = "OFF BINARY\n";
  io::detail::store(out, std::int32_t(v.size()), io::Endian::big);
  io::detail::store(out, std::int32_t(f.size()), io::Endian::big);
  io::detail::store(out, std::int32_t(0), io::Endian::big);
  for (const auto& p : v)
    for (float c : p) io::detail::store(out, c, io::Endian::big);
  for (const auto& face : f) {
    io::detail::store(out, std::int32_t(face.size()), io::Endian::big);
    for (std::int32_t i : face) io::detail::store(out, i, io::Endian::big);
    io::detail::store(out, std::int32_t(0), io::Endian::big);
  }
  return out;
}
} // namespace

TYPED_TEST(OffTest, PlainTetrahedron) {
  using T = TypeParam;
  auto r = io::parse_off<T>(tet_off, {});
  ASSERT_TRUE(r.has_value()) << r.error().what();
  EXPECT_EQ(*r, test::tetrahedron<T>());
}

TYPED_TEST(OffTest, DetectedByContentWhateverTheExtension) {
  using T = TypeParam;
  EXPECT_EQ(io::detect_format(tet_off, "x.stl"), io::MeshFormat::off);
  EXPECT_EQ(io::detect_format("# made by hand\nCOFF\n", "x.obj"), io::MeshFormat::off);
  EXPECT_EQ(io::detect_format("OFF BINARY\n", ""), io::MeshFormat::off);
  EXPECT_EQ(io::detect_format("OFFSET 1\n", ""), io::MeshFormat::unknown);
  EXPECT_EQ(io::detect_format("something\n", "a.OFF"), io::MeshFormat::off);
  io::ReadOptions opt;
  opt.path = "tet.stl";
  auto r = io::parse_mesh<T>(tet_off, opt);
  ASSERT_TRUE(r.has_value()) << r.error().what();
  EXPECT_EQ(*r, test::tetrahedron<T>());
}

TYPED_TEST(OffTest, PolygonsAreKept) {
  using T = TypeParam;
  auto r = io::parse_off<T>("OFF\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n"
                            "4 0 1 2 3\n5 0 1 2 3 4\n",
                            {});
  ASSERT_TRUE(r.has_value()) << r.error().what();
  EXPECT_EQ(r->face_count(), 2u);
  EXPECT_EQ(r->face_size(0), 4u);
  EXPECT_EQ(r->face_size(1), 5u);
  EXPECT_EQ(r->triangle_count(), 5u);
}

TYPED_TEST(OffTest, BinaryMatchesAscii) {
  using T = TypeParam;
  const std::string bin = binary_off({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
                                     {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}});
  auto r = io::parse_mesh<T>(bin, {});
  ASSERT_TRUE(r.has_value()) << r.error().what();
  EXPECT_EQ(*r, test::tetrahedron<T>());
}

TYPED_TEST(OffTest, LimitsAreCheckedBeforeAllocating) {
  using T = TypeParam;
  io::ReadOptions opt;
  opt.max_triangles = 3;
  auto r = io::parse_off<T>(tet_off, opt);
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::size_mismatch);
  EXPECT_EQ(r.error().line, 2u);
  // a polygon face counts as its fan triangles
  opt.max_triangles = 4;
  auto q = io::parse_off<T>("OFF\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n"
                            "4 0 1 2 3\n5 0 1 2 3 4\n",
                            opt);
  ASSERT_FALSE(q.has_value());
  EXPECT_EQ(q.error().code, ErrorCode::size_mismatch);
  EXPECT_EQ(q.error().line, 9u);
}

// Random polygon meshes written by the OFF writer read back exactly (shortest round-trip text).
TYPED_TEST(OffTest, WriterRoundTripsExactly) {
  using T = TypeParam;
  std::mt19937 rng(7);
  std::uniform_real_distribution<T> u(T(-1e6), T(1e6));
  PolygonSoup<T> soup;
  for (int i = 0; i < 200; ++i) soup.add_vertex(Vec3<T>{u(rng), u(rng), u(rng) * T(1e-9)});
  std::uniform_int_distribution<int> vi(0, 199), sz(3, 7);
  for (int f = 0; f < 100; ++f) {
    std::vector<Index> c(std::size_t(sz(rng)));
    for (Index& i : c) i = Index(vi(rng));
    soup.add_face(c);
  }
  io::WriteOptions w;
  w.format = io::MeshFormat::off;
  w.encoding = io::Encoding::binary; // OFF is written as text whatever is asked
  auto bytes = io::encode_mesh(soup, w);
  ASSERT_TRUE(bytes.has_value()) << bytes.error().what();
  EXPECT_EQ(bytes->rfind("OFF\n", 0), 0u);
  EXPECT_EQ(io::effective_encoding(io::MeshFormat::off, io::Encoding::binary), io::Encoding::ascii);
  EXPECT_EQ(io::effective_encoding(io::MeshFormat::ply, io::Encoding::binary),
            io::Encoding::binary);
  auto back = io::parse_mesh<T>(*bytes, {});
  ASSERT_TRUE(back.has_value()) << back.error().what();
  EXPECT_EQ(*back, soup);
}

// STL stores float: a double mesh whose coordinates float cannot hold is refused (it would
// become a file of infinities), while double-precision formats keep it.
TEST(WriteMesh, StlRefusesCoordinatesOutsideFloat) {
  PolygonSoup<double> soup = test::tetrahedron<double>();
  soup.vertices[2].y = 1e300;
  io::WriteOptions w;
  w.format = io::MeshFormat::stl;
  auto r = io::encode_mesh(soup, w);
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::invalid_argument);
  EXPECT_NE(r.error().what().find("vertex 2"), std::string::npos) << r.error().what();
  for (io::MeshFormat f :
       {io::MeshFormat::ply, io::MeshFormat::obj, io::MeshFormat::off, io::MeshFormat::vtk}) {
    w.format = f;
    auto ok = io::encode_mesh(soup, w);
    ASSERT_TRUE(ok.has_value()) << io::to_string(f);
    auto back = io::parse_mesh<double>(*ok, {});
    ASSERT_TRUE(back.has_value()) << io::to_string(f) << ": " << back.error().what();
    EXPECT_EQ(back->vertices[2].y, 1e300) << io::to_string(f);
  }
  // large but representable coordinates keep finite normals (computed in double)
  soup.vertices[2].y = 1e30;
  w.format = io::MeshFormat::stl;
  auto big = io::encode_mesh(soup, w);
  ASSERT_TRUE(big.has_value());
  for (std::size_t t = 0; t < 4; ++t)
    for (int k = 0; k < 3; ++k) {
      const float n =
          io::detail::load<float>(big->data() + 84 + 50 * t + 4 * k, io::Endian::little);
      EXPECT_TRUE(std::isfinite(n)) << "triangle " << t;
    }
}
