// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// ebgeom command-line tool: entry point, subcommand dispatch and error reporting.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/error.hpp"
#include "ebgeom/io/atomic_file.hpp"

int main(int argc, char** argv) {
  using namespace ebgeom::cli;
  // SIGINT, SIGTERM, SIGHUP, SIGPIPE: remove unfinished temporary outputs, then end as usual.
  ebgeom::remove_temp_files_on_signals();
  CLI::App app{"ebgeom: fast exact signed distance fields (S < 0 inside, S > 0 outside)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("ebgeom ") + EBGEOM_VERSION_STRING);
  app.footer("Exit status: 0 success, 1 internal error, 2 usage, 3 input, 4 output, 5 memory.\n"
             "Run 'ebgeom COMMAND --help' for a command's options and examples.");
  std::vector<Subcommand> subs;
  subs.push_back(add_demo(app));
  subs.push_back(add_sdf(app));
  subs.push_back(add_query(app));
  subs.push_back(add_convert(app));
  subs.push_back(add_info(app));
  // An unknown first word is a mistyped command: name it and list the commands (CLI11 would say
  // only that a subcommand is required).
  bool known = argc < 2 || argv[1][0] == '-';
  for (const auto& s : subs) known = known || s.app->check_name(argv[1]);
  if (!known) {
    std::string names;
    for (const auto& s : subs) names += (names.empty() ? "" : ", ") + s.app->get_name();
    std::fprintf(stderr, "ebgeom: error: unknown command '%s'; the commands are: %s\n", argv[1],
                 names.c_str());
    std::fprintf(stderr, "Run 'ebgeom --help' or 'ebgeom COMMAND --help' for usage.\n");
    return exit_usage;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "ebgeom: error: %s\n", e.what());
    std::fprintf(stderr, "Run 'ebgeom --help' or 'ebgeom COMMAND --help' for usage.\n");
    return exit_usage;
  }
  try {
    for (const auto& s : subs)
      if (s.app->parsed()) return s.run();
  } catch (const CliError& e) {
    std::fprintf(stderr, "ebgeom: error: %s\n", e.what());
    return e.code;
  } catch (const ebgeom::Exception& e) {
    std::fprintf(stderr, "ebgeom: error: %s\n", e.what());
    return exit_failure;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "ebgeom: error: out of memory\n");
    return exit_resource;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ebgeom: error: %s\n", e.what());
    return exit_failure;
  }
  return exit_ok;
}
