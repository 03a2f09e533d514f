// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "ebgeom/io.hpp"
#include "io_test_util.hpp"
#include "test_support.hpp"

using namespace ebgeom;

namespace {
template <class T> class ReadMeshTest : public ::testing::Test {};
TYPED_TEST_SUITE(ReadMeshTest, test::FloatTypes);

std::string fixture(const std::string& name) {
  return std::string(EBGEOM_TEST_DATA_DIR) + "/io/" + name;
}

ErrorCode code_from_name(const std::string& s) {
  for (int c = 0; c <= int(ErrorCode::out_of_memory); ++c)
    if (s == to_string(ErrorCode(c))) return ErrorCode(c);
  ADD_FAILURE() << "unknown code " << s;
  return ErrorCode::ok;
}
} // namespace

TEST(DetectFormat, ByContentFirstThenExtension) {
  using io::MeshFormat;
  EXPECT_EQ(io::detect_format("ply\nformat ascii 1.0\n"), MeshFormat::ply);
  EXPECT_EQ(io::detect_format("ply\r\nformat ascii 1.0\r\n", "x.obj"), MeshFormat::ply);
  EXPECT_EQ(io::detect_format("\xEF\xBB\xBFply\n"), MeshFormat::ply);
  EXPECT_EQ(io::detect_format("# vtk DataFile Version 2.0\n", "a.stl"), MeshFormat::vtk);
  EXPECT_EQ(io::detect_format("solid x\nfacet normal 0 0 1\n", "a.obj"), MeshFormat::stl);
  EXPECT_EQ(io::detect_format("# made by hand\n\nv 1 2 3\n", "a.stl"), MeshFormat::obj);
  EXPECT_EQ(io::detect_format("mtllib a.mtl\n"), MeshFormat::obj);
  EXPECT_EQ(io::detect_format("hello world\n"), MeshFormat::unknown);
  EXPECT_EQ(io::detect_format("hello world\n", "dir.v2/Mesh.OBJ"), MeshFormat::obj);
  EXPECT_EQ(io::detect_format("hello world\n", "dir.obj/mesh"), MeshFormat::unknown);
  // a binary STL whose header starts with "solid": the size rule wins
  std::string stl = "solid but binary";
  stl.resize(80, ' ');
  stl += std::string("\x01\0\0\0", 4) + std::string(50, '\0');
  EXPECT_EQ(io::detect_format(stl, "a.ply"), MeshFormat::stl);
  EXPECT_TRUE(io::is_binary_stl(stl));
}

TYPED_TEST(ReadMeshTest, DodecahedronIsTheSameInAllFormats) {
  using T = TypeParam;
  const char* const names[] = {"formats/dodecahedron.obj", "formats/dodecahedron.ply",
                               "formats/dodecahedron.stl", "formats/dodecahedron.vtk"};
  for (const char* n : names) EBGEOM_REQUIRE_MESH(n);
  std::vector<PolygonSoup<T>> meshes;
  for (const char* n : names) {
    auto r = io::read_mesh<T>(test::mesh_path(n));
    ASSERT_TRUE(r.has_value()) << r.error().what();
    EXPECT_EQ(r->vertex_count(), 20u) << n;
    EXPECT_EQ(r->face_count(), 36u) << n;
    meshes.push_back(std::move(*r));
  }
  // OBJ, PLY and VTK number the vertices alike: identical soups.
  EXPECT_EQ(meshes[0], meshes[1]);
  EXPECT_EQ(meshes[0], meshes[3]);
  // STL is welded in first-appearance order: equal up to numbering.
  EXPECT_FALSE(meshes[0] == meshes[2]);
  EXPECT_TRUE(test::same_mesh(meshes[0], meshes[2]));
  // Detection does not depend on the extension: the same bytes under a wrong name.
  for (const char* n : names) {
    io::ReadOptions opt;
    opt.path = "misnamed.txt";
    auto r = io::parse_mesh<T>(test::slurp(test::mesh_path(n)), opt);
    ASSERT_TRUE(r.has_value()) << n << ": " << r.error().what();
    EXPECT_TRUE(test::same_mesh(*r, meshes[0]));
  }
}

