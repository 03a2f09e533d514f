// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "ebgeom/io/ply.hpp"
#include "io_test_util.hpp"
#include "test_support.hpp"

using namespace ebgeom;
using test::Bytes;

namespace {

template <class T> class PlyTest : public ::testing::Test {};
TYPED_TEST_SUITE(PlyTest, test::FloatTypes);

const char* const all_types[] = {"char",  "uchar",  "short",   "ushort", "int",   "uint",
                                 "float", "double", "int8",    "uint8",  "int16", "uint16",
                                 "int32", "uint32", "float32", "float64"};

// Appends `v` stored as PLY type `ty`.
void put_as(Bytes& b, const std::string& ty, double v) {
  if (ty == "char" || ty == "int8")
    b.put(std::int8_t(v));
  else if (ty == "uchar" || ty == "uint8")
    b.put(std::uint8_t(v));
  else if (ty == "short" || ty == "int16")
    b.put(std::int16_t(v));
  else if (ty == "ushort" || ty == "uint16")
    b.put(std::uint16_t(v));
  else if (ty == "int" || ty == "int32")
    b.put(std::int32_t(v));
  else if (ty == "uint" || ty == "uint32")
    b.put(std::uint32_t(v));
  else if (ty == "float" || ty == "float32")
    b.put(float(v));
  else
    b.put(double(v));
}

bool is_int_type(const std::string& ty) {
  return ty.find("float") == std::string::npos && ty != "double";
}

struct PlySpec {
  std::string format = "ascii"; // or binary_little_endian / binary_big_endian
  std::string coord = "float";
  std::string count = "uchar";
  std::string index = "int";
  bool extras = false; // an extra property before x, a list in the vertices, and an extra element
};

// The tetrahedron as a PLY file described by `spec`.
std::string tet_ply(const PlySpec& sp) {
  const auto tet = test::tetrahedron<double>();
  Bytes b;
  b.e = sp.format == "binary_big_endian" ? io::Endian::big : io::Endian::little;
  const bool ascii = sp.format == "ascii";
  std::string h = "ply\nformat " + sp.format + " 1.0\ncomment test\n";
  if (sp.extras) h += "element material 2\nproperty list uchar float rgb\nproperty int id\n";
  h += "element vertex 4\n";
  if (sp.extras) h += "property uchar flag\n";
  h += "property " + sp.coord + " x\nproperty " + sp.coord + " y\nproperty " + sp.coord + " z\n";
  if (sp.extras) h += "property list ushort int16 neighbours\nproperty double quality\n";
  h += "element face 4\n";
  if (sp.extras) h += "property uint tag\n";
  h += "property list " + sp.count + " " + sp.index + " vertex_indices\n";
  if (sp.extras)
    h += "property list uchar float texcoord\nelement edge 1\nproperty int a\nproperty int b\n";
  h += "end_header\n";
  b.text(h);
  auto num = [&](const std::string& ty, double v) {
    if (ascii)
      b.text((is_int_type(ty) ? std::to_string((long long)v) : std::to_string(v)) + " ");
    else
      put_as(b, ty, v);
  };
  if (sp.extras) {
    for (int m = 0; m < 2; ++m) {
      num("uchar", 3);
      for (int k = 0; k < 3; ++k) num("float", 0.5);
      num("int", m);
      if (ascii) b.text("\n");
    }
  }
  for (const auto& v : tet.vertices) {
    if (sp.extras) num("uchar", 7);
    num(sp.coord, v.x);
    num(sp.coord, v.y);
    num(sp.coord, v.z);
    if (sp.extras) {
      num("ushort", 2);
      num("int16", -1);
      num("int16", 3);
      num("double", 0.25);
    }
    if (ascii) b.text("\n");
  }
  for (std::size_t f = 0; f < tet.face_count(); ++f) {
    if (sp.extras) num("uint", 99);
    num(sp.count, 3);
    for (Index i : tet.face(f)) num(sp.index, i);
    if (sp.extras) {
      num("uchar", 2);
      num("float", 0.1);
      num("float", 0.2);
    }
    if (ascii) b.text("\n");
  }
  if (sp.extras) {
    num("int", 0);
    num("int", 1);
  }
  return b.s;
}

const char* const formats[] = {"ascii", "binary_little_endian", "binary_big_endian"};

} // namespace

TYPED_TEST(PlyTest, EveryCoordinateTypeAndEncoding) {
  using T = TypeParam;
  const auto tet = test::tetrahedron<T>();
  for (const char* fmt : formats)
    for (const char* ty : all_types) {
      PlySpec sp;
      sp.format = fmt;
      sp.coord = ty;
      auto r = io::parse_ply<T>(tet_ply(sp), {});
      ASSERT_TRUE(r.has_value()) << fmt << " " << ty << ": " << r.error().what();
      EXPECT_EQ(*r, tet) << fmt << " " << ty;
    }
}

