// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// The scene component in process: scenes compiled from JSON text against closed-form distances,
// the library's own static shapes, transforms and CSG (bit for bit), and mesh inputs against the
// library's brute-force mesh SDF; batch and single-point values, kinds, the mesh path of `visit`
// through the grid sampler, and errors that name the JSON pointer.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "ebgeom/eval/evaluate.hpp"
#include "ebgeom/eval/grid.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/scene/scene.hpp"
#include "ebgeom/sdf/brute_force_mesh_sdf.hpp"
#include "ebgeom/sdf/csg.hpp"
#include "ebgeom/sdf/shapes.hpp"
#include "ebgeom/sdf/transforms.hpp"

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

template <class T> scene::SceneSdf<T> compile(const std::string& json) {
  return scene::compile_scene<T>(scene::parse_json_text(json, "test.json"), "test.json");
}

/// Batch values of `s` at `pts` (through `evaluate`, as the tools call it).
template <class S> std::vector<double> batch(const S& s, const std::vector<V>& pts) {
  std::vector<double> out(pts.size());
  EXPECT_TRUE(evaluate(s, Span<const V>(pts), Span<double>(out)));
  return out;
}

/// The scene's batch and single-point values equal `ref(p)` bit for bit.
template <class F> void expect_same(const std::string& json, F ref) {
  const auto s = compile<double>(json);
  const std::vector<V> pts = lattice();
  const std::vector<double> v = batch(s, pts);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    ASSERT_EQ(v[i], double(ref(pts[i]))) << json << " at " << pts[i];
    ASSERT_EQ(s(pts[i]), v[i]) << "single point at " << pts[i];
  }
}

const char* sphere_json = R"({"type": "sphere", "center": [0.2, 0, 0], "radius": 0.9})";
const char* box_json = R"({"type": "box", "center": [-0.3, 0.1, 0], "half_size": [0.6, 0.4, 0.8]})";
const Sphere<double> lib_sphere{{0.2, 0, 0}, 0.9};
const Box<double> lib_box{{0.6, 0.4, 0.8}, {-0.3, 0.1, 0}};

std::string two(const std::string& type, const std::string& extra) {
  return R"({"type": ")" + type + R"(", )" + extra + R"("children": [)" + sphere_json + ", " +
         box_json + "]}";
}

} // namespace

TEST(SceneCompile, SphereMinusBoxIsTheClosedForm) {
  const std::vector<V> pts = lattice();
  const auto s = compile<double>(two("difference", ""));
  const std::vector<double> v = batch(s, pts);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const V& p = pts[i];
    const double a = norm(p - V{0.2, 0, 0}) - 0.9;
    const V q = abs(p - V{-0.3, 0.1, 0}) - V{0.6, 0.4, 0.8};
    const double b = norm(max(q, V::zero())) + std::min(max_component(q), 0.0);
    EXPECT_NEAR(v[i], std::max(a, -b), 1e-12) << p;
  }
}

TEST(SceneCompile, CsgIsTheLibrarysBitForBit) {
  expect_same(two("union", ""), [](const V& p) { return unite(lib_sphere, lib_box)(p); });
  expect_same(two("intersection", ""),
              [](const V& p) { return intersect(lib_sphere, lib_box)(p); });
  expect_same(two("difference", ""), [](const V& p) { return subtract(lib_sphere, lib_box)(p); });
  expect_same(two("union", R"("smooth": 0.3, )"),
              [](const V& p) { return smooth_unite(lib_sphere, lib_box, 0.3)(p); });
  expect_same(two("intersection", R"("smooth": 0.3, )"),
              [](const V& p) { return smooth_intersect(lib_sphere, lib_box, 0.3)(p); });
  expect_same(two("difference", R"("smooth": 0.3, )"),
              [](const V& p) { return smooth_subtract(lib_sphere, lib_box, 0.3)(p); });
  // three children fold left, as nested binary library operations
  const Capsule<double> cap{{-1, 0, 0}, {1, 0.5, 0}, 0.2};
  expect_same(R"({"type": "union", "smooth": 0.25, "children": [)" + std::string(sphere_json) +
                  ", " + box_json +
                  R"(, {"type": "capsule", "a": [-1, 0, 0], "b": [1, 0.5, 0], "radius": 0.2}]})",
              [&](const V& p) {
                return smooth_unite(smooth_unite(lib_sphere, lib_box, 0.25), cap, 0.25)(p);
              });
}

