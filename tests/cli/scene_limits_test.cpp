// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Hostile and extreme scene files and numeric options: deep nesting, duplicate keys, numbers
// beyond double or the working precision, NaN options. Each ends with one short error line and
// the documented exit status, never a crash, a NaN grid or a silently ignored value.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#include "cli_support.hpp"

using namespace ebgeom::clitest;

namespace {

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

/// The error line: one line, prefixed, shorter than `max`.
void expect_one_short_line(const RunResult& r, std::size_t max = 300) {
  EXPECT_EQ(r.err.rfind("ebgeom: error: ", 0), 0u) << r.err;
  EXPECT_LE(r.err.size(), max) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

RunResult sdf(const std::string& dir, const std::string& scene, const std::string& extra = "") {
  write_text(dir + "/s.json", scene);
  return run("sdf '" + dir + "/s.json' -o '" + dir + "/s.npy' --res 8 " + extra);
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

} // namespace

TEST(SceneLimits, HundredThousandNestedArraysAreAnInputError) {
  // Crashed (stack overflow) while formatting the error message.
  const std::string dir = test_dir();
  const RunResult r = sdf(dir, std::string(100000, '[') + std::string(100000, ']'));
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "line 1, column 1002: JSON nested deeper than 1000 levels")) << r.err;
  expect_one_short_line(r);
  EXPECT_FALSE(exists(dir + "/s.npy"));
}

TEST(SceneLimits, LongJsonPointersAreCutWithAnEllipsis) {
  const std::string dir = test_dir();
  std::string scene = R"({"type": "sphere", "radius": -1})";
  for (int i = 0; i < 150; ++i) scene = R"({"type": "union", "children": [)" + scene + "]}";
  const RunResult r = sdf(dir, scene);
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "/children/0/children/0")) << r.err;
  EXPECT_TRUE(contains(r.err, "...")) << r.err;
  EXPECT_TRUE(contains(r.err, "/radius: expected a positive number, got -1")) << r.err;
  expect_one_short_line(r);
  EXPECT_LE(r.err.size() - r.err.find("s.json: "), 140u) << r.err; // the pointer is cut
}

TEST(SceneLimits, LargeValuesAreQuotedShortly) {
  const std::string dir = test_dir();
  std::string big = "[";
  for (int i = 0; i < 200000; ++i) big += "1,";
  big += "1]";
  const RunResult r = sdf(dir, R"({"type": "sphere", "radius": )" + big + "}");
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "/radius: expected a positive number, got [1,1,1")) << r.err;
  expect_one_short_line(r);
}

TEST(SceneLimits, DuplicateKeysNameTheKeyAndTheLine) {
  const std::string dir = test_dir();
  const RunResult r = sdf(dir, "{\"type\": \"union\", \"children\": [\n"
                               "  {\"type\": \"sphere\", \"radius\": 1},\n"
                               "  {\"type\": \"sphere\", \"radius\": 1, \"radius\": 2}]}");
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "s.json: line 3, column ")) << r.err;
  EXPECT_TRUE(contains(r.err, "duplicate key \"radius\"")) << r.err;
  expect_one_short_line(r);
  // The same key in different objects is fine.
  EXPECT_EQ(sdf(dir, R"({"type": "sphere", "radius": 1, "translate": [0, 0, 0],
                        "rotate": {"axis": [0, 0, 1], "degrees": 0}})",
                "-q")
                .code,
            0);
}

TEST(SceneLimits, NumbersBeyondDoubleAreInputErrorsWithTheirPlace) {
  // Exited 1 ("a bug") with nlohmann-json's raw message and no place.
  const std::string dir = test_dir();
  const RunResult r = sdf(dir, "{\"type\": \"sphere\",\n \"radius\": 1e400}");
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "s.json: line 2, column ")) << r.err;
  EXPECT_TRUE(contains(r.err, "1e400 is out of the range of a double")) << r.err;
  EXPECT_FALSE(contains(r.err, "json.exception")) << r.err;
  expect_one_short_line(r);
}

TEST(SceneLimits, ValuesBeyondTheWorkingPrecisionNameTheirKey) {
  // Each gave an all-NaN or all-inf grid with null min/max and exit 0 (or "unbounded").
  const std::string dir = test_dir();
  struct Case {
    const char* scene;
    const char* extra;
    const char* key;
  };
  const Case cases[] = {
      {R"({"type": "sphere", "radius": 1e29})", "", "/radius: 1e+29 is too large for float"},
      {R"({"type": "sphere", "radius": 1, "scale": 1e-300})", "--precision double",
       "/scale: 1e-300 is too small for double"},
      {R"({"type": "sphere", "radius": 1, "scale": 1e-300})", "", "/scale: 1e-300 is too small"},
      {R"({"type": "union", "smooth": 1e39, "children": [{"type": "sphere", "radius": 1}]})", "",
       "/smooth: 1e+39 is too large for float"},
      {R"({"type": "sphere", "radius": 1, "translate": [0, 1e300, 0]})", "--precision double",
       "/translate/1: 1e+300 is too large for double"},
      {R"({"type": "mesh", "generate": "box", "min": [0, 0, 0], "max": [1e30, 1, 1]})", "",
       "/max/0: 1e+30 is too large for float"},
  };
  for (const Case& c : cases) {
    const RunResult r = sdf(dir, c.scene, c.extra);
    EXPECT_EQ(r.code, 3) << c.scene << "\n" << r.err;
    EXPECT_TRUE(contains(r.err, c.key)) << c.scene << "\n" << r.err;
    EXPECT_FALSE(contains(r.err, "unbounded")) << r.err;
    expect_one_short_line(r);
  }
  // The same radius is fine in double.
  EXPECT_EQ(sdf(dir, R"({"type": "sphere", "radius": 1e29})", "--precision double -q").code, 0);
}

