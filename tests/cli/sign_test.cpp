// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// `--sign` for `ebgeom sdf` and `ebgeom query`, the scene key "sign", and `ebgeom info`'s report
// of what `--sign auto` would pick. The fixture is a unit cube without its top face (open).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "cli_support.hpp"

using namespace ebgeom::clitest;

namespace {

// Unit cube, outward quads, top (z = 1) missing.
const char* open_box_obj = R"(v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 1 4 3 2
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
)";

// The same cube, closed.
const char* closed_box_obj = R"(v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
)";

std::string write_file(const std::string& dir, const std::string& name, const char* text) {
  const std::string p = dir + "/" + name;
  std::ofstream(p) << text;
  return p;
}

// Inside the box; above the missing top (outside: the winding number is about 0.17 there, but
// pseudonormal takes the rim for the surface and says inside); beside the box (outside).
const double probe[] = {0.5, 0.5, 0.3, 0.5, 0.5, 1.5, 1.6, 0.5, 0.5};

std::string write_probes(const std::string& dir) {
  write_npy_bytes(dir + "/p.npy", "<f8", "(3, 3)", probe, sizeof(probe));
  return dir + "/p.npy";
}

struct Query {
  std::vector<double> d;
  nlohmann::json j;
};

Query query(const std::string& dir, const std::string& input, const std::string& sign_args) {
  const RunResult r = run("query '" + input + "' --points '" + write_probes(dir) + "' -o '" + dir +
                          "/d.npy' --json " + sign_args);
  EXPECT_EQ(r.code, 0) << sign_args << "\n" << r.err;
  Query q;
  if (r.code != 0) return q;
  q.j = nlohmann::json::parse(r.out);
  q.d = read_npy(dir + "/d.npy").data;
  return q;
}

TEST(Sign, QueryModesOnAnOpenMesh) {
  const std::string dir = test_dir();
  const std::string obj = write_file(dir, "open.obj", open_box_obj);
  const Query pn = query(dir, obj, "--sign pseudonormal");
  const Query w = query(dir, obj, "--sign winding");
  const Query fw = query(dir, obj, "--sign fast-winding");
  const Query un = query(dir, obj, "--sign unsigned");
  const Query au = query(dir, obj, "--sign auto");
  const Query def = query(dir, obj, "");
  for (const Query* q : {&pn, &w, &fw, &un, &au, &def}) {
    ASSERT_EQ(q->d.size(), 3u);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(std::abs(q->d[i]), std::abs(pn.d[i])) << i;
  }
  EXPECT_NEAR(std::abs(pn.d[0]), 0.3, 1e-12);
  EXPECT_NEAR(std::abs(pn.d[1]), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(pn.d[2], 0.6, 1e-12);
  // pseudonormal: inside, inside (wrong), outside; the winding modes: inside, outside, outside.
  EXPECT_LT(pn.d[0], 0);
  EXPECT_LT(pn.d[1], 0);
  for (const Query* q : {&w, &fw, &au, &def}) {
    EXPECT_LT(q->d[0], 0);
    EXPECT_GT(q->d[1], 0);
    EXPECT_GT(q->d[2], 0);
  }
  for (double v : un.d) EXPECT_GT(v, 0);
  EXPECT_EQ(pn.j["sign"], "pseudonormal");
  EXPECT_EQ(fw.j["sign"], "fast-winding");
  EXPECT_EQ(un.j["sign"], "unsigned");
  EXPECT_EQ(def.j["sign"], "auto");
  EXPECT_EQ(def.j["sign_used"]["mode"], "fast-winding");
  EXPECT_NE(def.j["sign_used"]["reason"].get<std::string>().find("not closed"), std::string::npos)
      << def.j.dump();
  EXPECT_EQ(w.j["sign_used"]["mode"], "winding");
  EXPECT_EQ(w.j["sign_used"]["reason"], "requested");
}

TEST(Sign, AutoIsPseudonormalOnAClosedMesh) {
  const std::string dir = test_dir();
  const std::string obj = write_file(dir, "closed.obj", closed_box_obj);
  const Query au = query(dir, obj, "");
  const Query pn = query(dir, obj, "--sign pseudonormal");
  EXPECT_EQ(au.j["sign_used"]["mode"], "pseudonormal");
  EXPECT_EQ(au.j["sign_used"]["reason"], "closed, manifold and consistently oriented");
  EXPECT_EQ(au.d, pn.d);
  EXPECT_GT(au.d[1], 0); // closed: above the top is outside
}

TEST(Sign, SdfGridWithEachMode) {
  const std::string dir = test_dir();
  const std::string obj = write_file(dir, "open.obj", open_box_obj);
  std::vector<double> ref;
  for (const char* mode : {"winding", "fast-winding", "auto", "pseudonormal", "unsigned"}) {
    const RunResult r = run("sdf '" + obj + "' -o '" + dir +
                            "/g.npy' --res 12 --precision double " + "--json --sign " + mode);
    ASSERT_EQ(r.code, 0) << mode << "\n" << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["sign"], mode);
    EXPECT_TRUE(j.contains("sign_used")) << j.dump();
    const std::vector<double> g = read_npy(dir + "/g.npy").data;
    ASSERT_EQ(g.size(), 12u * 12 * 12);
    if (ref.empty()) ref = g; // exact winding
    std::size_t sign_changes = 0;
    for (std::size_t i = 0; i < g.size(); ++i) {
      ASSERT_EQ(std::abs(g[i]), std::abs(ref[i]));
      sign_changes += (g[i] < 0) != (ref[i] < 0);
    }
    const std::string m = mode;
    if (m == "fast-winding" || m == "auto") {
      EXPECT_EQ(sign_changes, 0u) << mode;
    } else if (m == "pseudonormal") {
      EXPECT_GT(sign_changes, 0u); // cells above the open top read as inside
    } else if (m == "unsigned") {
      EXPECT_GE(j["min"].get<double>(), 0.0);
    }
    if (m == "winding") {
      EXPECT_GT(j["inside_fraction"].get<double>(), 0.2);
    }
  }
  // Text output names the mode used.
  const RunResult t = run("sdf '" + obj + "' -o '" + dir + "/g.npy' --res 4");
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.out.find("sign      fast-winding (not closed"), std::string::npos) << t.out;
}

