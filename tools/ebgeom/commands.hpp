// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// Subcommand registration: each subcommand file adds its CLI11 sub-app and the function that runs
// it once the command line is parsed.

#include <CLI/CLI.hpp>

#include <functional>
#include <vector>

namespace ebgeom::cli {

struct Subcommand {
  CLI::App* app = nullptr;
  std::function<int()> run;
};

Subcommand add_demo(CLI::App& app);
Subcommand add_sdf(CLI::App& app);
Subcommand add_query(CLI::App& app);
Subcommand add_convert(CLI::App& app);
Subcommand add_info(CLI::App& app);

} // namespace ebgeom::cli