TYPED_TEST(PlyTest, EveryListCountAndIndexType) {
  using T = TypeParam;
  const auto tet = test::tetrahedron<T>();
  for (const char* fmt : formats)
    for (const char* ct : all_types)
      for (const char* it : all_types) {
        if (!is_int_type(ct)) continue; // list counts must be integers (checked below)
        if (!is_int_type(it)) continue;
        PlySpec sp;
        sp.format = fmt;
        sp.count = ct;
        sp.index = it;
        auto r = io::parse_ply<T>(tet_ply(sp), {});
        ASSERT_TRUE(r.has_value()) << fmt << " " << ct << " " << it << ": " << r.error().what();
        EXPECT_EQ(*r, tet);
      }
  PlySpec sp;
  sp.count = "float";
  auto r = io::parse_ply<T>(tet_ply(sp), {});
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::unsupported);
  sp.count = "uchar";
  sp.index = "float";
  auto r2 = io::parse_ply<T>(tet_ply(sp), {});
  ASSERT_FALSE(r2.has_value());
  EXPECT_EQ(r2.error().code, ErrorCode::unsupported);
}

TYPED_TEST(PlyTest, ExtraElementsAndPropertiesAreSkipped) {
  using T = TypeParam;
  const auto tet = test::tetrahedron<T>();
  for (const char* fmt : formats) {
    PlySpec sp;
    sp.format = fmt;
    sp.extras = true;
    auto r = io::parse_ply<T>(tet_ply(sp), {});
    ASSERT_TRUE(r.has_value()) << fmt << ": " << r.error().what();
    EXPECT_EQ(*r, tet) << fmt;
  }
}

TYPED_TEST(PlyTest, HeaderIsParsed) {
  PlySpec sp;
  sp.extras = true;
  sp.format = "binary_big_endian";
  const std::string bytes = tet_ply(sp);
  auto h = io::parse_ply_header(bytes, {});
  ASSERT_TRUE(h.has_value());
  EXPECT_EQ(h->encoding, io::PlyEncoding::binary_big_endian);
  ASSERT_EQ(h->elements.size(), 4u);
  EXPECT_EQ(h->elements[1].name, "vertex");
  EXPECT_EQ(h->elements[1].count, 4u);
  EXPECT_EQ(h->elements[1].properties.size(), 6u);
  EXPECT_TRUE(h->elements[2].properties[1].is_list());
  EXPECT_EQ(h->elements[2].properties[1].count_type, io::ScalarType::u8);
  EXPECT_EQ(bytes.substr(h->data_offset - 11, 11), "end_header\n");
}

TYPED_TEST(PlyTest, TriangleStripsWithRestartsAndAlternatingWinding) {
  using T = TypeParam;
  // A 2x3 grid of vertices; strip 0 1 3 2 4 5 ... spelled as two strips separated by -1, plus a
  // degenerate stitch (repeated index) that must be dropped.
  //   3 4 5
  //   0 1 2
  std::string head =
      "ply\nformat ascii 1.0\nelement vertex 6\nproperty double x\nproperty double y\n"
      "property double z\nelement tristrips 1\nproperty list int int vertex_indices\n"
      "end_header\n0 0 0\n1 0 0\n2 0 0\n0 1 0\n1 1 0\n2 1 0\n";
  auto r = io::parse_ply<T>(head + "9 0 1 3 4 -1 1 2 4 4 5\n", {});
  ASSERT_TRUE(r.has_value()) << r.error().what();
  // Strip 0 1 3 4: (0 1 3), (3 1 4). Strip 1 2 4 4 5: (1 2 4), (4 2 4) dropped, (4 4 5) dropped.
  PolygonSoup<T> expect;
  expect.vertices = r->vertices;
  expect.add_triangle(0, 1, 3);
  expect.add_triangle(3, 1, 4);
  expect.add_triangle(1, 2, 4);
  EXPECT_EQ(*r, expect);
  // All kept triangles face +z (consistent winding): the z of each normal is positive.
  for (std::size_t f = 0; f < r->face_count(); ++f) {
    const auto c = r->face(f);
    const auto n =
        cross(r->vertices[c[1]] - r->vertices[c[0]], r->vertices[c[2]] - r->vertices[c[0]]);
    EXPECT_GT(n.z, T(0));
  }
  auto bad = io::parse_ply<T>(head + "4 0 1 -2 4\n", {});
  ASSERT_FALSE(bad.has_value());
  EXPECT_EQ(bad.error().code, ErrorCode::bad_index);
  EXPECT_EQ(bad.error().line, 16u);
}

