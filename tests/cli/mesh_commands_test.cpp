// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// `ebgeom sdf` on mesh files, `ebgeom query`, `ebgeom convert` and `ebgeom info`, checked against
// the library's reader and mesh SDF.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>

#include "cli_support.hpp"
#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/sdf/brute_force_mesh_sdf.hpp"

using namespace ebgeom;
using namespace ebgeom::clitest;
using V = Vec3<double>;

namespace {

/// An L-shaped closed prism (non-convex) as OBJ with quads and a hexagon, outward oriented.
const char* l_prism_obj = R"(# L prism
v 0 0 0
v 2 0 0
v 2 1 0
v 1 1 0
v 1 2 0
v 0 2 0
v 0 0 1
v 2 0 1
v 2 1 1
v 1 1 1
v 1 2 1
v 0 2 1
f 1 6 5 4 3 2
f 7 8 9 10 11 12
f 1 2 8 7
f 2 3 9 8
f 3 4 10 9
f 4 5 11 10
f 5 6 12 11
f 6 1 7 12
)";

std::string write_mesh_file(const std::string& dir, const std::string& name, const char* text) {
  const std::string p = dir + "/" + name;
  std::ofstream(p) << text;
  return p;
}

std::vector<V> sample_points() {
  std::vector<V> p;
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 5; ++j)
      for (int k = 0; k < 3; ++k) p.push_back({-0.7 + 0.55 * i, -0.6 + 0.7 * j, -0.4 + 0.9 * k});
  p.push_back({0.5, 0.5, 0.5}); // inside
  p.push_back({1.0, 0.5, 1.0}); // on the top face
  return p;
}

} // namespace