TEST(Sign, NarrowBandKeepsTheWindingSign) {
  // The winding sign also changes across the surface that fills the hole, far from the mesh: a
  // narrow band must not propagate signs through it (the mesh is sampled as an implicit SDF).
  const std::string dir = test_dir();
  const std::string obj = write_file(dir, "open.obj", open_box_obj);
  const std::string common =
      "sdf '" + obj + "' --res 16 --precision double -q --sign fast-winding ";
  ASSERT_EQ(run(common + "-o '" + dir + "/dense.npy'").code, 0);
  ASSERT_EQ(run(common + "--band 1 -o '" + dir + "/band.npy'").code, 0);
  const std::vector<double> d = read_npy(dir + "/dense.npy").data,
                            b = read_npy(dir + "/band.npy").data;
  ASSERT_EQ(d.size(), b.size());
  for (std::size_t i = 0; i < d.size(); ++i) ASSERT_EQ(d[i] < 0, b[i] < 0) << i;
}

TEST(Sign, SceneKeySign) {
  const std::string dir = test_dir();
  write_file(dir, "open.obj", open_box_obj);
  Query q[2];
  const char* modes[2] = {"pseudonormal", "fast-winding"};
  for (int k = 0; k < 2; ++k) {
    std::ofstream(dir + "/s.json")
        << R"({"type": "mesh", "path": "open.obj", "sign": ")" << modes[k] << R"("})";
    q[k] = query(dir, dir + "/s.json", "");
    ASSERT_EQ(q[k].d.size(), 3u);
  }
  EXPECT_LT(q[0].d[1], 0);
  EXPECT_GT(q[1].d[1], 0);
  // Without the key a mesh node uses auto (fast winding for this open mesh).
  std::ofstream(dir + "/s.json") << R"({"type": "mesh", "path": "open.obj"})";
  const Query def = query(dir, dir + "/s.json", "");
  EXPECT_EQ(def.d, q[1].d);
  // A bad value names its JSON pointer.
  std::ofstream(dir + "/s.json") << R"({"type": "mesh", "path": "open.obj", "sign": "guess"})";
  const RunResult r = run("sdf '" + dir + "/s.json' -o '" + dir + "/x.npy'");
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.err.find("/sign: unknown sign mode 'guess'"), std::string::npos) << r.err;
}

TEST(Sign, BadSignIsAUsageError) {
  const std::string dir = test_dir();
  const std::string obj = write_file(dir, "open.obj", open_box_obj);
  for (const char* cmd : {"sdf", "query"}) {
    const std::string points =
        std::string(cmd) == "query" ? "--points '" + write_probes(dir) + "' " : "";
    const RunResult r = run(std::string(cmd) + " '" + obj + "' " + points + "-o '" + dir +
                            "/x.npy' --sign fast_winding");
    EXPECT_EQ(r.code, 2) << cmd << "\n" << r.err;
    EXPECT_NE(r.err.find("expected pseudonormal, winding, fast-winding, unsigned or auto"),
              std::string::npos)
        << r.err;
  }
}

TEST(Sign, InfoReportsWhatAutoWouldPick) {
  const std::string dir = test_dir();
  const std::string open = write_file(dir, "open.obj", open_box_obj);
  const std::string closed = write_file(dir, "closed.obj", closed_box_obj);
  RunResult r = run("info '" + open + "'");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("--sign auto would use fast-winding: not closed: 4 boundary edges in 1 "
                       "holes"),
            std::string::npos)
      << r.out;
  r = run("info '" + open + "' --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["auto_sign"]["mode"], "fast-winding");
  EXPECT_NE(j["auto_sign"]["reason"].get<std::string>().find("not closed"), std::string::npos);
  r = run("info '" + closed + "' --json");
  ASSERT_EQ(r.code, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["auto_sign"]["mode"], "pseudonormal");
  EXPECT_EQ(j["auto_sign"]["reason"], "closed, manifold and consistently oriented");
}

} // namespace
