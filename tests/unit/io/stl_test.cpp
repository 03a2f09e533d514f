// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "ebgeom/io/stl.hpp"
#include "io_test_util.hpp"
#include "test_support.hpp"

using namespace ebgeom;
using test::Bytes;

namespace {

template <class T> class StlTest : public ::testing::Test {};
TYPED_TEST_SUITE(StlTest, test::FloatTypes);

// A binary STL of the soup's triangles (normals zero), header `header`.
template <class T> std::string binary_stl(const PolygonSoup<T>& s, const std::string& header) {
  Bytes b;
  std::string h = header;
  h.resize(80, ' ');
  b.text(h).put(std::uint32_t(s.face_count()));
  for (std::size_t f = 0; f < s.face_count(); ++f) {
    b.put(0.f).put(0.f).put(0.f);
    for (Index i : s.face(f))
      b.put(float(s.vertices[i].x)).put(float(s.vertices[i].y)).put(float(s.vertices[i].z));
    b.put(std::uint16_t(0));
  }
  return b.s;
}

template <class T> std::string ascii_stl(const PolygonSoup<T>& s, const std::string& name) {
  std::string out = "solid " + name + "\n";
  for (std::size_t f = 0; f < s.face_count(); ++f) {
    out += "facet normal 0 0 0\nouter loop\n";
    for (Index i : s.face(f))
      out += "vertex " + std::to_string(s.vertices[i].x) + " " + std::to_string(s.vertices[i].y) +
             " " + std::to_string(s.vertices[i].z) + "\n";
    out += "endloop\nendfacet\n";
  }
  return out + "endsolid " + name + "\n";
}

} // namespace

TYPED_TEST(StlTest, BinaryWeldsExactDuplicates) {
  using T = TypeParam;
  const auto tet = test::tetrahedron<T>();
  const std::string bytes = binary_stl(tet, "binary");
  EXPECT_TRUE(io::is_binary_stl(bytes));
  auto r = io::parse_stl<T>(bytes, {});
  ASSERT_TRUE(r.has_value()) << r.error().what();
  EXPECT_TRUE(test::same_mesh(*r, tet));
  // The first vertex met is numbered first: the weld keeps first-appearance order.
  EXPECT_EQ(r->vertices[0], tet.vertices[0]);
  EXPECT_EQ(r->face(0)[0], 0u);
}

TYPED_TEST(StlTest, KeepModeGivesThreeVerticesPerTriangle) {
  using T = TypeParam;
  const auto tet = test::tetrahedron<T>();
  io::ReadOptions opt;
  opt.stl_vertices = io::StlVertices::keep;
  auto r = io::parse_stl<T>(binary_stl(tet, "x"), opt);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->vertex_count(), 12u);
  EXPECT_EQ(test::canonical_triangles(*r), test::canonical_triangles(tet));
}

TYPED_TEST(StlTest, NegativeZeroWeldsWithZero) {
  using T = TypeParam;
  PolygonSoup<T> s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-0.0, 0, 0}, {0, 0, 1}};
  s.add_triangle(0, 1, 2);
  s.add_triangle(3, 1, 4);
  auto r = io::parse_stl<T>(binary_stl(s, "z"), {});
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->vertex_count(), 4u);
  EXPECT_FALSE(std::signbit(r->vertices[0].x));
}

TYPED_TEST(StlTest, BinaryWhoseHeaderStartsWithSolid) {
  using T = TypeParam;
  const auto tet = test::tetrahedron<T>();
  const std::string bytes = binary_stl(tet, "solid exported by a CAD tool");
  EXPECT_TRUE(io::is_binary_stl(bytes));
  auto r = io::parse_stl<T>(bytes, {});
  ASSERT_TRUE(r.has_value()) << r.error().what();
  EXPECT_TRUE(test::same_mesh(*r, tet));
}

TYPED_TEST(StlTest, TrailingBytesAreToleratedUnlessHeaderSaysSolid) {
  using T = TypeParam;
  const auto tet = test::tetrahedron<T>();
  auto r = io::parse_stl<T>(binary_stl(tet, "binary") + std::string(13, '\0'), {});
  ASSERT_TRUE(r.has_value()) << r.error().what();
  EXPECT_TRUE(test::same_mesh(*r, tet));
  // "solid" + wrong size: taken as ASCII, which then fails on the binary bytes.
  auto a = io::parse_stl<T>(binary_stl(tet, "solid x") + "junk", {});
  ASSERT_FALSE(a.has_value());
  EXPECT_GT(a.error().line, 0u);
}

TYPED_TEST(StlTest, LyingCountIsRejectedBeforeAllocating) {
  using T = TypeParam;
  Bytes b;
  b.text(std::string(80, ' ')).put(std::uint32_t(1) << 31).text(std::string(1000, '\0'));
  auto r = io::parse_stl<T>(b.s, {});
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::size_mismatch);
  EXPECT_EQ(r.error().byte_offset, 80u);
  // Below the triangle cap the same file still fails on size, not on memory.
  io::ReadOptions big;
  big.max_triangles = std::uint64_t(1) << 32;
  auto r2 = io::parse_stl<T>(b.s, big);
  ASSERT_FALSE(r2.has_value());
  EXPECT_EQ(r2.error().code, ErrorCode::size_mismatch);
  EXPECT_NE(r2.error().what().find("1000 bytes follow"), std::string::npos) << r2.error().what();
}

