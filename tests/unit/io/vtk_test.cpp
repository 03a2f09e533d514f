// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include <gtest/gtest.h>

#include <string>

#include "ebgeom/io/vtk.hpp"
#include "io_test_util.hpp"
#include "test_support.hpp"

using namespace ebgeom;
using test::Bytes;

namespace {
template <class T> class VtkTest : public ::testing::Test {};
TYPED_TEST_SUITE(VtkTest, test::FloatTypes);

const std::string head = "# vtk DataFile Version 3.0\ntet\nASCII\nDATASET POLYDATA\n";
const std::string points = "POINTS 4 float\n0 0 0 1 0 0\n0 1 0 0 0 1\n";
const std::string polys = "POLYGONS 4 16\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n";

// The tetrahedron as a BINARY legacy file (big-endian), points as `ty` ("float" or "double").
std::string binary_tet(const std::string& ty, bool v51) {
  const auto tet = test::tetrahedron<double>();
  Bytes b;
  b.e = io::Endian::big;
  b.text("# vtk DataFile Version 5.1\ntet\nBINARY\nDATASET POLYDATA\nPOINTS 4 " + ty + "\n");
  for (const auto& v : tet.vertices)
    for (double c : {v.x, v.y, v.z}) ty == "float" ? (void)b.put(float(c)) : (void)b.put(c);
  b.text("\nVERTICES 1 2\n").put(std::int32_t(1)).put(std::int32_t(0));
  if (v51) {
    b.text("\nPOLYGONS 5 12\nOFFSETS vtktypeint64\n");
    for (std::int64_t o : {0, 3, 6, 9, 12}) b.put(o);
    b.text("\nCONNECTIVITY vtktypeint64\n");
    for (Index i : tet.indices) b.put(std::int64_t(i));
  } else {
    b.text("\nPOLYGONS 4 16\n");
    for (std::size_t f = 0; f < 4; ++f) {
      b.put(std::int32_t(3));
      for (Index i : tet.face(f)) b.put(std::int32_t(i));
    }
  }
  b.text("\nCELL_DATA 4\nSCALARS s float 1\nLOOKUP_TABLE default\n");
  return b.s;
}
} // namespace

TYPED_TEST(VtkTest, AsciiPolygons) {
  using T = TypeParam;
  auto r = io::parse_vtk<T>(head + points + polys + "POINT_DATA 4\nSCALARS d float\n", {});
  ASSERT_TRUE(r.has_value()) << r.error().what();
  EXPECT_EQ(*r, test::tetrahedron<T>());
}

TYPED_TEST(VtkTest, AsciiSkipsFieldMetadataVerticesAndLines) {
  using T = TypeParam;
  const std::string text =
      head + "FIELD FieldData 2\nTIME 1 1 double\n0.5\nNAMES 2 1 int\n1 2\n" + points +
      "METADATA\nINFORMATION 0\n\nVERTICES 2 4\n1 0\n1 1\nLINES 1 3\n2 0 1\n" + polys;
  auto r = io::parse_vtk<T>(text, {});
  ASSERT_TRUE(r.has_value()) << r.error().what();
  EXPECT_EQ(*r, test::tetrahedron<T>());
}

TYPED_TEST(VtkTest, Vtk51OffsetsConnectivityAscii) {
  using T = TypeParam;
  const std::string text =
      head + points +
      "POLYGONS 5 12\nOFFSETS vtktypeint64\n0 3 6 9 12\nCONNECTIVITY vtktypeint64\n"
      "0 2 1 0 1 3 1 2 3 0 3 2\n";
  auto r = io::parse_vtk<T>(text, {});
  ASSERT_TRUE(r.has_value()) << r.error().what();
  EXPECT_EQ(*r, test::tetrahedron<T>());
  auto bad =
      io::parse_vtk<T>(head + points +
                           "POLYGONS 3 6\nOFFSETS vtktypeint64\n0 4 3\nCONNECTIVITY vtktypeint64\n"
                           "0 1 2 0 1 3\n",
                       {});
  ASSERT_FALSE(bad.has_value());
  EXPECT_EQ(bad.error().code, ErrorCode::size_mismatch);
  EXPECT_EQ(bad.error().line, 10u);
}

