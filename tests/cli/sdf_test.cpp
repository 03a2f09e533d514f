// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// `ebgeom sdf`: every node type of the scene format against independent closed forms or the
// library, every output format read back, --band, --json, and every error path.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <functional>

#include "cli_support.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/sdf/brute_force_mesh_sdf.hpp"

using namespace ebgeom;
using namespace ebgeom::clitest;
using V = Vec3<double>;

namespace {

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

/// Runs `ebgeom sdf` on `scene` over the box [-2, 2]^3 with n^3 cells in double precision and
/// compares every sample with `ref` at the cell centres.
void check_scene(const std::string& scene, const std::function<double(const V&)>& ref,
                 double tol = 1e-9, int n = 10) {
  const std::string dir = test_dir();
  write_text(dir + "/s.json", scene);
  const RunResult r = run("sdf '" + dir + "/s.json' -o '" + dir + "/s.npy' --res " +
                          std::to_string(n) + " --box -2 -2 -2 2 2 2 --precision double -q");
  ASSERT_EQ(r.code, 0) << r.err;
  const Npy a = read_npy(dir + "/s.npy");
  ASSERT_EQ(a.descr, "<f8");
  ASSERT_EQ(a.shape, (std::vector<std::size_t>{std::size_t(n), std::size_t(n), std::size_t(n)}));
  const double h = 4.0 / n;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const V p{-2 + (i + 0.5) * h, -2 + (j + 0.5) * h, -2 + (k + 0.5) * h};
        ASSERT_NEAR(a.data[i + n * (j + n * k)], ref(p), tol) << scene << " at " << p;
      }
}

double sphere(const V& p, const V& c, double r) { return norm(p - c) - r; }
double box(const V& p, const V& c, const V& h, double rr = 0) {
  const V q = abs(p - c) - (h - V::constant(rr));
  return norm(max(q, V::zero())) + std::min(max_component(q), 0.0) - rr;
}
double segment_dist(const V& p, const V& a, const V& b) {
  const V ab = b - a;
  const double t = std::clamp(dot(p - a, ab) / dot(ab, ab), 0.0, 1.0);
  return norm(p - (a + ab * t));
}

} // namespace

TEST(SceneNodes, Sphere) {
  check_scene(R"({"type": "sphere", "center": [0.1, 0.2, -0.3], "radius": 0.9})", [](const V& p) {
    return sphere(p, {0.1, 0.2, -0.3}, 0.9);
  });
}

TEST(SceneNodes, BoxSizeHalfSizeAndRounding) {
  check_scene(R"({"type": "box", "center": [0, 0.5, 0], "size": [2, 1, 3]})", [](const V& p) {
    return box(p, {0, 0.5, 0}, {1, 0.5, 1.5});
  });
  check_scene(R"({"type": "box", "half_size": [1, 0.5, 1.5], "rounding": 0.2})", [](const V& p) {
    return box(p, {0, 0, 0}, {1, 0.5, 1.5}, 0.2);
  });
}

TEST(SceneNodes, Capsule) {
  check_scene(R"({"type": "capsule", "a": [-1, 0, 0], "b": [1, 0.5, 0], "radius": 0.3})",
              [](const V& p) {
                return segment_dist(p, {-1, 0, 0}, {1, 0.5, 0}) - 0.3;
              });
}

TEST(SceneNodes, CylinderAlongZ) {
  // Independent closed form for an axis-aligned capped cylinder: a 2D box in (radial, z).
  check_scene(
      R"({"type": "cylinder", "a": [0, 0, -1], "b": [0, 0, 1], "radius": 0.5})", [](const V& p) {
        const double dx = std::hypot(p.x, p.y) - 0.5, dz = std::abs(p.z) - 1;
        return std::min(std::max(dx, dz), 0.0) + std::hypot(std::max(dx, 0.0), std::max(dz, 0.0));
      });
}

