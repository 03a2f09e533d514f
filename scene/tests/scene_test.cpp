// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// The scene component in process: scenes compiled from JSON text against closed-form distances,
// mesh inputs against the library's brute-force mesh SDF, and errors that name the JSON pointer.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/scene/scene.hpp"
#include "ebgeom/sdf/brute_force_mesh_sdf.hpp"

using namespace ebgeom;
using V = Vec3<double>;

namespace {

/// Points on a 9^3 lattice over [-2, 2]^3 (off the symmetry planes).
std::vector<V> lattice() {
  std::vector<V> p;
  for (int k = 0; k < 9; ++k)
    for (int j = 0; j < 9; ++j)
      for (int i = 0; i < 9; ++i)
        p.push_back({-2 + 0.5 * i + 0.013, -2 + 0.5 * j - 0.021, -2 + 0.5 * k + 0.007});
  return p;
}

template <class T> scene::Program<T> compile(const std::string& json) {
  return scene::compile_scene<T>(scene::parse_json_text(json, "test.json"), "test.json");
}

/// Batch values of `prog` at `pts`.
template <class S> std::vector<double> batch(const S& prog, const std::vector<V>& pts) {
  std::vector<double> out(pts.size());
  prog.eval(Span<const V>(pts), Span<double>(out));
  return out;
}

} // namespace

TEST(SceneCompile, SphereMinusBoxIsTheClosedForm) {
  const auto prog = compile<double>(R"({"type": "difference", "children": [
      {"type": "sphere", "center": [0.1, 0, 0], "radius": 1.2},
      {"type": "box", "center": [1, 0, 0], "half_size": [0.5, 0.5, 0.5]}]})");
  const std::vector<V> pts = lattice();
  const std::vector<double> v = batch(prog, pts);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const V& p = pts[i];
    const double s = norm(p - V{0.1, 0, 0}) - 1.2;
    const V q = abs(p - V{1, 0, 0}) - V::constant(0.5);
    const double b = norm(max(q, V::zero())) + std::min(max_component(q), 0.0);
    EXPECT_NEAR(v[i], std::max(s, -b), 1e-12) << p;
    EXPECT_EQ(v[i], prog(p)) << "batch and single-point values agree bit for bit at " << p;
  }
}

TEST(SceneCompile, GeneratedMeshEqualsTheBruteForce) {
  const auto prog = compile<double>(R"({"type": "mesh", "generate": "icosphere",
                                        "subdivisions": 2, "radius": 1.5})");
  auto soup = make_icosphere<double>(2, 1.5);
  ASSERT_TRUE(soup);
  auto mesh = make_triangle_mesh(*soup);
  ASSERT_TRUE(mesh);
  const BruteForceMeshSdf<double> ref(*mesh);
  const std::vector<V> pts = lattice();
  const std::vector<double> v = batch(prog, pts);
  for (std::size_t i = 0; i < pts.size(); ++i) EXPECT_EQ(v[i], ref(pts[i])) << pts[i];
}

TEST(SceneCompile, ErrorsNameTheJsonPointer) {
  try {
    compile<float>(R"({"type": "union", "children": [{"type": "sphere", "radius": -1}]})");
    FAIL() << "a negative radius compiled";
  } catch (const scene::ToolError& e) {
    EXPECT_EQ(e.code, scene::exit_input);
    EXPECT_NE(std::string(e.what()).find("test.json: /children/0/radius"), std::string::npos)
        << e.what();
  }
}
