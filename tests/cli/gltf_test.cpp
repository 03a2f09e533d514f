// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// glTF 2.0 / GLB input: files written here by hand (a unit cube instanced by nodes with known
// transforms), queried with `ebgeom query` and compared with the closed-form box distance.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "ebgeom/core/vec.hpp"

using namespace ebgeom;
using namespace ebgeom::clitest;
using V = Vec3<double>;

namespace {

/// Closed-form signed distance of the box [lo, hi].
double box_sdf(const V& p, const V& lo, const V& hi) {
  V q;
  double inside = -1e300;
  for (int a = 0; a < 3; ++a) {
    const double c = 0.5 * (lo[a] + hi[a]), h = 0.5 * (hi[a] - lo[a]);
    q[a] = std::abs(p[a] - c) - h;
    inside = std::max(inside, q[a]);
  }
  const V out{std::max(q.x, 0.0), std::max(q.y, 0.0), std::max(q.z, 0.0)};
  return norm(out) + std::min(inside, 0.0);
}

/// The binary buffer: the 8 corners of [-1, 1]^3 (float VEC3) then 36 uint16 indices of its 12
/// outward triangles.
std::string cube_buffer() {
  std::string b;
  for (int i = 0; i < 8; ++i) {
    const float c[3] = {i & 1 ? 1.f : -1.f, i & 2 ? 1.f : -1.f, i & 4 ? 1.f : -1.f};
    b.append(reinterpret_cast<const char*>(c), 12);
  }
  const std::uint16_t tri[36] = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                                 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
  b.append(reinterpret_cast<const char*>(tri), sizeof tri);
  return b; // 96 + 72 bytes
}

/// The glTF JSON: node 0 (translation (10, 0, 0), scale 2) holds the cube and has child node 1
/// (translation (0, 3, 0), rotation 90 degrees about z, scale (1, 0.5, 1)) holding it again; node 2
/// mirrors the cube (scale (-1, 1, 1)) at (0, 0, -20). `buffer` is the buffer object.
nlohmann::json cube_gltf(const nlohmann::json& buffer) {
  const double s = std::sqrt(0.5);
  nlohmann::json j = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0, 2}}}}},
      {"nodes",
       {{{"mesh", 0}, {"translation", {10, 0, 0}}, {"scale", {2, 2, 2}}, {"children", {1}}},
        {{"mesh", 0},
         {"translation", {0, 3, 0}},
         {"rotation", {0, 0, s, s}},
         {"scale", {1, 0.5, 1}}},
        {{"mesh", 0}, {"matrix", {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -20, 1}}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"mode", 4}},
           {{"attributes", {{"POSITION", 0}}}, {"mode", 0}}}}}}}, // points: skipped
      {"buffers", {buffer}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 96}},
        {{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 72}}}},
      {"accessors",
       {{{"bufferView", 0},
         {"componentType", 5126},
         {"count", 8},
         {"type", "VEC3"},
         {"min", {-1, -1, -1}},
         {"max", {1, 1, 1}}},
        {{"bufferView", 1}, {"componentType", 5123}, {"count", 36}, {"type", "SCALAR"}}}}};
  return j;
}

std::string glb(const nlohmann::json& j, const std::string& bin) {
  std::string js = j.dump();
  while (js.size() % 4) js += ' ';
  std::string b = bin;
  while (b.size() % 4) b += '\0';
  auto u32 = [](std::string& out, std::uint32_t v) {
    out.append(reinterpret_cast<const char*>(&v), 4);
  };
  std::string out = "glTF";
  u32(out, 2);
  u32(out, std::uint32_t(12 + 8 + js.size() + 8 + b.size()));
  u32(out, std::uint32_t(js.size()));
  out += "JSON";
  out += js;
  u32(out, std::uint32_t(b.size()));
  out += std::string("BIN\0", 4);
  out += b;
  return out;
}

/// The expected surface: node 0's cube [8, 12] x [-2, 2] x [-2, 2]; node 1's: local x/y scaled
/// by (1, 0.5), rotated 90 degrees about z (x -> y, y -> -x), moved by (0, 3, 0), then node 0's
/// transform: x in 10 + 2 * [-0.5, 0.5], y in 2 * (3 + [-1, 1]), z in 2 * [-1, 1]; node 2's
/// mirrored cube [-1, 1]^2 x [-21, -19].
double expected(const V& p) {
  const double a = box_sdf(p, {8, -2, -2}, {12, 2, 2});
  const double b = box_sdf(p, {9, 4, -2}, {11, 8, 2});
  const double c = box_sdf(p, {-1, -1, -21}, {1, 1, -19});
  // the first two boxes touch along y = 2..4? no: [-2, 2] and [4, 8] are apart
  return std::min({a, b, c});
}

std::vector<V> points() {
  std::vector<V> p;
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 9; ++j)
      for (int k = 0; k < 9; ++k) p.push_back({-3 + 2.0 * i, -4 + 1.6 * j, -24 + 3.3 * k});
  p.push_back({10, 0, 0});  // inside node 0's cube: -2
  p.push_back({10, 6, 0});  // inside node 1's cube: -1
  p.push_back({0, 0, -20}); // inside the mirrored cube: -1
  return p;
}