TEST(SceneNodes, Torus) {
  check_scene(R"({"type": "torus", "major_radius": 1.2, "minor_radius": 0.3})",
              [](const V& p) { return std::hypot(std::hypot(p.x, p.y) - 1.2, p.z) - 0.3; });
}

TEST(SceneNodes, PlaneNeedsABoxAndIsAHalfSpace) {
  check_scene(R"({"type": "plane", "normal": [0, 0, 2], "point": [0, 0, 0.5]})",
              [](const V& p) { return p.z - 0.5; });
  const std::string dir = test_dir();
  write_text(dir + "/p.json", R"({"type": "plane", "normal": [0, 0, 1]})");
  const RunResult r = run("sdf '" + dir + "/p.json' -o '" + dir + "/p.npy' -q");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("unbounded"), std::string::npos) << r.err;
}

TEST(SceneNodes, CsgSharp) {
  check_scene(R"({"type": "union", "children": [
      {"type": "sphere", "center": [-0.5, 0, 0], "radius": 0.7},
      {"type": "sphere", "center": [0.6, 0, 0], "radius": 0.5}]})",
              [](const V& p) {
                return std::min(sphere(p, {-0.5, 0, 0}, 0.7), sphere(p, {0.6, 0, 0}, 0.5));
              });
  check_scene(R"({"type": "intersection", "children": [
      {"type": "sphere", "radius": 1}, {"type": "box", "half_size": [0.8, 0.8, 0.8]}]})",
              [](const V& p) {
                return std::max(sphere(p, {0, 0, 0}, 1), box(p, {0, 0, 0}, {0.8, 0.8, 0.8}));
              });
  check_scene(R"({"type": "difference", "children": [
      {"type": "box", "half_size": [1, 1, 1]},
      {"type": "sphere", "center": [1, 1, 1], "radius": 0.8},
      {"type": "sphere", "center": [-1, -1, -1], "radius": 0.5}]})",
              [](const V& p) {
                return std::max({box(p, {0, 0, 0}, {1, 1, 1}), -sphere(p, {1, 1, 1}, 0.8),
                                 -sphere(p, {-1, -1, -1}, 0.5)});
              });
}

TEST(SceneNodes, CsgSmoothUsesThePolynomialSmoothMin) {
  auto smin = [](double a, double b, double k) {
    const double h = std::max(k - std::abs(a - b), 0.0) / k;
    return std::min(a, b) - h * h * k / 4;
  };
  check_scene(R"({"type": "union", "smooth": 0.4, "children": [
      {"type": "sphere", "center": [-0.5, 0, 0], "radius": 0.6},
      {"type": "sphere", "center": [0.5, 0, 0], "radius": 0.6}]})",
              [&](const V& p) {
                return smin(sphere(p, {-0.5, 0, 0}, 0.6), sphere(p, {0.5, 0, 0}, 0.6), 0.4);
              });
  check_scene(R"({"type": "intersection", "smooth": 0.3, "children": [
      {"type": "sphere", "radius": 1}, {"type": "box", "half_size": [0.7, 2, 2]}]})",
              [&](const V& p) {
                return -smin(-sphere(p, {0, 0, 0}, 1), -box(p, {0, 0, 0}, {0.7, 2, 2}), 0.3);
              });
}

TEST(SceneNodes, TransformsMoveTheShape) {
  // Rotating a box 90 degrees about z swaps its x and y sizes; then scale 0.5 and translate.
  check_scene(R"({"type": "box", "half_size": [1, 0.4, 0.6],
      "rotate": {"axis": [0, 0, 1], "degrees": 90}, "scale": 0.5, "translate": [0.3, 0, 0]})",
              [](const V& p) {
                return box(p, {0.3, 0, 0}, {0.2, 0.5, 0.3});
              },
              1e-9);
  check_scene(R"({"type": "transform", "translate": [0, 0, 1],
      "child": {"type": "sphere", "radius": 0.5}})",
              [](const V& p) {
                return sphere(p, {0, 0, 1}, 0.5);
              });
}

