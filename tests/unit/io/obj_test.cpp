// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include <gtest/gtest.h>

#include <string>

#include "ebgeom/io/obj.hpp"
#include "io_test_util.hpp"
#include "test_support.hpp"

using namespace ebgeom;

namespace {
template <class T> class ObjTest : public ::testing::Test {};
TYPED_TEST_SUITE(ObjTest, test::FloatTypes);

const char* const tet_vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
} // namespace

TYPED_TEST(ObjTest, PlainTetrahedron) {
  using T = TypeParam;
  auto r = io::parse_obj<T>(std::string(tet_vertices) + "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n", {});
  ASSERT_TRUE(r.has_value()) << r.error().what();
  EXPECT_EQ(*r, test::tetrahedron<T>());
}

TYPED_TEST(ObjTest, CornerFormsRelativeIndicesGroupsAndComments) {
  using T = TypeParam;
  const std::string text = "# comment\nmtllib x.mtl\no thing\n" + std::string(tet_vertices) +
                           "vt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\ng a b\nusemtl red\ns off\n"
                           "f 1/1 3/2 2/3\n"                        // v/vt
                           "f 1/1/1 2/2/1 4/3/1\n"                  // v/vt/vn
                           "f 2//1 3//1 4//1  # trailing comment\n" // v//vn
                           "f -4 -1 -2\n"                           // relative: 1 4 3
                           "l 1 2\np 3\n";
  auto r = io::parse_obj<T>(text, {});
  ASSERT_TRUE(r.has_value()) << r.error().what();
  EXPECT_EQ(*r, test::tetrahedron<T>());
}

