// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Every shared mesh reads with the counts its own file declares; igea's triangle strips give a
// closed, consistently oriented surface; real meshes survive the binary writers. Skips, saying
// so, when ../shared/meshes is absent.

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <string>
#include <utility>

#include "../unit/io/io_test_util.hpp"
#include "ebgeom/io.hpp"
#include "test_support.hpp"

using namespace ebgeom;

namespace {

// Independent oracle for OBJ counts: lines whose first token is "v" or "f".
std::pair<std::size_t, std::size_t> count_obj_lines(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::size_t v = 0, f = 0;
  while (std::getline(in, line)) {
    const std::size_t i = line.find_first_not_of(" \t");
    if (i == std::string::npos) continue;
    if (line.compare(i, 2, "v ") == 0 || line.compare(i, 2, "v\t") == 0) ++v;
    if (line.compare(i, 2, "f ") == 0 || line.compare(i, 2, "f\t") == 0) ++f;
  }
  return {v, f};
}

class ObjMeshes : public ::testing::TestWithParam<const char*> {};

} // namespace

TEST_P(ObjMeshes, CountsMatchTheFile) {
  const std::string name = GetParam();
  EBGEOM_REQUIRE_MESH(name);
  const std::string path = test::mesh_path(name);
  const auto [nv, nf] = count_obj_lines(path);
  auto r = io::read_mesh<double>(path);
  ASSERT_TRUE(r.has_value()) << r.error().what();
  EXPECT_EQ(r->vertex_count(), nv);
  EXPECT_EQ(r->face_count(), nf);
  EXPECT_EQ(io::detect_format(test::slurp(path)), io::MeshFormat::obj);
  // float reads the same structure
  auto f = io::read_mesh<float>(path);
  ASSERT_TRUE(f.has_value());
  EXPECT_EQ(f->indices, r->indices);
}

TEST_P(ObjMeshes, SurviveBinaryWriters) {
  const std::string name = GetParam();
  EBGEOM_REQUIRE_MESH(name);
  auto r = io::read_mesh<float>(test::mesh_path(name));
  ASSERT_TRUE(r.has_value());
  io::WriteOptions ply;
  ply.format = io::MeshFormat::ply;
  auto back = io::parse_mesh<float>(io::encode_mesh(*r, ply).value());
  ASSERT_TRUE(back.has_value()) << back.error().what();
  EXPECT_EQ(*back, *r);
  io::WriteOptions stl;
  stl.format = io::MeshFormat::stl;
  auto tri = io::parse_mesh<float>(io::encode_mesh(*r, stl).value());
  ASSERT_TRUE(tri.has_value()) << tri.error().what();
  EXPECT_EQ(tri->face_count(), r->triangle_count());
  EXPECT_LE(tri->vertex_count(), r->vertex_count()); // unreferenced vertices disappear
  EXPECT_EQ(test::canonical_triangles(*tri), test::canonical_triangles(*r));
}

INSTANTIATE_TEST_SUITE_P(Shared, ObjMeshes,
                         ::testing::Values("stanford-bunny.obj", "ogre.obj", "nefertiti.obj",
                                           "spot.obj", "fandisk.obj", "cow.obj", "teapot.obj",
                                           "suzanne.obj"));

TEST(IgeaPly, StripsGiveAClosedConsistentlyOrientedSurface) {
  EBGEOM_REQUIRE_MESH("igea.ply");
  const std::string path = test::mesh_path("igea.ply");
  const std::string bytes = test::slurp(path);
  auto h = io::parse_ply_header(bytes, {});
  ASSERT_TRUE(h.has_value()) << h.error().what();
  ASSERT_EQ(h->elements.size(), 2u);
  EXPECT_EQ(h->elements[1].name, "tristrips");
  auto r = io::read_mesh<double>(path);
  ASSERT_TRUE(r.has_value()) << r.error().what();
  EXPECT_EQ(r->vertex_count(), h->elements[0].count);
  // Each directed edge once and each undirected edge twice: closed and consistently oriented,
  // which only holds if every second strip triangle was flipped.
  std::map<std::pair<Index, Index>, int> directed;
  for (std::size_t f = 0; f < r->face_count(); ++f) {
    const auto c = r->face(f);
    ASSERT_EQ(c.size(), 3u);
    for (int k = 0; k < 3; ++k) ++directed[{c[k], c[(k + 1) % 3]}];
  }
  std::size_t bad = 0;
  for (const auto& [e, n] : directed) {
    if (n != 1) ++bad;
    auto twin = directed.find({e.second, e.first});
    if (twin == directed.end() || twin->second != 1) ++bad;
  }
  EXPECT_EQ(bad, 0u);
  // Euler: V - E + F = 2 for a closed genus-0 surface with E = 3F/2.
  const long long V = (long long)r->vertex_count(), F = (long long)r->face_count();
  EXPECT_EQ(V - 3 * F / 2 + F, 2);
}