TEST(SceneNodes, OffsetAndShell) {
  check_scene(R"({"type": "box", "half_size": [0.5, 0.5, 0.5], "offset": 0.25})", [](const V& p) {
    return box(p, {0, 0, 0}, {0.5, 0.5, 0.5}) - 0.25;
  });
  check_scene(R"({"type": "sphere", "radius": 1, "shell": 0.1})", [](const V& p) {
    return std::abs(sphere(p, {0, 0, 0}, 1)) - 0.1;
  });
}

TEST(SceneNodes, GeneratedMeshesMatchTheLibrary) {
  const auto soup = make_icosphere<double>(1, 1.3).value();
  const auto ref = BruteForceMeshSdf<double>::build(soup).value();
  check_scene(R"({"type": "mesh", "generate": "icosphere", "subdivisions": 1, "radius": 1.3})",
              [&](const V& p) { return ref(p); }, 1e-12, 8);
  const auto tor = BruteForceMeshSdf<double>::build(make_torus<double>(1.0, 0.4).value()).value();
  check_scene(R"({"type": "mesh", "generate": "torus", "major_radius": 1, "minor_radius": 0.4,
                  "sign": "unsigned"})",
              [&](const V& p) { return std::abs(tor(p)); }, 1e-12, 6);
}

TEST(SceneFiles, EveryExampleSceneRuns) {
  std::size_t count = 0;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::string(EBGEOM_SOURCE_DIR) + "/examples/scenes")) {
    if (entry.path().extension() != ".json") continue;
    ++count;
    const std::string name = entry.path().filename().string();
    const std::string dir = test_dir();
    const std::string in = entry.path().string();
    const RunResult r = run("sdf '" + in + "' -o '" + dir + "/x.vti' --res 12 --json");
    ASSERT_EQ(r.code, 0) << name << ": " << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_GT(j["inside_fraction"].get<double>(), 0.0) << name;
    EXPECT_LT(j["inside_fraction"].get<double>(), 1.0) << name;
    const Vti v = read_vti(dir + "/x.vti");
    EXPECT_EQ(v.data.size(), 12u * 12 * 12);
  }
  EXPECT_GE(count, 3u);
}