TYPED_TEST(ReadMeshTest, RoundTripThroughEveryWriter) {
  using T = TypeParam;
  // A mesh with a quad and a pentagon, non-trivial coordinates.
  PolygonSoup<T> s;
  s.vertices = {{0, 0, 0},
                {T(1.1), 0, 0},
                {T(1.1), T(0.3), T(1e-7)},
                {0, T(0.3), T(-2.5e6)},
                {T(0.5), T(-1) / T(3), T(3.14159265358979)}};
  s.add_face({0, 1, 2, 3});
  s.add_face({0, 4, 1});
  s.add_face({4, 3, 2, 1, 0});
  for (io::MeshFormat f :
       {io::MeshFormat::stl, io::MeshFormat::ply, io::MeshFormat::obj, io::MeshFormat::vtk})
    for (io::Encoding e : {io::Encoding::binary, io::Encoding::ascii}) {
      io::WriteOptions w;
      w.format = f;
      w.encoding = e;
      auto bytes = io::encode_mesh(s, w);
      ASSERT_TRUE(bytes.has_value()) << bytes.error().what();
      EXPECT_EQ(io::detect_format(*bytes), f);
      auto r = io::parse_mesh<T>(*bytes);
      ASSERT_TRUE(r.has_value()) << io::to_string(f) << ": " << r.error().what();
      if (f == io::MeshFormat::stl) {
        // STL: float coordinates, fan triangles, welded numbering
        PolygonSoup<float> fs;
        for (const auto& v : s.vertices) fs.vertices.push_back(Vec3<float>::from(v));
        fs.indices = s.indices;
        fs.offsets = s.offsets;
        PolygonSoup<float> rs;
        for (const auto& v : r->vertices) rs.vertices.push_back(Vec3<float>::from(v));
        rs.indices = r->indices;
        rs.offsets = r->offsets;
        EXPECT_EQ(r->face_count(), s.triangle_count());
        EXPECT_EQ(test::canonical_triangles(rs), test::canonical_triangles(fs));
      } else {
        EXPECT_EQ(*r, s) << io::to_string(f) << " " << int(e); // exact, same numbering
      }
    }
}

TYPED_TEST(ReadMeshTest, WriteAndReadFiles) {
  using T = TypeParam;
  const auto tet = test::tetrahedron<T>();
  const std::string path =
      ::testing::TempDir() + "ebgeom_io_rt_" + std::to_string(sizeof(T)) + ".ply";
  ASSERT_TRUE(io::write_mesh(path, tet).has_value());
  auto r = io::read_mesh<T>(path);
  ASSERT_TRUE(r.has_value()) << r.error().what();
  EXPECT_EQ(*r, tet);
  io::ReadOptions small;
  small.max_bytes = 10;
  auto big = io::read_mesh<T>(path, small);
  ASSERT_FALSE(big.has_value());
  EXPECT_EQ(big.error().code, ErrorCode::size_mismatch);
  std::remove(path.c_str());
  auto missing = io::read_mesh<T>(path);
  ASSERT_FALSE(missing.has_value());
  EXPECT_EQ(missing.error().code, ErrorCode::io);
  EXPECT_EQ(missing.error().path, path);
  EXPECT_EQ(io::write_mesh("/nonexistent-dir/x.stl", tet).error().code, ErrorCode::io);
  EXPECT_EQ(io::write_mesh("x.unknown", tet).error().code, ErrorCode::invalid_argument);
  PolygonSoup<T> bad = tet;
  bad.indices[4] = 17;
  io::WriteOptions w;
  w.format = io::MeshFormat::ply;
  EXPECT_EQ(io::encode_mesh(bad, w).error().code, ErrorCode::invalid_argument);
}

// Every fixture in tests/data/io/expected.txt reads with its expected code and location; "ok"
// fixtures are the unit tetrahedron in some tolerated spelling (CRLF, BOM, solid-named binary...).
TYPED_TEST(ReadMeshTest, FixturesGiveTheirExpectedErrors) {
  using T = TypeParam;
  std::ifstream manifest(fixture("expected.txt"));
  ASSERT_TRUE(manifest.good());
  std::string name, code, line, offset;
  int count = 0;
  while (manifest >> name >> code >> line >> offset) {
    ++count;
    auto r = io::read_mesh<T>(fixture(name));
    if (code == "ok") {
      ASSERT_TRUE(r.has_value()) << name << ": " << r.error().what();
      EXPECT_TRUE(test::same_mesh(*r, test::tetrahedron<T>())) << name;
      continue;
    }
    ASSERT_FALSE(r.has_value()) << name;
    const ParseError& e = r.error();
    EXPECT_EQ(e.code, code_from_name(code)) << name << ": " << e.what();
    EXPECT_EQ(e.path, fixture(name));
    if (line != "-") {
      EXPECT_EQ(e.line, std::stoull(line)) << name << ": " << e.what();
    }
    if (offset != "-") {
      EXPECT_EQ(e.line, 0u) << name;
      EXPECT_EQ(e.byte_offset, std::stoull(offset)) << name << ": " << e.what();
    }
    EXPECT_EQ(e.what().rfind(fixture(name) + ": ", 0), 0u) << e.what();
  }
  EXPECT_GE(count, 40);
}