TEST(SceneLimits, HugeRotationAnglesAreReducedNotInfinite) {
  const std::string dir = test_dir();
  const RunResult r = sdf(dir, R"({"type": "box", "half_size": [1, 0.5, 0.25],
      "rotate": {"axis": [0, 0, 1], "degrees": 1e300}})",
                          "--json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j["min"].is_number()) << r.out;
  ASSERT_TRUE(j["max"].is_number()) << r.out;
  EXPECT_LT(j["min"].get<double>(), 0);
  EXPECT_GT(j["max"].get<double>(), 0);
}

TEST(SceneLimits, OverflowingBoundsAreNotCalledUnbounded) {
  // Every key is within range, but the nested scales overflow float: reported as "unbounded
  // (e.g. a plane)" before.
  const std::string dir = test_dir();
  const RunResult r = sdf(dir, R"({"type": "transform", "scale": 1e17, "child":
      {"type": "transform", "scale": 1e17, "child": {"type": "sphere", "radius": 1e17}}})");
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "s.json: /: the bounds of this node overflow float precision"))
      << r.err;
  EXPECT_FALSE(contains(r.err, "unbounded")) << r.err;
  expect_one_short_line(r);
}

TEST(SceneLimits, GridsWithNaNAreNeverWritten) {
  // Every value is in range, but two nested scales of 1e-15 map the grid's points to 1e30 in the
  // sphere's frame, whose squared length overflows float inside the evaluation. (This once wrote
  // a half-NaN grid with null min/max and exit 0.)
  const std::string dir = test_dir();
  const std::string nested = R"({"type": "transform", "scale": 1e-15,
      "child": {"type": "sphere", "radius": 1, "scale": 1e-15}})";
  const RunResult r = sdf(dir, nested, "--json --box -1 -1 -1 1 1 1");
  EXPECT_EQ(r.code, 3) << r.err << r.out;
  EXPECT_TRUE(contains(r.err, "samples are NaN or infinite")) << r.err;
  EXPECT_TRUE(contains(r.err, "nothing written")) << r.err;
  EXPECT_FALSE(contains(r.out, "null")) << r.out;
  EXPECT_FALSE(exists(dir + "/s.npy"));
  expect_one_short_line(r);
  // In double the same scene is fine, and --json has numbers for min and max.
  const RunResult d = sdf(dir, nested, "--json --box -1 -1 -1 1 1 1 --precision double");
  ASSERT_EQ(d.code, 0) << d.err;
  const auto j = nlohmann::json::parse(d.out);
  EXPECT_TRUE(j["min"].is_number() && j["max"].is_number()) << d.out;
  // Lengths of 1e17 are within float's range for the library's capped cylinder (no product of
  // three lengths): the grid is written, its extremes the closed form's at the cell centres.
  const RunResult c =
      sdf(dir, R"({"type": "cylinder", "a": [0, 0, -1e17], "b": [0, 0, 1e17], "radius": 1e17})",
          "--json");
  ASSERT_EQ(c.code, 0) << c.err;
  const auto jc = nlohmann::json::parse(c.out);
  ASSERT_TRUE(jc["min"].is_number() && jc["max"].is_number()) << c.out;
  EXPECT_LT(jc["min"].get<double>(), 0);
  EXPECT_GT(jc["max"].get<double>(), 0);
}

TEST(SceneLimits, MeshCoordinatesBeyondThePrecisionAreRefused) {
  const std::string dir = test_dir();
  write_text(dir + "/t.obj", "v 0 0 0\nv 1e30 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n"
                             "f 2 3 4\n");
  RunResult r = run("sdf '" + dir + "/t.obj' -o '" + dir + "/t.npy' --res 4");
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "t.obj: vertex 1 has a coordinate of magnitude 1e+30")) << r.err;
  EXPECT_TRUE(contains(r.err, "float")) << r.err;
  expect_one_short_line(r);
  write_text(dir + "/u.obj", "v 0 0 0\nv 1e300 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n"
                             "f 2 3 4\n");
  r = run("sdf '" + dir + "/u.obj' -o '" + dir + "/u.npy' --res 4 --precision double");
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "too large for double")) << r.err;
}