TEST(SdfCommand, OutputsAgreeAcrossFormatsAndWithTheJsonSummary) {
  const std::string dir = test_dir();
  write_text(dir + "/s.json", R"({"type": "sphere", "radius": 1})");
  const std::string common = " --res 9 7 5 --png '" + dir + "/s.png' --slice x=0.25 --json";
  RunResult r = run("sdf '" + dir + "/s.json' -o '" + dir + "/s.npy'" + common);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"input", "triangles", "dims", "box", "spacing", "timings", "min", "max",
                          "inside_fraction", "sign", "threads"})
    EXPECT_TRUE(j.contains(key)) << key;
  for (const char* key : {"parse_s", "build_s", "eval_s", "write_s"})
    EXPECT_TRUE(j["timings"].contains(key)) << key;
  EXPECT_EQ(j["dims"], nlohmann::json::array({9, 7, 5}));
  // Default box: bounds [-1, 1]^3 plus 10% of the extent per side.
  EXPECT_NEAR(j["box"]["lo"][0].get<double>(), -1.2, 1e-6);
  EXPECT_NEAR(j["box"]["hi"][2].get<double>(), 1.2, 1e-6);
  EXPECT_NEAR(j["spacing"][1].get<double>(), 2.4 / 7, 1e-6);
  const Npy npy = read_npy(dir + "/s.npy");
  EXPECT_EQ(npy.descr, "<f4");
  EXPECT_EQ(npy.shape, (std::vector<std::size_t>{5, 7, 9}));
  double mn = 1e9, mx = -1e9;
  for (double x : npy.data) mn = std::min(mn, x), mx = std::max(mx, x);
  EXPECT_DOUBLE_EQ(j["min"].get<double>(), mn);
  EXPECT_DOUBLE_EQ(j["max"].get<double>(), mx);
  const Png png = read_png(dir + "/s.png");
  EXPECT_EQ(png.width, unsigned(j["png"]["width"].get<int>()));
  EXPECT_EQ(png.height, unsigned(j["png"]["height"].get<int>()));
  EXPECT_GE(png.width, 256u);

  r = run("sdf '" + dir + "/s.json' -o '" + dir + "/s.vti'" + common);
  ASSERT_EQ(r.code, 0) << r.err;
  const Vti vti = read_vti(dir + "/s.vti");
  EXPECT_EQ(vti.data, npy.data);
  EXPECT_NEAR(vti.origin[0], -1.2 + 1.2 / 9, 1e-6);

  r = run("sdf '" + dir + "/s.json' -o '" + dir + "/g.raw' --res 9 7 5 -q --precision double");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string raw = slurp(dir + "/g.raw");
  ASSERT_EQ(raw.size(), npy.data.size() * 8);
  for (std::size_t i = 0; i < npy.data.size(); ++i) {
    double d;
    std::memcpy(&d, raw.data() + i * 8, 8);
    ASSERT_NEAR(d, npy.data[i], 1e-6);
  }
  // The sidecar of s.raw would be s.json, the input itself: refused.
  r = run("sdf '" + dir + "/s.json' -o '" + dir + "/s.raw' --res 4 -q");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("would overwrite the input"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(dir + "/s.json"), R"({"type": "sphere", "radius": 1})");
}

TEST(SdfCommand, RawSidecarDescribesTheGrid) {
  const std::string dir = test_dir();
  write_text(dir + "/in.json", R"({"type": "sphere", "radius": 1})");
  const RunResult r = run("sdf '" + dir + "/in.json' -o '" + dir + "/g.raw' --res 4 5 6 -q");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto side = nlohmann::json::parse(slurp(dir + "/g.json"));
  EXPECT_EQ(side["dims"], nlohmann::json::array({4, 5, 6}));
  EXPECT_EQ(side["dtype"], "float32");
  EXPECT_EQ(side["file"], "g.raw");
  EXPECT_EQ(slurp(dir + "/g.raw").size(), 4u * 5 * 6 * 4);
}

TEST(SdfCommand, BandClampsFarValuesAndKeepsNearOnes) {
  const std::string dir = test_dir();
  write_text(dir + "/s.json", R"({"type": "sphere", "radius": 1})");
  RunResult r = run("sdf '" + dir + "/s.json' -o '" + dir + "/d.npy' --res 24 -q");
  ASSERT_EQ(r.code, 0) << r.err;
  r = run("sdf '" + dir + "/s.json' -o '" + dir + "/b.npy' --res 24 --band 2 -q");
  ASSERT_EQ(r.code, 0) << r.err;
  const Npy d = read_npy(dir + "/d.npy"), b = read_npy(dir + "/b.npy");
  ASSERT_EQ(d.data.size(), b.data.size());
  const double band = 2 * 2.4 / 24;
  std::size_t clamped = 0;
  for (std::size_t i = 0; i < d.data.size(); ++i) {
    if (std::abs(d.data[i]) <= band - 1e-6) {
      ASSERT_EQ(b.data[i], d.data[i]);
    } else if (std::abs(d.data[i]) > band + 1e-6) {
      ASSERT_NEAR(b.data[i], std::copysign(band, d.data[i]), 1e-6);
      ++clamped;
    }
  }
  EXPECT_GT(clamped, 0u);
}

TEST(SdfErrors, MissingInputIsAnInputError) {
  const std::string dir = test_dir();
  const RunResult r = run("sdf '" + dir + "/nope.json' -o '" + dir + "/x.npy'");
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.err.find("ebgeom: error: " + dir + "/nope.json: no such file"), std::string::npos)
      << r.err;
  EXPECT_FALSE(exists(dir + "/x.npy"));
}