TYPED_TEST(PlyTest, LyingCountsFailBeforeAllocating) {
  using T = TypeParam;
  for (const char* fmt : formats) {
    PlySpec sp;
    sp.format = fmt;
    std::string s = tet_ply(sp);
    const std::string from = "element vertex 4", to = "element vertex 1000000000000";
    s.replace(s.find(from), from.size(), to);
    auto r = io::parse_ply<T>(s, {});
    ASSERT_FALSE(r.has_value()) << fmt;
    EXPECT_EQ(r.error().code, ErrorCode::size_mismatch) << r.error().what();
    EXPECT_EQ(r.error().line, 4u);
    std::string f = tet_ply(sp);
    const std::string ff = "element face 4", tf = "element face 4000000000";
    f.replace(f.find(ff), ff.size(), tf);
    auto r2 = io::parse_ply<T>(f, {});
    ASSERT_FALSE(r2.has_value());
    EXPECT_EQ(r2.error().code, ErrorCode::size_mismatch);
  }
}

TYPED_TEST(PlyTest, ElementsWithoutPropertiesAreSkippedWithoutALoop) {
  // Such an element holds no data, so the check of counts against the bytes left cannot bound it:
  // its entries must not be visited one by one (a fuzzer's 456-byte file declared 444,444,444,440).
  using T = TypeParam;
  const auto tet = test::tetrahedron<T>();
  for (const char* fmt : formats) {
    PlySpec sp;
    sp.format = fmt;
    std::string s = tet_ply(sp);
    s.insert(s.find("element vertex"), "element nothing 18000000000000000000\n");
    auto r = io::parse_ply<T>(s, {});
    ASSERT_TRUE(r.has_value()) << fmt << ": " << r.error().what();
    EXPECT_EQ(*r, tet) << fmt;
  }
}

TYPED_TEST(PlyTest, BinaryErrorsCarryOffsets) {
  using T = TypeParam;
  PlySpec sp;
  sp.format = "binary_little_endian";
  const std::string good = tet_ply(sp);
  const std::size_t data = good.find("end_header\n") + 11;
  // vertex 2's y (float) -> NaN
  std::string s = good;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&s[data + 2 * 12 + 4], &nan, 4);
  auto r = io::parse_ply<T>(s, {});
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::non_finite);
  EXPECT_EQ(r.error().byte_offset, data + 2 * 12 + 4);
  EXPECT_EQ(r.error().line, 0u);
  // face 1's count -> 2
  std::string d = good;
  d[data + 48 + 13] = 2;
  auto r2 = io::parse_ply<T>(d, {});
  ASSERT_FALSE(r2.has_value());
  EXPECT_EQ(r2.error().code, ErrorCode::degenerate);
  EXPECT_EQ(r2.error().byte_offset, data + 48 + 13);
  // cut inside the last face
  auto r3 = io::parse_ply<T>(good.substr(0, good.size() - 2), {});
  ASSERT_FALSE(r3.has_value());
  EXPECT_EQ(r3.error().code, ErrorCode::truncated);
  EXPECT_EQ(r3.error().byte_offset, good.size() - 4);
}

TYPED_TEST(PlyTest, HeaderErrors) {
  using T = TypeParam;
  PlySpec sp;
  const std::string good = tet_ply(sp);
  auto with = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    s.replace(s.find(from), from.size(), to);
    return io::parse_ply<T>(s, {});
  };
  struct Case {
    const char* from;
    const char* to;
    ErrorCode code;
    std::uint64_t line;
  };
  const Case cases[] = {
      {"format ascii", "format utf8", ErrorCode::unsupported, 2},
      {"property float y", "property float x", ErrorCode::syntax, 6},
      {"element face 4", "element vertex 4", ErrorCode::syntax, 8},
      {"element face 4", "element face -4", ErrorCode::bad_number, 8},
      {"comment test", "commentary test", ErrorCode::syntax, 3},
      {"property float z\n", "property float z\nproperty list uchar int z2\nproperty floot w\n",
       ErrorCode::unsupported, 9},
      {"vertex_indices", "a\nproperty list uchar int b", ErrorCode::syntax, 8},
      {"end_header\n", "end_header junk\n", ErrorCode::syntax, 10},
  };
  for (const Case& c : cases) {
    auto r = with(c.from, c.to);
    ASSERT_FALSE(r.has_value()) << c.to;
    EXPECT_EQ(r.error().code, c.code) << c.to << ": " << r.error().what();
    EXPECT_EQ(r.error().line, c.line) << c.to << ": " << r.error().what();
  }
  auto empty = io::parse_ply<T>("", {});
  ASSERT_FALSE(empty.has_value());
  EXPECT_EQ(empty.error().code, ErrorCode::empty);
  // A point cloud (no faces) is `empty`.
  auto cloud = io::parse_ply<T>("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                                "property float y\nproperty float z\nend_header\n1 2 3\n",
                                {});
  ASSERT_FALSE(cloud.has_value());
  EXPECT_EQ(cloud.error().code, ErrorCode::empty);
}