TEST(SceneCompile, TransformsAndModifiersAreTheLibrarys) {
  const Mat3<double> r = Mat3<double>::axis_degrees({1, 2, 3}, 40);
  expect_same(R"({"type": "box", "half_size": [0.6, 0.4, 0.8], "center": [-0.3, 0.1, 0],
                  "rotate": {"axis": [1, 2, 3], "degrees": 400}, "scale": 1.5,
                  "translate": [0.1, -0.2, 0.3]})",
              [&](const V& p) {
                return transform(scale(lib_box, 1.5), r, V{0.1, -0.2, 0.3})(p);
              });
  expect_same(R"({"type": "sphere", "center": [0.2, 0, 0], "radius": 0.9, "offset": -0.2})",
              [](const V& p) { return offset(lib_sphere, -0.2)(p); });
  expect_same(R"({"type": "sphere", "center": [0.2, 0, 0], "radius": 0.9, "shell": 0.1})",
              [](const V& p) { return shell(lib_sphere, 0.1)(p); });
}

TEST(SceneCompile, CylinderAndConeAreExactDistances) {
  // A tilted cylinder: the closed form in its own frame (radial rho, axial z in [-1, 1]).
  const V a{0.1, -0.2, -0.6}, b{0.5, 0.4, 0.9};
  const double len = norm(b - a), r = 0.45;
  const V w = (b - a) / len;
  const auto cyl = compile<double>(R"({"type": "cylinder", "a": [0.1, -0.2, -0.6],
                                       "b": [0.5, 0.4, 0.9], "radius": 0.45})");
  for (const V& p : lattice()) {
    const double h = dot(p - a, w), rho = norm(p - a - w * h);
    const double dr = rho - r, dh = std::max(-h, h - len);
    const double ref = dr > 0 && dh > 0   ? std::hypot(dr, dh)
                       : dr > 0 || dh > 0 ? std::max(dr, dh)
                                          : std::max(dr, dh);
    EXPECT_NEAR(cyl(p), ref, 1e-12) << p;
  }
  // A frustum from radius 0.7 at a to 0.2 at b: distance to its meridian outline (bottom cap,
  // slanted side, top cap) by brute force over 20001 points of each segment.
  const double ra = 0.7, rb = 0.2;
  const auto cone = compile<double>(R"({"type": "cone", "a": [0.1, -0.2, -0.6],
                                        "b": [0.5, 0.4, 0.9], "radius_a": 0.7, "radius_b": 0.2})");
  const Vec2<double> outline[4] = {{0, 0}, {ra, 0}, {rb, len}, {0, len}};
  for (const V& p : lattice()) {
    const double h = dot(p - a, w), rho = norm(p - a - w * h);
    double d = 1e300;
    for (int s = 0; s < 3; ++s)
      for (int t = 0; t <= 20000; ++t) {
        const Vec2<double> q = outline[s] + (outline[s + 1] - outline[s]) * (t / 20000.0);
        d = std::min(d, std::hypot(rho - q.x, h - q.y));
      }
    const bool inside = h > 0 && h < len && rho < ra + (rb - ra) * h / len;
    EXPECT_NEAR(cone(p), inside ? -d : d, 1e-4) << p;
  }
}

TEST(SceneCompile, KindsFollowTheLibrarysRules) {
  EXPECT_EQ(compile<double>(sphere_json).dynamic_kind(), SdfKind::exact);
  EXPECT_EQ(compile<double>(two("union", "")).dynamic_kind(), SdfKind::bound);
  EXPECT_EQ(compile<double>(two("union", R"("smooth": 0.2, )")).dynamic_kind(), SdfKind::bound);
  EXPECT_EQ(compile<double>(R"({"type": "union", "children": [)" + std::string(sphere_json) + "]}")
                .dynamic_kind(),
            SdfKind::exact);
  EXPECT_EQ(compile<double>(R"({"type": "sphere", "radius": 1, "shell": 0.1})").dynamic_kind(),
            SdfKind::bound);
  EXPECT_EQ(compile<double>(R"({"type": "mesh", "generate": "box", "min": [0, 0, 0],
                                "max": [1, 1, 1], "sign": "unsigned"})")
                .dynamic_kind(),
            SdfKind::implicit);
}

TEST(SceneCompile, AcceleratedUnionEqualsTheLinearUnion) {
  std::string j = R"({"type": "union", "accelerate": true, "children": [)";
  std::string l = R"({"type": "union", "children": [)";
  for (int i = 0; i < 20; ++i) {
    const std::string c = R"({"type": "sphere", "radius": 0.2, "center": [)" +
                          std::to_string(-1.9 + 0.2 * i) + ", " + std::to_string(0.1 * (i % 3)) +
                          ", 0]}" + (i < 19 ? ", " : "");
    j += c;
    l += c;
  }
  const auto acc = compile<double>(j + "]}"), lin = compile<double>(l + "]}");
  EXPECT_EQ(acc.dynamic_kind(), SdfKind::bound);
  const std::vector<V> pts = lattice();
  const std::vector<double> a = batch(acc, pts), b = batch(lin, pts);
  for (std::size_t i = 0; i < pts.size(); ++i) EXPECT_EQ(a[i], b[i]) << pts[i];
}