TEST(SdfErrors, MalformedJsonNamesTheLine) {
  const std::string dir = test_dir();
  write_text(dir + "/bad.json", "{\n  \"type\": \"sphere\",\n  \"radius\": ,\n}\n");
  const RunResult r = run("sdf '" + dir + "/bad.json' -o '" + dir + "/x.npy'");
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.err.find("bad.json: line 3"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST(SdfErrors, BadSceneValuesNameTheirJsonPointer) {
  const std::string dir = test_dir();
  struct Case {
    const char* scene;
    const char* expect;
  };
  const Case cases[] = {
      {R"({"root": {"type": "union", "children": [{"type": "sphere", "radius": 1},
          {"type": "sphere", "radius": 1}, {"type": "sphere", "radius": -1}]}})",
       "/root/children/2/radius: expected a positive number, got -1"},
      {R"({"type": "sphere", "radus": 1})", "/radus: unknown key for a sphere"},
      {R"({"type": "sphere"})", ": missing \"radius\""},
      {R"({"type": "blob"})", "/type: unknown node type \"blob\""},
      {R"({"type": "box", "size": [1, 2]})", "/size: expected an array of 3 numbers"},
      {R"({"type": "union", "children": []})", "/children: expected a non-empty array"},
      {R"({"type": "mesh", "path": "missing.stl"})", "/path: mesh file"},
      {R"({"type": "mesh", "generate": "icosphere", "sign": "windy"})",
       "/sign: unknown sign mode 'windy'"},
      {R"({"type": "sphere", "radius": 1, "rotate": {"axis": [0, 0, 0], "degrees": 3}})",
       "/rotate/axis: the rotation axis must not be zero"},
      {R"([1, 2])", "expected a node object"},
  };
  for (const Case& c : cases) {
    write_text(dir + "/s.json", c.scene);
    const RunResult r = run("sdf '" + dir + "/s.json' -o '" + dir + "/x.npy'");
    EXPECT_EQ(r.code, 3) << c.scene << "\n" << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << c.scene << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("ebgeom: error: " + dir + "/s.json: ", 0), 0u) << r.err;
    EXPECT_FALSE(exists(dir + "/x.npy"));
  }
}

TEST(SdfErrors, UsageErrors) {
  const std::string dir = test_dir();
  write_text(dir + "/s.json", R"({"type": "sphere", "radius": 1})");
  const std::string in = "sdf '" + dir + "/s.json' ";
  const char* bad[] = {
      "-o x.txt",                         // unknown output extension
      "-o x.npy --sign bogus",            // unknown
      "-o x.npy --res 4 4",               // two numbers
      "-o x.npy --res 4 --dx 0.1",        // exclusive
      "-o x.npy --precision half",        // not a precision
      "-o x.npy --slice z",               // --slice needs --png
      "-o x.npy --png p.png --slice w",   // bad axis
      "-o x.npy --png p.png --slice z=2", // fraction out of range
      "-o x.npy --box 1 1 1 0 0 0",       // inverted box
      "",                                 // missing -o
  };
  for (const char* args : bad) {
    const RunResult r = run(in + args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("ebgeom: error: ", 0), 0u) << args << "\n" << r.err;
  }
  const RunResult w = run(in + "-o x.npy --sign bogus");
  EXPECT_NE(w.err.find("unknown sign mode 'bogus'"), std::string::npos) << w.err;
}