void check_query(const std::string& dir, const std::string& mesh) {
  const auto pts = points();
  std::vector<double> pf;
  for (const V& p : pts) pf.insert(pf.end(), {p.x, p.y, p.z});
  write_npy_bytes(dir + "/p.npy", "<f8", "(" + std::to_string(pts.size()) + ", 3)", pf.data(),
                  pf.size() * 8);
  const RunResult r =
      run("query '" + mesh + "' --points '" + dir + "/p.npy' -o '" + dir + "/d.npy' --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["triangles"], 36u);
  const Npy d = read_npy(dir + "/d.npy");
  ASSERT_EQ(d.data.size(), pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i)
    ASSERT_NEAR(d.data[i], expected(pts[i]), 1e-9) << mesh << " at " << pts[i];
  EXPECT_NEAR(d.data[pts.size() - 3], -2, 1e-12);
  EXPECT_NEAR(d.data[pts.size() - 2], -1, 1e-12);
  EXPECT_NEAR(d.data[pts.size() - 1], -1, 1e-12);
}

} // namespace

#if EBGEOM_TEST_GLTF

// The same scene three ways: .gltf with a separate .bin, .gltf with an embedded base64 buffer,
// and .glb. Node transforms (TRS, a child under its parent, a mirroring matrix) are applied; the
// mirrored cube keeps its inside (its winding is reversed).
TEST(Gltf, NodeTransformsAreApplied) {
  const std::string dir = test_dir();
  const std::string bin = cube_buffer();
  std::ofstream(dir + "/cube.bin", std::ios::binary) << bin;
  std::ofstream(dir + "/cubes.gltf")
      << cube_gltf({{"uri", "cube.bin"}, {"byteLength", bin.size()}}).dump(1);
  check_query(dir, dir + "/cubes.gltf");

  static const char* b64 = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string enc;
  for (std::size_t i = 0; i < bin.size(); i += 3) {
    const std::uint32_t n =
        (std::uint32_t((unsigned char)bin[i]) << 16) |
        (i + 1 < bin.size() ? std::uint32_t((unsigned char)bin[i + 1]) << 8 : 0) |
        (i + 2 < bin.size() ? std::uint32_t((unsigned char)bin[i + 2]) : 0);
    enc += b64[(n >> 18) & 63];
    enc += b64[(n >> 12) & 63];
    enc += i + 1 < bin.size() ? b64[(n >> 6) & 63] : '=';
    enc += i + 2 < bin.size() ? b64[n & 63] : '=';
  }
  std::ofstream(dir + "/embedded.gltf")
      << cube_gltf(
             {{"uri", "data:application/octet-stream;base64," + enc}, {"byteLength", bin.size()}})
             .dump();
  check_query(dir, dir + "/embedded.gltf");

  std::ofstream(dir + "/cubes.glb", std::ios::binary)
      << glb(cube_gltf({{"byteLength", bin.size()}}), bin);
  check_query(dir, dir + "/cubes.glb");

  // and `sdf` and `info` read it too
  RunResult r = run("info '" + dir + "/cubes.glb' --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["triangles"], 36u);
  r = run("sdf '" + dir + "/cubes.glb' -o '" + dir + "/g.npy' --res 16 -q");
  EXPECT_EQ(r.code, 0) << r.err;
}

// Hostile files are input errors naming the file and what is wrong, never a crash.
TEST(Gltf, BadFilesAreInputErrors) {
  const std::string dir = test_dir();
  const std::string bin = cube_buffer();
  std::ofstream(dir + "/cube.bin", std::ios::binary) << bin;
  auto expect_error = [&](const std::string& name, const nlohmann::json& j, const char* says) {
    std::ofstream(dir + "/" + name) << j.dump();
    const RunResult r = run("info '" + dir + "/" + name + "'");
    EXPECT_EQ(r.code, 3) << name << ": " << r.err;
    EXPECT_NE(r.err.find(name), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << name << ": " << r.err;
  };
  const nlohmann::json buf = {{"uri", "cube.bin"}, {"byteLength", bin.size()}};
  nlohmann::json j = cube_gltf(buf);
  j["accessors"][1]["count"] = 3600;
  expect_error("long_indices.gltf", j, "do not fit");
  j = cube_gltf(buf);
  j["accessors"][0]["componentType"] = 5121;
  expect_error("byte_positions.gltf", j, "POSITION must be float VEC3");
  j = cube_gltf(buf);
  j["accessors"][0]["count"] = 4; // indices then point past the positions
  expect_error("few_positions.gltf", j, "past the 4 positions");
  j = cube_gltf(buf);
  j["nodes"][1]["children"] = {0}; // a cycle
  expect_error("cycle.gltf", j, "deeper than");
  j = cube_gltf(buf);
  j["meshes"][0]["primitives"][0]["mode"] = 1; // lines only
  j["meshes"][0]["primitives"].erase(1);
  expect_error("lines.gltf", j, "no triangles");
  std::ofstream(dir + "/garbage.glb") << "glTF not really";
  const RunResult r = run("info '" + dir + "/garbage.glb'");
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("garbage.glb"), std::string::npos) << r.err;
}

#else

TEST(Gltf, WithoutTinygltfTheErrorSaysHowToGetIt) {
  const std::string dir = test_dir();
  std::ofstream(dir + "/a.gltf") << "{}";
  const RunResult r = run("info '" + dir + "/a.gltf'");
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.err.find("libtinygltf-dev"), std::string::npos) << r.err;
}

#endif