TEST(SceneCompile, GeneratedMeshEqualsTheBruteForce) {
  const auto s = compile<double>(R"({"type": "mesh", "generate": "icosphere",
                                     "subdivisions": 2, "radius": 1.5})");
  auto soup = make_icosphere<double>(2, 1.5);
  ASSERT_TRUE(soup);
  auto mesh = make_triangle_mesh(*soup);
  ASSERT_TRUE(mesh);
  const BruteForceMeshSdf<double> ref(*mesh);
  const std::vector<V> pts = lattice();
  const std::vector<double> v = batch(s, pts);
  for (std::size_t i = 0; i < pts.size(); ++i) EXPECT_EQ(v[i], ref(pts[i])) << pts[i];
  EXPECT_EQ(s.triangle_count(), mesh->triangle_count());
}

TEST(SceneMesh, BatchesInSpaceOrderEqualSinglePoints) {
  // Scenes with a mesh sort large batches in Morton order (SceneSdf::eval); the values must be
  // the single-point values wherever the points are and whatever their order, on every thread
  // count. A rotated mesh in a union with a sphere, a mesh alone, and shapes alone (input order).
  const std::string ico = R"({"type": "mesh", "generate": "icosphere", "subdivisions": 3,
                              "radius": 1.1, "rotate": {"axis": [1, 2, 3], "degrees": 20}})";
  const std::string scenes[] = {R"({"type": "union", "children": [)" + ico + ", " + sphere_json +
                                    "]}",
                                ico, two("difference", "")};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-2.5, 2.5);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const std::string& json : scenes) {
    const auto s = compile<double>(json);
    for (std::size_t n : {0, 1, 63, 64, 65, 257, 5000}) {
      std::vector<V> pts(n);
      for (V& p : pts) p = {u(rng), u(rng), u(rng)};
      if (n > 2) pts[n / 2] = {nan, 0, 0}, pts[n / 3] = pts[n / 3 + 1]; // NaN, a repeated point
      std::vector<double> got(n, -7.0);
      s.eval(Span<const V>(pts), Span<double>(got));
      for (std::size_t i = 0; i < n; ++i) {
        const double want = s(pts[i]);
        if (std::isnan(want))
          ASSERT_TRUE(std::isnan(got[i])) << json << " n " << n << " at " << i;
        else
          ASSERT_EQ(got[i], want) << json << " n " << n << " at " << pts[i];
      }
      for (int threads : {1, 2, 3}) {
        std::vector<double> e(n, -7.0);
        ExecOptions ex;
        ex.threads = threads;
        ASSERT_TRUE(evaluate(s, Span<const V>(pts), Span<double>(e), ex));
        for (std::size_t i = 0; i < n; ++i)
          ASSERT_TRUE(e[i] == got[i] || (std::isnan(e[i]) && std::isnan(got[i])))
              << json << " threads " << threads << " at " << i;
      }
    }
  }
}

TEST(SceneMesh, VisitSamplesTheMeshSdfItselfWithTheSameValues) {
  auto soup = make_torus<double>(1.0, 0.35);
  ASSERT_TRUE(soup);
  for (SignMode m : {SignMode::automatic, SignMode::fast_winding, SignMode::unsigned_distance}) {
    const scene::SceneSdf<double> s = scene::mesh_scene(*soup, "torus", m);
    ASSERT_NE(s.mesh(), nullptr);
    EXPECT_EQ(s.requested_sign(), m);
    // pseudonormal (auto on a closed torus) reaches MeshSdf, the others SignedMeshSdf
    const bool is_mesh_sdf = s.visit([](const auto& sdf) {
      return std::is_same_v<std::decay_t<decltype(sdf)>, MeshSdf<double>>;
    });
    EXPECT_EQ(is_mesh_sdf, m == SignMode::automatic);
    GridSpec<double> spec;
    spec.box = Aabb<double>({-1.6, -1.6, -0.6}, {1.6, 1.6, 0.6});
    spec.dims = {{20, 20, 9}};
    for (double band : {0.0, 0.25}) {
      GridOptions opt;
      opt.band = band;
      std::vector<double> g(spec.size());
      ASSERT_TRUE(
          s.visit([&](const auto& sdf) { return sample_grid(sdf, spec, Span<double>(g), opt); }));
      for (std::size_t k = 0; k < spec.nz(); ++k)
        for (std::size_t j = 0; j < spec.ny(); ++j)
          for (std::size_t i = 0; i < spec.nx(); ++i) {
            const double v = s(spec.point(i, j, k));
            const double want = band == 0 || std::abs(v) <= band ? v : std::copysign(band, v);
            ASSERT_EQ(g[spec.index(i, j, k)], want) << int(m) << " band " << band;
          }
    }
  }
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