TYPED_TEST(VtkTest, BinaryBigEndianBothForms) {
  using T = TypeParam;
  for (const char* ty : {"float", "double"})
    for (bool v51 : {false, true}) {
      auto r = io::parse_vtk<T>(binary_tet(ty, v51), {});
      ASSERT_TRUE(r.has_value()) << ty << v51 << ": " << r.error().what();
      EXPECT_EQ(*r, test::tetrahedron<T>());
    }
  // A bad index in binary data reports its byte offset.
  std::string s = binary_tet("float", false);
  const std::size_t last = s.find("\nCELL_DATA") - 4;
  s[last + 3] = 9;
  auto r = io::parse_vtk<T>(s, {});
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::bad_index);
  EXPECT_EQ(r.error().line, 0u);
  EXPECT_EQ(r.error().byte_offset, last);
}

TYPED_TEST(VtkTest, TriangleStrips) {
  using T = TypeParam;
  // 3 4 5 over 0 1 2; strip 0 1 3 4 -> (0 1 3), (3 1 4) both facing +z
  const std::string text = head + "POINTS 6 double\n0 0 0 1 0 0 2 0 0 0 1 0 1 1 0 2 1 0\n"
                                  "TRIANGLE_STRIPS 2 9\n4 0 1 3 4\n3 1 2 4\n";
  auto r = io::parse_vtk<T>(text, {});
  ASSERT_TRUE(r.has_value()) << r.error().what();
  PolygonSoup<T> expect;
  expect.vertices = r->vertices;
  expect.add_triangle(0, 1, 3);
  expect.add_triangle(3, 1, 4);
  expect.add_triangle(1, 2, 4);
  EXPECT_EQ(*r, expect);
}

TYPED_TEST(VtkTest, Errors) {
  using T = TypeParam;
  struct Case {
    std::string text;
    ErrorCode code;
    std::uint64_t line;
  };
  const std::string ph = head + points;
  const Case cases[] = {
      {"# vtk DataFile Version 3.0\nx\nASCII\nDATASET UNSTRUCTURED_GRID\n", ErrorCode::unsupported,
       4},
      {"# vtk DataFile Version 3.0\nx\nASCII\nDATASET STRUCTURED_POINTS\n", ErrorCode::unsupported,
       4},
      {"# vtk DataFile Version 3.0\nx\nUTF8\n", ErrorCode::syntax, 3},
      {"# vtk DataFile Version 3.0\n", ErrorCode::truncated, 2},
      {"# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 2 bit\n",
       ErrorCode::unsupported, 5},
      {head + "POINTS 4 float\n0 0 0 1 0 0\n0 1 0 0 0\n", ErrorCode::truncated, 8},
      {head + "POINTS 1 float\n0 nan 0\n", ErrorCode::non_finite, 6},
      {ph + "POLYGONS 1 3\n2 0 1\n", ErrorCode::degenerate, 9},
      {ph + "POLYGONS 1 4\n3 0 1 4\n", ErrorCode::bad_index, 9},
      {ph + "POLYGONS 1 4\n3 0 1 -1\n", ErrorCode::bad_index, 9},
      {ph + "POLYGONS 1 4\n5 0 1 2 3 0\n", ErrorCode::size_mismatch, 9},
      {ph + "POLYGONS 5 4\n3 0 1 2\n", ErrorCode::size_mismatch, 8},
      {ph + "POLYGONS 1 4000000000\n3 0 1 2\n", ErrorCode::size_mismatch, 8},
      {ph + "POLYGONS 1 4\n3 0 1\n", ErrorCode::truncated, 10},
      {ph, ErrorCode::empty, 0},
      {ph + points, ErrorCode::syntax, 8},
  };
  for (const Case& c : cases) {
    auto r = io::parse_vtk<T>(c.text, {});
    ASSERT_FALSE(r.has_value()) << c.text;
    EXPECT_EQ(r.error().code, c.code) << c.text << "\n" << r.error().what();
    if (c.line) {
      EXPECT_EQ(r.error().line, c.line) << c.text << "\n" << r.error().what();
    }
  }
}
