// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// `ebgeom query` shows the same progress bar as `sdf` when stderr is a terminal (run under
// script(1) for a pseudo-terminal; skipped without it), and none with --quiet. The bar's
// half-second delay is set to 0 through EBGEOM_PROGRESS_DELAY so that the test does not depend on
// speed.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "cli_support.hpp"

using namespace ebgeom::clitest;

TEST(Progress, QueryShowsABarOnATerminal) {
  if (std::system("command -v script >/dev/null 2>&1") != 0) GTEST_SKIP() << "no script(1)";
  const std::string dir = test_dir();
  std::ofstream(dir + "/s.json")
      << R"({"type": "mesh", "generate": "icosphere", "subdivisions": 3})";
  // EBGEOM_PROGRESS_DELAY=0: the bar appears at once, however fast the machine
  std::vector<float> p;
  const std::size_t n = 200000;
  p.reserve(3 * n);
  for (std::size_t i = 0; i < n; ++i)
    p.insert(p.end(),
             {float(i % 97) / 40 - 1.2f, float(i % 89) / 35 - 1.2f, float(i % 83) / 33 - 1.2f});
  write_npy_bytes(dir + "/p.npy", "<f4", "(" + std::to_string(n) + ", 3)", p.data(), p.size() * 4);
  auto under_tty = [&](const std::string& extra) {
    const std::string cmd = "EBGEOM_PROGRESS_DELAY=0 " + std::string(EBGEOM_CLI_BINARY) +
                            " query " + dir + "/s.json --points " + dir + "/p.npy -o " + dir +
                            "/d.npy --threads 1" + extra;
    const std::string log = dir + "/tty.log";
    const int st =
        std::system(("script -qec '" + cmd + "' /dev/null > '" + log + "' 2>&1").c_str());
    EXPECT_EQ(st, 0) << slurp(log);
    return slurp(log);
  };
  const std::string shown = under_tty("");
  EXPECT_NE(shown.find("querying ["), std::string::npos) << shown;
  EXPECT_NE(shown.find("ebgeom query:"), std::string::npos) << shown; // the summary follows
  const std::string quiet = under_tty(" -q");
  EXPECT_EQ(quiet.find("querying"), std::string::npos) << quiet;
}