TEST(MeshInput, SdfGridMatchesTheLibraryMeshSdf) {
  const std::string dir = test_dir();
  const std::string obj = write_mesh_file(dir, "l.obj", l_prism_obj);
  const RunResult r =
      run("sdf '" + obj + "' -o '" + dir + "/l.vti' --res 10 --precision double --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["triangles"], 4 + 4 + 6 * 2);
  EXPECT_EQ(j["input_kind"], "mesh");
  // Default box: [0,2]x[0,2]x[0,1] + 10% of each extent per side.
  EXPECT_NEAR(j["box"]["lo"][2].get<double>(), -0.1, 1e-12);
  EXPECT_NEAR(j["box"]["hi"][0].get<double>(), 2.2, 1e-12);
  const auto sdf = BruteForceMeshSdf<double>::build(io::read_mesh<double>(obj).value()).value();
  const Vti v = read_vti(dir + "/l.vti");
  ASSERT_EQ(v.type, "Float64");
  std::size_t inside = 0;
  for (int k = 0; k < 10; ++k)
    for (int jj = 0; jj < 10; ++jj)
      for (int i = 0; i < 10; ++i) {
        const V p{v.origin[0] + i * v.spacing[0], v.origin[1] + jj * v.spacing[1],
                  v.origin[2] + k * v.spacing[2]};
        const double got = v.data[i + 10 * (jj + 10 * k)];
        ASSERT_NEAR(got, sdf(p), 1e-12) << p;
        inside += got < 0;
      }
  EXPECT_NEAR(double(inside) / 1000, j["inside_fraction"].get<double>(), 1e-12);
  // The notch of the L (x, y in (1, 2)) is outside.
  EXPECT_GT(sdf({1.5, 1.5, 0.5}), 0);
}

TEST(MeshInput, MalformedMeshIsAnInputErrorWithItsLocation) {
  const std::string dir = test_dir();
  const std::string obj = write_mesh_file(dir, "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
  RunResult r = run("sdf '" + obj + "' -o '" + dir + "/x.npy'");
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_EQ(r.err.rfind("ebgeom: error: " + obj + ": line 4", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(exists(dir + "/x.npy"));
  const std::string junk = write_mesh_file(dir, "junk.stl", "this is not a mesh");
  r = run("sdf '" + junk + "' -o '" + dir + "/x.npy'");
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find(junk + ": "), std::string::npos) << r.err;
}

TEST(Query, DistancesClosestPointsAndNormalsOnAMesh) {
  const std::string dir = test_dir();
  const std::string obj = write_mesh_file(dir, "l.obj", l_prism_obj);
  const auto pts = sample_points();
  // float32 input points: the tool reads them as float and computes in double.
  std::vector<float> pf;
  for (const V& p : pts) pf.insert(pf.end(), {float(p.x), float(p.y), float(p.z)});
  write_npy_bytes(dir + "/p.npy", "<f4", "(" + std::to_string(pts.size()) + ", 3)", pf.data(),
                  pf.size() * 4);
  const RunResult r =
      run("query '" + obj + "' --points '" + dir + "/p.npy' -o '" + dir + "/d.npy' --closest '" +
          dir + "/c.npy' --normals '" + dir + "/n.npy' --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["points"], pts.size());
  for (const char* key :
       {"input", "triangles", "timings", "min", "max", "inside_fraction", "sign", "threads"})
    EXPECT_TRUE(j.contains(key)) << key;
  const Npy d = read_npy(dir + "/d.npy"), c = read_npy(dir + "/c.npy"),
            n = read_npy(dir + "/n.npy");
  EXPECT_EQ(d.descr, "<f8");
  EXPECT_EQ(d.shape, (std::vector<std::size_t>{pts.size()}));
  EXPECT_EQ(c.shape, (std::vector<std::size_t>{pts.size(), 3}));
  EXPECT_EQ(n.shape, (std::vector<std::size_t>{pts.size(), 3}));
  const auto sdf = BruteForceMeshSdf<double>::build(io::read_mesh<double>(obj).value()).value();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const V p{double(pf[3 * i]), double(pf[3 * i + 1]), double(pf[3 * i + 2])};
    const auto ref = sdf.closest(p);
    ASSERT_EQ(d.data[i], ref.distance) << p;
    const V cp{c.data[3 * i], c.data[3 * i + 1], c.data[3 * i + 2]};
    const V nn{n.data[3 * i], n.data[3 * i + 1], n.data[3 * i + 2]};
    // The closest point: at the reported distance from p and on the surface (on exact ties the
    // BVH may report another closest point than the brute force).
    EXPECT_NEAR(norm(p - cp), std::abs(ref.distance), 1e-12) << p;
    EXPECT_NEAR(sdf(cp), 0, 1e-12) << p;
    EXPECT_NEAR(norm(nn), 1, 1e-12);
    // Moving against the normal by S lands on the closest point: p - S n = c.
    EXPECT_NEAR(norm(p - nn * ref.distance - cp), 0, 1e-9) << p;
  }
}

TEST(Query, SceneGradientGivesNormalsAndClosestPoints) {
  const std::string dir = test_dir();
  std::ofstream(dir + "/s.json") << R"({"type": "sphere", "center": [1, 0, 0], "radius": 2})";
  const std::vector<double> p{4, 0, 0, 1, 1, 0.5, -3, 2, 1};
  write_npy_bytes(dir + "/p.npy", "<f8", "(3, 3)", p.data(), p.size() * 8);
  const RunResult r = run("query '" + dir + "/s.json' --points '" + dir + "/p.npy' -o '" + dir +
                          "/d.npy' --closest '" + dir + "/c.npy' --normals '" + dir + "/n.npy' -q");
  ASSERT_EQ(r.code, 0) << r.err;
  const Npy d = read_npy(dir + "/d.npy"), c = read_npy(dir + "/c.npy"),
            n = read_npy(dir + "/n.npy");
  for (int i = 0; i < 3; ++i) {
    const V q{p[3 * i], p[3 * i + 1], p[3 * i + 2]};
    const V rel = q - V{1, 0, 0};
    EXPECT_NEAR(d.data[i], norm(rel) - 2, 1e-12);
    const V u = normalized(rel);
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(n.data[3 * i + a], u[a], 1e-6);
      EXPECT_NEAR(c.data[3 * i + a], (V{1, 0, 0} + u * 2.0)[a], 1e-6);
    }
  }
}

TEST(Query, BadPointFilesAreInputErrors) {
  const std::string dir = test_dir();
  std::ofstream(dir + "/s.json") << R"({"type": "sphere", "radius": 1})";
  const std::vector<double> six(6, 0.5);
  const std::vector<std::int32_t> ints(6, 1);
  struct Case {
    std::function<void(const std::string&)> make;
    const char* expect;
  };
  const Case cases[] = {
      {[&](const std::string& f) { write_npy_bytes(f, "<i4", "(2, 3)", ints.data(), 24); },
       "dtype '<i4' is not supported"},
      {[&](const std::string& f) { write_npy_bytes(f, "<f8", "(3, 2)", six.data(), 48); },
       "is not (N, 3)"},
      {[&](const std::string& f) { write_npy_bytes(f, "<f8", "(6,)", six.data(), 48); },
       "is not (N, 3)"},
      {[&](const std::string& f) { write_npy_bytes(f, "<f8", "(4, 3)", six.data(), 48); },
       "truncated data"},
      {[&](const std::string& f) { std::ofstream(f) << "not numpy at all"; }, "bad magic"},
  };
  for (const Case& c : cases) {
    const std::string f = dir + "/p.npy";
    c.make(f);
    const RunResult r =
        run("query '" + dir + "/s.json' --points '" + f + "' -o '" + dir + "/d.npy'");
    EXPECT_EQ(r.code, 3) << c.expect << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("ebgeom: error: " + f + ": byte ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err;
    EXPECT_FALSE(exists(dir + "/d.npy"));
  }
  const RunResult missing =
      run("query '" + dir + "/s.json' --points '" + dir + "/none.npy' -o '" + dir + "/d.npy'");
  EXPECT_EQ(missing.code, 3);
  const RunResult usage = run("query '" + dir + "/s.json' -o '" + dir + "/d.npy'");
  EXPECT_EQ(usage.code, 2); // --points is required
}

TEST(Convert, RoundTripsThroughEveryFormat) {
  const std::string dir = test_dir();
  const std::string obj = write_mesh_file(dir, "l.obj", l_prism_obj);
  const auto ref = BruteForceMeshSdf<double>::build(io::read_mesh<double>(obj).value()).value();
  for (const char* out : {"l.stl", "l.ply", "l.vtk", "l2.obj", "l.off"}) {
    for (const char* flag : {"", " --ascii"}) {
      const RunResult r = run("convert '" + obj + "' '" + dir + "/" + out + "'" + flag);
      ASSERT_EQ(r.code, 0) << out << flag << "\n" << r.err;
      EXPECT_NE(r.out.find("12 vertices"), std::string::npos) << r.out;
      auto soup = io::read_mesh<double>(dir + "/" + out);
      ASSERT_TRUE(soup) << out << flag;
      EXPECT_EQ(soup->triangle_count(), 20u) << out;
      const auto sdf = BruteForceMeshSdf<double>::build(*soup).value();
      for (const V& p : sample_points()) ASSERT_NEAR(sdf(p), ref(p), 1e-6) << out << flag << p;
    }
  }
}

// The summary names the encoding really written: OBJ and OFF are text even without --ascii.
TEST(Convert, ReportsTheRealEncoding) {
  const std::string dir = test_dir();
  const std::string obj = write_mesh_file(dir, "l.obj", l_prism_obj);
  struct Case {
    const char* out;
    const char* flag;
    const char* says;
  };
  for (const Case& c : {Case{"a.obj", "", "(obj ascii)"}, Case{"a.off", "", "(off ascii)"},
                        Case{"a.stl", "", "(stl binary)"}, Case{"b.stl", " --ascii", "(stl ascii)"},
                        Case{"a.ply", "", "(ply binary)"}}) {
    const RunResult r = run("convert '" + obj + "' '" + dir + "/" + c.out + "'" + c.flag);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find(c.says), std::string::npos) << c.out << ": " << r.out;
  }
  EXPECT_EQ(slurp(dir + "/a.off").rfind("OFF\n", 0), 0u);
}

// A double mesh whose coordinates float cannot hold is not written as an STL of infinities (which
// ebgeom itself would then refuse); formats that keep double precision take it exactly.
TEST(Convert, RefusesCoordinatesTheOutputCannotHold) {
  const std::string dir = test_dir();
  const std::string obj = write_mesh_file(
      dir, "big.obj",
      "v 0 0 0\nv 1e300 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n");
  RunResult r = run("convert '" + obj + "' '" + dir + "/big.stl'");
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("outside the range of float"), std::string::npos) << r.err;
  EXPECT_FALSE(exists(dir + "/big.stl"));
  for (const char* out : {"big.ply", "big.off", "big.vtk"}) {
    r = run("convert '" + obj + "' '" + dir + "/" + out + "'");
    ASSERT_EQ(r.code, 0) << out << ": " << r.err;
    auto soup = io::read_mesh<double>(dir + "/" + out);
    ASSERT_TRUE(soup) << out;
    EXPECT_EQ(soup->bounds().hi.x, 1e300) << out;
  }
}

// An OFF file works as input to every mesh command.
TEST(MeshInput, OffFilesAreRead) {
  const std::string dir = test_dir();
  const std::string off = write_mesh_file(
      dir, "tet.off",
      "OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n");
  RunResult r = run("info '" + off + "' --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["vertices"], 4);
  EXPECT_EQ(j["faces"], 4);
  EXPECT_EQ(j["boundary_edges"], 0);
  r = run("convert '" + off + "' '" + dir + "/tet.stl'");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string bad = write_mesh_file(dir, "bad.off", "OFF\n4 4 6\n0 0 0\n1 0 0\n");
  r = run("info '" + bad + "'");
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("bad.off:"), std::string::npos) << r.err;
}

TEST(Cli, UnknownCommandIsNamedAndTheCommandsListed) {
  const RunResult r = run("sfd x.stl");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("unknown command 'sfd'"), std::string::npos) << r.err;
  for (const char* c : {"demo", "sdf", "query", "convert", "info"})
    EXPECT_NE(r.err.find(c), std::string::npos) << c << ": " << r.err;
  EXPECT_EQ(run("sdf --help").code, 0);
}