TYPED_TEST(StlTest, MaxTrianglesIsEnforced) {
  using T = TypeParam;
  io::ReadOptions opt;
  opt.max_triangles = 3;
  const auto tet = test::tetrahedron<T>();
  auto b = io::parse_stl<T>(binary_stl(tet, "b"), opt);
  ASSERT_FALSE(b.has_value());
  EXPECT_EQ(b.error().code, ErrorCode::size_mismatch);
  auto a = io::parse_stl<T>(ascii_stl(tet, "a"), opt);
  ASSERT_FALSE(a.has_value());
  EXPECT_EQ(a.error().code, ErrorCode::size_mismatch);
}

TYPED_TEST(StlTest, BinaryTruncatedAndNonFinite) {
  using T = TypeParam;
  const auto tet = test::tetrahedron<T>();
  const std::string good = binary_stl(tet, "b");
  auto cut = io::parse_stl_binary<T>(good.substr(0, good.size() - 1), {});
  ASSERT_FALSE(cut.has_value());
  EXPECT_EQ(cut.error().code, ErrorCode::size_mismatch);
  auto tiny = io::parse_stl_binary<T>(good.substr(0, 83), {});
  ASSERT_FALSE(tiny.has_value());
  EXPECT_EQ(tiny.error().code, ErrorCode::truncated);
  EXPECT_EQ(tiny.error().byte_offset, 83u);
  for (float bad :
       {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    std::string s = good;
    const std::size_t off = 84 + 2 * 50 + 12 + 3 * 4 + 8; // triangle 2, vertex 1, z
    std::memcpy(&s[off], &bad, 4);
    auto r = io::parse_stl<T>(s, {});
    ASSERT_FALSE(r.has_value());
    EXPECT_EQ(r.error().code, ErrorCode::non_finite);
    EXPECT_EQ(r.error().byte_offset, off - 8);
  }
  // A NaN normal is fine (normals are ignored).
  std::string s = good;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&s[84], &nan, 4);
  EXPECT_TRUE(io::parse_stl<T>(s, {}).has_value());
}

TYPED_TEST(StlTest, AsciiMultipleSolidsCrlfAndNames) {
  using T = TypeParam;
  const auto tet = test::tetrahedron<T>();
  PolygonSoup<T> first = tet, second = tet;
  first.offsets.resize(3); // faces 0, 1
  first.indices.resize(6);
  second.offsets = {0, 3, 6}; // faces 2, 3
  second.indices.assign(tet.indices.begin() + 6, tet.indices.end());
  std::string text = ascii_stl(first, "part one") + "\n\n" + ascii_stl(second, "two");
  for (const bool crlf : {false, true}) {
    std::string t = text;
    if (crlf) {
      std::string c;
      for (char ch : t) c += ch == '\n' ? std::string("\r\n") : std::string(1, ch);
      t = c;
    }
    auto r = io::parse_stl<T>(t, {});
    ASSERT_TRUE(r.has_value()) << r.error().what();
    EXPECT_TRUE(test::same_mesh(*r, tet));
  }
}

TYPED_TEST(StlTest, AsciiUppercaseKeywordsAndPolygonFacets) {
  using T = TypeParam;
  const std::string t = "SOLID q\nFACET NORMAL 0 0 1\nOUTER LOOP\nVERTEX 0 0 0\nVERTEX 1 0 0\n"
                        "VERTEX 1 1 0\nVERTEX 0 1 0\nENDLOOP\nENDFACET\nENDSOLID\n";
  auto r = io::parse_stl<T>(t, {});
  ASSERT_TRUE(r.has_value()) << r.error().what();
  EXPECT_EQ(r->face_count(), 1u);
  EXPECT_EQ(r->face_size(0), 4u);
  EXPECT_EQ(r->vertex_count(), 4u);
}

TYPED_TEST(StlTest, AsciiErrorsCarryLines) {
  using T = TypeParam;
  io::ReadOptions opt;
  opt.path = "part.stl";
  auto r =
      io::parse_stl<T>("solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0\n", opt);
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::truncated);
  EXPECT_EQ(r.error().line, 6u);
  EXPECT_EQ(r.error().what().rfind("part.stl: line 6: ", 0), 0u) << r.error().what();
  auto s = io::parse_stl<T>("solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 x\n",
                            opt);
  ASSERT_FALSE(s.has_value());
  EXPECT_EQ(s.error().code, ErrorCode::bad_number);
  EXPECT_EQ(s.error().line, 5u);
  auto e = io::parse_stl<T>("solid a\nendsolid a\n", opt);
  ASSERT_FALSE(e.has_value());
  EXPECT_EQ(e.error().code, ErrorCode::empty);
  auto z = io::parse_stl<T>("", opt);
  ASSERT_FALSE(z.has_value());
  EXPECT_EQ(z.error().code, ErrorCode::empty);
}