TYPED_TEST(ObjTest, RelativeIndicesCountFromTheVerticesSoFar) {
  using T = TypeParam;
  // The second face's -3 -2 -1 are vertices 4 5 6 (0-based 3 4 5), not 1 2 3.
  auto r = io::parse_obj<T>(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 0 0 1\nv 1 0 1\nv 0 1 1\nf -3 -2 -1\n", {});
  ASSERT_TRUE(r.has_value()) << r.error().what();
  ASSERT_EQ(r->face_count(), 2u);
  EXPECT_EQ(r->face(0)[0], 0u);
  EXPECT_EQ(r->face(1)[0], 3u);
  EXPECT_EQ(r->face(1)[2], 5u);
}

TYPED_TEST(ObjTest, PolygonsColorsContinuationAndCrlf) {
  using T = TypeParam;
  const std::string text = "v 0 0 0 1 0 0\r\nv 1 0 0 0 1 0\r\nv 1 1 \\\r\n 0\r\nv 0 1 0 1.0\r\n"
                           "f 1 2 \\\n 3 4\r\n";
  auto r = io::parse_obj<T>(text, {});
  ASSERT_TRUE(r.has_value()) << r.error().what();
  ASSERT_EQ(r->vertex_count(), 4u);
  EXPECT_EQ(r->vertices[2], (Vec3<T>{1, 1, 0}));
  ASSERT_EQ(r->face_count(), 1u);
  EXPECT_EQ(r->face_size(0), 4u);
  EXPECT_EQ(r->triangle_count(), 2u);
  // lines are still counted through continuations
  auto e = io::parse_obj<T>(text + "f 1 2 \\\n 9\n", {});
  ASSERT_FALSE(e.has_value());
  EXPECT_EQ(e.error().code, ErrorCode::bad_index);
  EXPECT_EQ(e.error().line, 9u); // the line holding the bad index
}

TYPED_TEST(ObjTest, NumbersThroughFromChars) {
  using T = TypeParam;
  auto r = io::parse_obj<T>("v +1.5 -2e-3 1E2\nv 1e-60000 0 0\nv 0 0 1\nf 1 2 3\n", {});
  ASSERT_TRUE(r.has_value()) << r.error().what();
  EXPECT_EQ(r->vertices[0], (Vec3<T>{T(1.5), T(-2e-3), T(100)}));
  EXPECT_EQ(r->vertices[1].x, T(0)); // underflow is zero
  auto over = io::parse_obj<T>("v 1e999999 0 0\n", {});
  ASSERT_FALSE(over.has_value());
  EXPECT_EQ(over.error().code, ErrorCode::bad_number);
  for (const char* bad : {"v 0x10 0 0\n", "v 1,5 0 0\n", "v 1.0.0 0 0\n", "v - 0 0\n"}) {
    auto b = io::parse_obj<T>(bad, {});
    ASSERT_FALSE(b.has_value()) << bad;
    EXPECT_EQ(b.error().code, ErrorCode::bad_number) << bad;
    EXPECT_EQ(b.error().line, 1u);
  }
  for (const char* nf : {"v nan 0 0\n", "v 0 -inf 0\n", "v 0 0 infinity\n"}) {
    auto b = io::parse_obj<T>(nf, {});
    ASSERT_FALSE(b.has_value()) << nf;
    EXPECT_EQ(b.error().code, ErrorCode::non_finite) << nf;
  }
}

TYPED_TEST(ObjTest, FaceCornersOutsideTheFourFormsAreRejectedWithLineAndColumn) {
  using T = TypeParam;
  const std::string v = tet_vertices;
  // Accepted: v, v/vt, v/vt/vn, v//vn (negative indices too).
  for (const char* face : {"f 1 2 3\n", "f 1/1 2/2 3/3\n", "f 1/1/1 2/2/2 3/3/3\n",
                           "f 1//1 2//2 3//3\n", "f -4/-1/-1 -3//-2 -2/-3\n"}) {
    auto r = io::parse_obj<T>(v + face, {});
    EXPECT_TRUE(r.has_value()) << face << (r ? "" : r.error().what());
  }
  struct Case {
    const char* face;
    std::size_t column;
  };
  const Case cases[] = {{"f 1/2/3/4 2 3\n", 3}, {"f 1 2 1/2/3/4/5\n", 7}, {"f 1 2 3/\n", 7},
                        {"f 1 2/ 3\n", 5},      {"f 1// 2 3\n", 3},       {"f 1 2 3//\n", 7},
                        {"f 1 2 3/1/\n", 7},    {"f 1 2 3///1\n", 7},     {"f 1/-/1 2 3\n", 3},
                        {"f  1 2 3/4-5\n", 8}};
  for (const Case& c : cases) {
    auto r = io::parse_obj<T>(v + c.face, {});
    ASSERT_FALSE(r.has_value()) << c.face;
    EXPECT_EQ(r.error().code, ErrorCode::syntax) << c.face << ": " << r.error().what();
    EXPECT_EQ(r.error().line, 5u) << c.face;
    EXPECT_NE(r.error().what().find("line 5: column " + std::to_string(c.column) +
                                    ": malformed face corner"),
              std::string::npos)
        << c.face << ": " << r.error().what();
  }
}

TYPED_TEST(ObjTest, IndexErrors) {
  using T = TypeParam;
  const std::string v = tet_vertices;
  struct Case {
    const char* face;
    ErrorCode code;
  };
  const Case cases[] = {{"f 1 2 0\n", ErrorCode::bad_index},
                        {"f 1 2 5\n", ErrorCode::bad_index},
                        {"f -5 1 2\n", ErrorCode::bad_index},
                        {"f 1 2\n", ErrorCode::degenerate},
                        {"f\n", ErrorCode::degenerate},
                        {"f 1 2 x\n", ErrorCode::bad_number},
                        {"f 1 2 3a\n", ErrorCode::bad_number},
                        {"f 1 2 3/a\n", ErrorCode::syntax},
                        {"f 1 2 99999999999999999999\n", ErrorCode::bad_number}};
  for (const Case& c : cases) {
    auto r = io::parse_obj<T>(v + c.face, {});
    ASSERT_FALSE(r.has_value()) << c.face;
    EXPECT_EQ(r.error().code, c.code) << c.face << ": " << r.error().what();
    EXPECT_EQ(r.error().line, 5u) << c.face;
  }
  auto weird = io::parse_obj<T>(v + "\x01\x02 1 2 3\n", {});
  ASSERT_FALSE(weird.has_value());
  EXPECT_EQ(weird.error().code, ErrorCode::syntax);
  auto none = io::parse_obj<T>(v, {});
  ASSERT_FALSE(none.has_value());
  EXPECT_EQ(none.error().code, ErrorCode::empty);
  io::ReadOptions opt;
  opt.max_triangles = 1;
  auto cap = io::parse_obj<T>(v + "f 1 2 3 4\n", opt);
  ASSERT_FALSE(cap.has_value());
  EXPECT_EQ(cap.error().code, ErrorCode::size_mismatch);
}