TEST(Convert, Errors) {
  const std::string dir = test_dir();
  const std::string obj = write_mesh_file(dir, "l.obj", l_prism_obj);
  RunResult r = run("convert '" + obj + "' '" + dir + "/l.xyz'");
  EXPECT_EQ(r.code, 2) << r.err;
  r = run("convert '" + dir + "/none.obj' '" + dir + "/l.stl'");
  EXPECT_EQ(r.code, 3) << r.err;
  r = run("convert '" + obj + "' '" + dir + "/no/dir/l.stl'");
  EXPECT_EQ(r.code, 4) << r.err;
  const std::string bad = write_mesh_file(dir, "bad.obj", "v 0 0 0\nf 1 2 3\n");
  r = run("convert '" + bad + "' '" + dir + "/b.stl'");
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_FALSE(exists(dir + "/b.stl"));
}

TEST(Info, ReportsCountsTopologyAndGeometry) {
  const std::string dir = test_dir();
  const std::string obj = write_mesh_file(dir, "l.obj", l_prism_obj);
  RunResult r = run("info '" + obj + "' --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["vertices"], 12);
  EXPECT_EQ(j["faces"], 8);
  EXPECT_EQ(j["triangles"], 20);
  EXPECT_EQ(j["boundary_edges"], 0);
  EXPECT_EQ(j["non_manifold_edges"], 0);
  EXPECT_EQ(j["degenerate_faces"], 0);
  EXPECT_EQ(j["watertight"], true);
  EXPECT_EQ(j["consistently_oriented"], true);
  EXPECT_NEAR(j["volume"].get<double>(), 3.0, 1e-12);       // L of area 3, height 1
  EXPECT_NEAR(j["area"].get<double>(), 2 * 3 + 8.0, 1e-12); // caps + perimeter 8 x height 1
  EXPECT_EQ(j["bbox"]["hi"], nlohmann::json::array({2.0, 2.0, 1.0}));
  EXPECT_EQ(j["sdf_well_defined"], true);
  // An open box (top removed) has 4 boundary edges in one hole.
  std::string open = l_prism_obj;
  open = open.substr(0, open.find("f 7 8 9 10 11 12"));
  open += "f 1 2 8 7\nf 2 3 9 8\nf 3 4 10 9\nf 4 5 11 10\nf 5 6 12 11\nf 6 1 7 12\n";
  const std::string o2 = write_mesh_file(dir, "open.obj", open.c_str());
  r = run("info '" + o2 + "' --json");
  ASSERT_EQ(r.code, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["boundary_edges"], 6);
  EXPECT_EQ(j["watertight"], false);
  EXPECT_EQ(j["sdf_well_defined"], false);
  r = run("info '" + obj + "'");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("watertight yes"), std::string::npos) << r.out;
  r = run("info '" + dir + "/none.obj'");
  EXPECT_EQ(r.code, 3);
}
