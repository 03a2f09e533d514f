// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// The `sdf --help` narrow-band example must work on the mesh it names (a real mesh: label slow,
// run by the separate CTest entry cli.slow.help_examples, skipped in the plain cli run).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.hpp"

using namespace ebgeom::clitest;

TEST(SlowHelpExamples, SdfBandExampleWorksOnItsMesh) {
  if (!std::getenv("EBGEOM_SLOW_TESTS")) GTEST_SKIP() << "slow: run by cli.slow.help_examples";
  const std::string meshes = EBGEOM_TEST_MESH_DIR;
  const RunResult help = run("sdf --help");
  ASSERT_EQ(help.code, 0);
  // the example line with a band and a .npz output
  std::istringstream lines(help.out);
  std::string line, example;
  while (std::getline(lines, line))
    if (line.find("ebgeom sdf ") != std::string::npos && line.find(".npz") != std::string::npos &&
        line.find("--band") != std::string::npos)
      example = line;
  ASSERT_FALSE(example.empty()) << help.out;
  std::istringstream words(example.substr(example.find("ebgeom sdf ") + 11));
  std::vector<std::string> w;
  for (std::string x; words >> x && x[0] != '(';) w.push_back(x);
  ASSERT_GE(w.size(), 1u);
  const std::string mesh = meshes + "/" + w[0];
  if (!exists(mesh)) GTEST_SKIP() << mesh << " not found";
  // The example as printed, at a lower resolution to keep the test short.
  const std::string dir = test_dir();
  std::string args = "sdf '" + mesh + "'";
  for (std::size_t i = 1; i < w.size(); ++i) {
    if (w[i] == "-o") {
      args += " -o '" + dir + "/" + w[++i] + "'";
    } else if (w[i] == "--res") {
      args += " --res 256";
      ++i;
    } else {
      args += " " + w[i];
    }
  }
  const RunResult r = run(args + " --json");
  ASSERT_EQ(r.code, 0) << args << "\n" << r.err;
  const auto j = nlohmann::json::parse(r.out);
  // a closed mesh: the pseudonormal sign, and the band skips most tiles
  EXPECT_EQ(j["sign_used"]["mode"], "pseudonormal") << j["sign_used"].dump();
  EXPECT_LT(j["kept_tiles"].get<double>(), 0.5 * j["tiles"][0].get<double>() *
                                               j["tiles"][1].get<double>() *
                                               j["tiles"][2].get<double>());
}