TEST(SdfErrors, UnwritableOutputLeavesNothingBehind) {
  const std::string dir = test_dir();
  write_text(dir + "/s.json", R"({"type": "sphere", "radius": 1})");
  const RunResult r = run("sdf '" + dir + "/s.json' -o '" + dir + "/no/such/dir/x.vti' --res 4 -q");
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_NE(r.err.find("cannot open for writing"), std::string::npos) << r.err;
  // A failing PNG (after the grid was written) is an output error too.
  const RunResult p = run("sdf '" + dir + "/s.json' -o '" + dir + "/x.npy' --res 4 -q --png '" +
                          dir + "/no/p.png'");
  EXPECT_EQ(p.code, 4) << p.err;
  for (const auto& name : list_dir(dir)) EXPECT_EQ(name.find("tmp"), std::string::npos) << name;
}

TEST(SdfErrors, HugeGridsAreRefusedWithTheRequiredSize) {
  const std::string dir = test_dir();
  write_text(dir + "/s.json", R"({"type": "sphere", "radius": 1})");
  const RunResult r =
      run("sdf '" + dir + "/s.json' -o '" + dir + "/x.npy' --res 200000 200000 100 -q");
  EXPECT_EQ(r.code, 5) << r.err;
  EXPECT_NE(r.err.find("needs 14.6 TiB"), std::string::npos) << r.err;
  EXPECT_FALSE(exists(dir + "/x.npy"));
}

TEST(SdfErrors, DeeplyNestedScenesAreRefused) {
  const std::string dir = test_dir();
  std::string scene = R"({"type": "sphere", "radius": 1})";
  for (int i = 0; i < 300; ++i) scene = R"({"type": "transform", "child": )" + scene + "}";
  write_text(dir + "/deep.json", scene);
  const RunResult r = run("sdf '" + dir + "/deep.json' -o '" + dir + "/x.npy' --res 4");
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("nested deeper than"), std::string::npos) << r.err;
}

TEST(SceneNodes, AcceleratedUnionEqualsThePlainUnion) {
  const std::string dir = test_dir();
  // 60 spheres, a box and a generated mesh; then a mixed one with a smooth (non-exact) child.
  std::string kids;
  for (int i = 0; i < 60; ++i) {
    const double x = -1.5 + 0.05 * i, y = std::sin(i * 0.7), z = std::cos(i * 1.3);
    kids += R"({"type": "sphere", "center": [)" + std::to_string(x) + ", " + std::to_string(y) +
            ", " + std::to_string(z) + R"(], "radius": 0.15}, )";
  }
  kids += R"({"type": "box", "center": [1, 1, 1], "half_size": [0.2, 0.3, 0.1]}, )";
  kids += R"({"type": "mesh", "generate": "icosphere", "subdivisions": 1, "radius": 0.4})";
  const std::string mixed = kids + R"(, {"type": "union", "smooth": 0.2, "children": [
      {"type": "sphere", "radius": 0.3}, {"type": "box", "half_size": [0.2, 0.2, 0.6]}]})";
  for (const std::string& k : {kids, mixed}) {
    write_text(dir + "/plain.json", R"({"type": "union", "children": [)" + k + "]}");
    write_text(dir + "/fast.json",
               R"({"type": "union", "accelerate": true, "children": [)" + k + "]}");
    const std::string opts = " --res 20 --box -2 -2 -2 2 2 2 --precision double -q";
    RunResult r = run("sdf '" + dir + "/plain.json' -o '" + dir + "/plain.npy'" + opts);
    ASSERT_EQ(r.code, 0) << r.err;
    r = run("sdf '" + dir + "/fast.json' -o '" + dir + "/fast.npy'" + opts);
#if __has_include("ebgeom/sdf/bvh_union.hpp")
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(slurp(dir + "/plain.npy"), slurp(dir + "/fast.npy")); // bit for bit
#else
    EXPECT_EQ(r.code, 3) << r.err;
    EXPECT_NE(r.err.find("/accelerate: BVH-accelerated unions are not available"),
              std::string::npos)
        << r.err;
#endif
  }