TEST(SceneLimits, NumericOptionsSayTheRuleInWords) {
  const std::string dir = test_dir();
  write_text(dir + "/s.json", R"({"type": "sphere", "radius": 1})");
  const std::string base = "sdf '" + dir + "/s.json' -o '" + dir + "/o.npy' ";
  struct Case {
    const char* args;
    const char* says;
  };
  const Case cases[] = {
      {"--band nan", "--band: must be a finite number >= 0, got 'nan'"},
      {"--band -1", "--band: must be a finite number >= 0, got '-1'"},
      {"--band inf", "--band: must be a finite number >= 0, got 'inf'"},
      {"--dx nan", "--dx: must be a finite number > 0, got 'nan'"},
      {"--dx 0", "--dx: must be a finite number > 0, got '0'"},
      {"--dx 1e999", "--dx: must be a finite number > 0"},
      {"--threads -1", "--threads: must be an integer >= 0, got '-1'"},
      {"--threads 1.5", "--threads: must be an integer >= 0"},
      {"--pad nan", "--pad: must be a finite number between 0 and 100"},
      {"--box 0 0 0 1 1 nan", "--box: every value must be a finite number"},
  };
  for (const Case& c : cases) {
    const RunResult r = run(base + c.args);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    EXPECT_TRUE(contains(r.err, c.says)) << c.args << "\n" << r.err;
    EXPECT_LE(r.err.size(), 300u) << r.err; // no 309-digit bound
    EXPECT_FALSE(exists(dir + "/o.npy")) << c.args;
  }
}

TEST(SceneLimits, NpyFortranOrderKeyIsReportedForWhatItIs) {
  const std::string dir = test_dir();
  write_text(dir + "/s.json", R"({"type": "sphere", "radius": 1})");
  auto write = [&](const std::string& dict) {
    std::string h = dict;
    while ((10 + h.size() + 1) % 64) h += ' ';
    h += '\n';
    std::ofstream out(dir + "/p.npy", std::ios::binary);
    out.write("\x93NUMPY\x01\x00", 8);
    const char len[2] = {char(h.size() & 0xff), char(h.size() >> 8)};
    out.write(len, 2);
    out << h;
    const double xyz[3] = {0, 0, 2};
    out.write(reinterpret_cast<const char*>(xyz), sizeof xyz);
  };
  auto query = [&] {
    return run("query '" + dir + "/s.json' --points '" + dir + "/p.npy' -o '" + dir + "/d.npy'");
  };
  write("{'descr': '<f8', 'shape': (1, 3), }");
  RunResult r = query();
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "no 'fortran_order' key")) << r.err;
  write("{'descr': '<f8', 'fortran_order': Maybe, 'shape': (1, 3), }");
  r = query();
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "'fortran_order' is 'Maybe', expected False or True")) << r.err;
  write("{'descr': '<f8', 'fortran_order': True, 'shape': (1, 3), }");
  r = query();
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "Fortran-order arrays are not supported")) << r.err;
  write("{'descr': '<f8', 'fortran_order': False, 'shape': (1, 3), }");
  r = query();
  EXPECT_EQ(r.code, 0) << r.err;
}

TEST(SceneSigns, JsonAndSummaryNameEachMeshSignAndWhy) {
  const std::string dir = test_dir();
  const std::string scene = R"({"type": "union", "children": [
    {"type": "mesh", "generate": "icosphere", "subdivisions": 1},
    {"type": "mesh", "generate": "box", "min": [2, 0, 0], "max": [3, 1, 1], "sign": "winding"}]})";
  RunResult r = sdf(dir, scene, "--json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j["meshes"].is_array()) << r.out;
  ASSERT_EQ(j["meshes"].size(), 2u) << r.out;
  EXPECT_EQ(j["meshes"][0]["node"], "/children/0");
  EXPECT_EQ(j["meshes"][0]["source"], "generate: icosphere");
  EXPECT_EQ(j["meshes"][0]["sign"], "auto");
  EXPECT_EQ(j["meshes"][0]["sign_used"], "pseudonormal");
  EXPECT_TRUE(contains(j["meshes"][0]["reason"], "closed, manifold")) << r.out;
  EXPECT_EQ(j["meshes"][1]["sign"], "winding");
  EXPECT_EQ(j["meshes"][1]["sign_used"], "winding");
  EXPECT_EQ(j["meshes"][1]["reason"], "requested");
  // `ebgeom query --json` lists them too.
  const double xyz[3] = {0, 0, 2};
  write_npy_bytes(dir + "/p.npy", "<f8", "(1, 3)", xyz, sizeof xyz);
  r = run("query '" + dir + "/s.json' --points '" + dir + "/p.npy' -o '" + dir + "/d.npy' --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto q = nlohmann::json::parse(r.out);
  ASSERT_EQ(q["meshes"].size(), 2u) << r.out;
  EXPECT_EQ(q["meshes"][1]["sign_used"], "winding");
  r = sdf(dir, scene);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "sign      /children/0 (generate: icosphere): pseudonormal (closed"))
      << r.out;
  EXPECT_TRUE(contains(r.out, "sign      /children/1 (generate: box): winding (requested)"))
      << r.out;
}