#if __has_include("ebgeom/sdf/bvh_union.hpp")
  write_text(dir + "/s.json", R"({"type": "union", "accelerate": true, "smooth": 0.1,
      "children": [{"type": "sphere", "radius": 1}]})");
  RunResult r = run("sdf '" + dir + "/s.json' -o '" + dir + "/x.npy' --res 4");
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.err.find("/accelerate: an accelerated union must be sharp"), std::string::npos)
      << r.err;
  write_text(dir + "/p.json", R"({"type": "union", "accelerate": true,
      "children": [{"type": "sphere", "radius": 1}, {"type": "plane", "normal": [0, 0, 1]}]})");
  r = run("sdf '" + dir + "/p.json' -o '" + dir + "/x.npy' --res 4 --box -1 -1 -1 1 1 1");
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.err.find("/children/1: children of an accelerated union must be bounded"),
            std::string::npos)
      << r.err;
#endif
}

TEST(SdfCommand, BandEqualsTheClampedDenseGridOnEveryExampleScene) {
  const std::string dir = test_dir();
  std::vector<std::string> scenes;
  for (const auto& e :
       std::filesystem::directory_iterator(std::string(EBGEOM_SOURCE_DIR) + "/examples/scenes"))
    if (e.path().extension() == ".json") scenes.push_back(e.path().string());
  // A thick shell of a difference (a bound, not exact): culling must stay conservative.
  write_text(dir + "/shell.json", R"({"type": "difference", "shell": 0.3, "children": [
      {"type": "box", "half_size": [1, 1, 1]}, {"type": "sphere", "center": [1, 1, 1], "radius": 1}]})");
  scenes.push_back(dir + "/shell.json");
  for (const std::string& s : scenes) {
    const std::string opts = " --res 20 --precision double";
    RunResult r = run("sdf '" + s + "' -o '" + dir + "/d.npy' --json" + opts);
    ASSERT_EQ(r.code, 0) << s << r.err;
    const auto j = nlohmann::json::parse(r.out);
    r = run("sdf '" + s + "' -o '" + dir + "/b.npy' -q --band 1.5" + opts);
    ASSERT_EQ(r.code, 0) << s << r.err;
    const Npy d = read_npy(dir + "/d.npy"), b = read_npy(dir + "/b.npy");
    ASSERT_EQ(d.data.size(), b.data.size());
    double hmax = 0;
    for (const auto& h : j["spacing"]) hmax = std::max(hmax, h.get<double>());
    const double band = 1.5 * hmax;
    for (std::size_t i = 0; i < d.data.size(); ++i) {
      const double expect =
          std::abs(d.data[i]) <= band ? d.data[i] : std::copysign(band, d.data[i]);
      ASSERT_EQ(b.data[i], expect) << s << " sample " << i;
    }
  }
}

TEST(SceneNodes, ConeAgainstItsRevolvedCrossSection) {
  // Independent reference: a cone along z is the revolution of the trapezoid with the bottom cap
  // (0,0)-(ra,0), the side (ra,0)-(rb,h) and the top cap (rb,h)-(0,h) in the (r, z) half-plane.
  const double ra = 0.8, rb = 0.3, z0 = -0.7, z1 = 0.9;
  auto seg = [](double px, double py, double ax, double ay, double bx, double by) {
    const double dx = bx - ax, dy = by - ay;
    const double t = std::clamp(((px - ax) * dx + (py - ay) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
    return std::hypot(px - ax - t * dx, py - ay - t * dy);
  };
  check_scene(R"({"type": "cone", "a": [0, 0, -0.7], "b": [0, 0, 0.9], "radius_a": 0.8,
                  "radius_b": 0.3})",
              [&](const V& p) {
                const double r = std::hypot(p.x, p.y), z = p.z;
                const double d = std::min({seg(r, z, 0, z0, ra, z0), seg(r, z, ra, z0, rb, z1),
                                           seg(r, z, rb, z1, 0, z1)});
                const bool inside = z > z0 && z < z1 && r < ra + (rb - ra) * (z - z0) / (z1 - z0);
                return inside ? -d : d;
              },
              1e-12);
  // A rotated cone (axis along x) is the same field with the coordinates permuted.
  check_scene(R"({"type": "cone", "a": [-0.7, 0, 0], "b": [0.9, 0, 0], "radius_a": 0.8,
                  "radius_b": 0.3})",
              [&](const V& p) {
                const double r = std::hypot(p.y, p.z), z = p.x;
                const double d = std::min({seg(r, z, 0, z0, ra, z0), seg(r, z, ra, z0, rb, z1),
                                           seg(r, z, rb, z1, 0, z1)});
                const bool inside = z > z0 && z < z1 && r < ra + (rb - ra) * (z - z0) / (z1 - z0);
                return inside ? -d : d;
              },
              1e-12);
}

TEST(SdfCommand, DxAndNodeCentredGrids) {
  const std::string dir = test_dir();
  write_text(dir + "/s.json", R"({"type": "sphere", "radius": 1})");
  // --dx 0.25 on the default box [-1.2, 1.2]^3: ceil(2.4 / 0.25) = 10 cubic cells, box grows.
  RunResult r = run("sdf '" + dir + "/s.json' -o '" + dir + "/a.npy' --dx 0.25 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["dims"], nlohmann::json::array({10, 10, 10}));
  EXPECT_NEAR(j["box"]["hi"][0].get<double>(), 1.3, 1e-6);
  EXPECT_NEAR(j["spacing"][2].get<double>(), 0.25, 1e-7);
  EXPECT_EQ(j["centering"], "cell");
  // --nodes: samples on both faces, spacing extent / (n - 1), origin at the box corner.
  r = run("sdf '" + dir + "/s.json' -o '" + dir +
          "/n.vti' --nodes --res 5 --box -2 -2 -2 2 2 2 "
          "--precision double --json");
  ASSERT_EQ(r.code, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["centering"], "node");
  EXPECT_NEAR(j["spacing"][0].get<double>(), 1.0, 1e-12);
  const Vti v = read_vti(dir + "/n.vti");
  EXPECT_EQ(v.origin[0], -2.0);
  EXPECT_EQ(v.extent[1], 4);
  for (int k = 0; k < 5; ++k)
    for (int jj = 0; jj < 5; ++jj)
      for (int i = 0; i < 5; ++i)
        ASSERT_NEAR(v.data[i + 5 * (jj + 5 * k)],
                    std::sqrt(double((i - 2) * (i - 2) + (jj - 2) * (jj - 2) + (k - 2) * (k - 2))) -
                        1,
                    1e-12);
}

TEST(SdfErrors, DirectoriesAreNotInputFiles) {
  const std::string dir = test_dir();
  std::filesystem::create_directories(dir + "/d.json");
  std::filesystem::create_directories(dir + "/m.obj");
  for (const char* in : {"/d.json", "/m.obj"}) {
    const RunResult r = run("sdf '" + dir + in + "' -o '" + dir + "/x.npy'");
    EXPECT_EQ(r.code, 3) << r.err;
    EXPECT_NE(r.err.find("is a directory"), std::string::npos) << r.err;
  }
  write_text(dir + "/s.json", R"({"type": "mesh", "path": "m.obj"})");
  const RunResult r = run("sdf '" + dir + "/s.json' -o '" + dir + "/x.npy'");
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("/path: "), std::string::npos) << r.err;
  // An output path that is a directory: an output error, nothing left behind.
  std::filesystem::create_directories(dir + "/out.npy");
  write_text(dir + "/ok.json", R"({"type": "sphere", "radius": 1})");
  const RunResult w = run("sdf '" + dir + "/ok.json' -o '" + dir + "/out.npy' --res 4 -q");
  EXPECT_EQ(w.code, 4) << w.err;
  for (const auto& name : list_dir(dir)) EXPECT_EQ(name.find("tmp"), std::string::npos) << name;
}
